// glint in parts: a glint configured without its optional parts (GLINT_BUILD_VIDEO, _CUT,
// _BENCH, _VIEWER and the tests OFF), of which only glint::render and the layers below it
// are built and installed (cmake --install --component, one per component), and a consumer
// (tests/install/render_consumer) that asks for the render component alone, builds against
// that prefix with the packages of the left-out parts hidden, and renders.
//
// What it proves: the options configure; find_package(glint COMPONENTS render) looks only
// for what glint::render links (the package's per-component lists come from the link
// graph), a left-out part is a one-line not-found message naming its option, and the prefix
// holds nothing of the left-out parts. Building only the needed targets keeps the test to
// the render libraries' compile time rather than the whole of glint.
#include "support/cli.h"

#include "glint/core/file.h"
#include "glint/image/image.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using glint::testing::freshDir;
using glint::testing::runShell;
using glint::testing::shellQuote;

namespace {
// This build's generator, compiler and launcher for another CMake project, and a build type.
std::string toolchain(const std::string& buildType) {
  const std::string launcher = GLINT_CXX_COMPILER_LAUNCHER;
  return fmt::format("-G {} -DCMAKE_MAKE_PROGRAM={} -DCMAKE_CXX_COMPILER={} {} -DCMAKE_BUILD_TYPE={}",
                     shellQuote(GLINT_CMAKE_GENERATOR), shellQuote(GLINT_CMAKE_MAKE_PROGRAM),
                     shellQuote(GLINT_CXX_COMPILER),
                     launcher.empty() ? "" : "-DCMAKE_CXX_COMPILER_LAUNCHER=" + shellQuote(launcher), shellQuote(buildType));
}
}  // namespace

TEST(Install, AConsumerOfGlintRenderAloneBuildsOnAPrefixWithoutTheOptionalParts) {
  const fs::path work = freshDir("install", "components");
  const fs::path glintBuild = work / "glint-build", prefix = work / "prefix";
  const std::string cmake = shellQuote(GLINT_CMAKE_COMMAND);

  // 1. glint without its optional parts: only the render libraries built, only their
  //    components (and the package files, in core) installed. Build type None (no -O2,
  //    no -g) compiles them in about 60% of the CPU time, a unity build (a few translation
  //    units per library) in half of that again: what is tested is the package.
  const auto configure = runShell(fmt::format(
      "{} -S {} -B {} {} -DGLINT_BUILD_VIDEO=OFF -DGLINT_BUILD_CUT=OFF -DGLINT_BUILD_BENCH=OFF "
      "-DGLINT_BUILD_VIEWER=OFF -DGLINT_BUILD_TESTS=OFF -DCMAKE_UNITY_BUILD=ON",
      cmake, shellQuote(GLINT_SOURCE_DIR), shellQuote(glintBuild), toolchain("None")));
  ASSERT_EQ(configure.status, 0) << configure.output;
  const auto build = runShell(fmt::format("{} --build {} --target glint_render", cmake, shellQuote(glintBuild)));
  ASSERT_EQ(build.status, 0) << build.output;
  for (const char* component : {"core", "image", "effects", "mesh", "pipedream", "shadows", "sim", "gl", "render"}) {
    const auto install = runShell(fmt::format("{} --install {} --prefix {} --component {}", cmake, shellQuote(glintBuild),
                                              shellQuote(prefix), component));
    ASSERT_EQ(install.status, 0) << install.output;
  }
  const fs::path lib = prefix / GLINT_INSTALL_LIBDIR, package = prefix / GLINT_INSTALL_CMAKE_DIR;
  for (const fs::path& file : {lib / "libglint_render.a", lib / "libglint_core.a", package / "glintConfig.cmake",
                               package / "glint-render-targets.cmake", prefix / GLINT_INSTALL_MODULE_DIR / "libglint_oiio.so",
                               prefix / GLINT_INSTALL_INCLUDEDIR / "glint/render/post/chain.h",
                               prefix / GLINT_INSTALL_INCLUDEDIR / "glint/post/effects.h", lib / "libglint_effects.a",
                               package / "PeerDependencies.cmake"}) {
    EXPECT_TRUE(fs::is_regular_file(file)) << file << " is not installed";
  }
  for (const fs::path& file : {lib / "libglint_scenes.a", lib / "libglint_cut.a", lib / "libglint_bench.a",
                               lib / "libglint_post.a", lib / "libglint_video.a", lib / "libglint_farm.a",
                               prefix / GLINT_INSTALL_INCLUDEDIR / "glint/post/job.h",
                               prefix / GLINT_INSTALL_MODULE_DIR / "libglint_ffmpeg.so", package / "glint-cut-targets.cmake",
                               prefix / GLINT_INSTALL_INCLUDEDIR / "glint/cut", prefix / GLINT_INSTALL_BINDIR / "glint"}) {
    EXPECT_FALSE(fs::exists(file)) << file << " is installed";
  }

  // 2. The consumer, with the CMake packages of the parts it does not use made unfindable
  //    (its CMakeLists also checks that no target of theirs exists, FFmpeg's included, and
  //    that asking for cut names GLINT_BUILD_CUT).
  const fs::path consumer = work / "consumer";
  const auto configureConsumer = runShell(fmt::format(
      "{} -S {} -B {} {} -DCMAKE_PREFIX_PATH={} -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON "
      "-DCMAKE_DISABLE_FIND_PACKAGE_CGAL=ON -DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON -DCMAKE_DISABLE_FIND_PACKAGE_glfw3=ON",
      cmake, shellQuote(GLINT_RENDER_CONSUMER_DIR), shellQuote(consumer), toolchain(GLINT_BUILD_TYPE), shellQuote(prefix)));
  ASSERT_EQ(configureConsumer.status, 0) << configureConsumer.output;
  const std::string cache = glint::readTextFile(consumer / "CMakeCache.txt");
  EXPECT_NE(cache.find("glint_DIR:PATH=" + package.string() + "\n"), std::string::npos)
      << "find_package(glint) did not use the prefix";
  const auto buildConsumer = runShell(fmt::format("{} --build {}", cmake, shellQuote(consumer)));
  ASSERT_EQ(buildConsumer.status, 0) << buildConsumer.output;

  // 3. It runs: a grey ramp through sepia on the GPU (sepia keeps red ≥ green ≥ blue).
  const fs::path png = work / "sepia.png";
  const auto run = runShell(fmt::format("{} {}", shellQuote(consumer / "render_post"), shellQuote(png)));
  ASSERT_EQ(run.status, 0) << run.output;
  const glint::Image image = glint::loadImage(png);
  ASSERT_EQ(image.width(), 64);
  ASSERT_EQ(image.height(), 16);
  const int x = 40, y = 8;
  EXPECT_GT(image.at(x, y, 0), image.at(x, y, 2) + 0.05f) << "not sepia-toned";
  EXPECT_GE(image.at(x, y, 0), image.at(x, y, 1));
  EXPECT_GE(image.at(x, y, 1), image.at(x, y, 2));
}
