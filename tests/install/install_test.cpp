// Installed use, as another project sees it: `cmake --install` into a fresh prefix, a
// consumer project (tests/install/consumer: find_package(glint) + glint::scenes) built
// against that prefix only, run to render basics/triangle/color, and the picture checked
// against the lecture's arithmetic and the reference image. The prefix is not the one
// this build was configured for, so the test also covers a moved install: the consumer
// and the installed glint command must find the OpenImageIO module (and glint post the
// FFmpeg module) inside the prefix.
//
// Each test works in its own test-output/install/<test> folder (ctest runs them in
// parallel processes); nothing is written elsewhere except the install manifest that
// `cmake --install` keeps in the build folder.
#include "support/cli.h"

#include "glint/core/file.h"
#include "glint/core/math.h"
#include "glint/image/image.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::CliRun;
using glint::testing::freshDir;
using glint::testing::oneLine;
using glint::testing::runGlint;

namespace {
std::string quote(const fs::path& path) { return "'" + path.string() + "'"; }

// Runs a shell command; its exit status and stdout + stderr.
CliRun run(const std::string& command) {
  CliRun r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (pipe && fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int raw = pipe ? pclose(pipe) : -1;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

// The dynamic loader's log (LD_DEBUG=files) names every object a run opened.
bool opened(const std::string& loaderLog, const fs::path& object) {
  return loaderLog.find("file=" + object.string() + " ") != std::string::npos;
}

// Environment for a run whose loader log goes to files <base>.<pid>, not into its output.
std::string logLoading(const fs::path& base) { return "LD_DEBUG=files LD_DEBUG_OUTPUT=" + base.string(); }

// Every <base>.<pid> file that logLoading(base) produced, concatenated.
std::string loaderLog(const fs::path& base) {
  std::string log;
  for (const auto& entry : fs::directory_iterator(base.parent_path())) {
    if (entry.path().filename().string().starts_with(base.filename().string() + ".")) log += readTextFile(entry.path());
  }
  return log;
}

std::string moduleName() { return "libglint_oiio.so"; }

double area(vec2 a, vec2 b, vec2 c) { return 0.5 * double((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y)); }
}  // namespace

TEST(Install, AConsumerProjectBuildsAgainstTheInstalledTreeAndRendersTheTriangle) {
  const fs::path work = freshDir("install", "consumer");
  const fs::path prefix = work / "prefix";

  // 1. Install this build into the fresh prefix.
  const auto install = run(fmt::format("{} --install {} --prefix {}", quote(GLINT_CMAKE_COMMAND),
                                       quote(GLINT_BINARY_DIR), quote(prefix)));
  ASSERT_EQ(install.status, 0) << install.output;
  for (const fs::path& relative : {
           fs::path(GLINT_INSTALL_BINDIR) / "glint",
           fs::path(GLINT_INSTALL_INCLUDEDIR) / "glint/core/error.h",
           fs::path(GLINT_INSTALL_INCLUDEDIR) / "glint/scenes/runner.h",
           fs::path(GLINT_INSTALL_LIBDIR) / "libglint_core.a",
           fs::path(GLINT_INSTALL_LIBDIR) / "libglint_scenes.a",
           fs::path(GLINT_INSTALL_MODULE_DIR) / moduleName(),
           fs::path(GLINT_INSTALL_MODULE_DIR) / "libglint_ffmpeg.so",
           fs::path(GLINT_INSTALL_CMAKE_DIR) / "glintConfig.cmake",
           fs::path(GLINT_INSTALL_CMAKE_DIR) / "glintConfigVersion.cmake",
           fs::path(GLINT_INSTALL_CMAKE_DIR) / "glint-scenes-targets.cmake",
       }) {
    EXPECT_TRUE(fs::is_regular_file(prefix / relative)) << relative << " is not installed";
  }
  // Data is installed when scripts/setup fetched it into this build's data directory.
  for (const char* file : {"env/courtyard.exr", "bunny/bunny.ply"}) {
    if (fs::exists(fs::path(GLINT_DATA_DIR) / file)) {
      EXPECT_TRUE(fs::is_regular_file(prefix / GLINT_INSTALL_DATA_DIR / file)) << file << " is not installed";
    }
  }
  // Only public headers: private ones (src/**) stay out of the installed tree.
  for (const auto& entry : fs::recursive_directory_iterator(prefix / GLINT_INSTALL_INCLUDEDIR)) {
    EXPECT_NE(entry.path().filename(), "oiio_module.h");
  }

  // 2. Configure and build the consumer against the prefix, with this build's tools.
  const fs::path build = work / "build";
  const std::string launcher = GLINT_CXX_COMPILER_LAUNCHER;
  const auto configure = run(fmt::format(
      "{} -S {} -B {} -G {} -DCMAKE_MAKE_PROGRAM={} -DCMAKE_CXX_COMPILER={} {} -DCMAKE_BUILD_TYPE={} "
      "-DCMAKE_PREFIX_PATH={}",
      quote(GLINT_CMAKE_COMMAND), quote(GLINT_CONSUMER_DIR), quote(build), quote(GLINT_CMAKE_GENERATOR),
      quote(GLINT_CMAKE_MAKE_PROGRAM), quote(GLINT_CXX_COMPILER),
      launcher.empty() ? "" : "-DCMAKE_CXX_COMPILER_LAUNCHER=" + quote(launcher), quote(GLINT_BUILD_TYPE),
      quote(prefix)));
  ASSERT_EQ(configure.status, 0) << configure.output;
  // The package came from the prefix, not from this build tree or a system install.
  const std::string cache = readTextFile(build / "CMakeCache.txt");
  EXPECT_NE(cache.find("glint_DIR:PATH=" + (prefix / GLINT_INSTALL_CMAKE_DIR).string() + "\n"), std::string::npos)
      << "find_package(glint) did not use the prefix";
  const auto compile = run(fmt::format("{} --build {}", quote(GLINT_CMAKE_COMMAND), quote(build)));
  ASSERT_EQ(compile.status, 0) << compile.output;

  // 3. Render. The OpenImageIO module must come from the prefix (the consumer's RUNPATH
  //    from glint::image), not from this build tree, which is still there. (TGA: PNG is
  //    written through libspng, without the module.)
  const fs::path png = work / "triangle.tga";
  const auto render = run(fmt::format("{} {} basics/triangle/color {}", logLoading(work / "consumer-loader"),
                                      quote(build / "render_scene"), quote(png)));
  ASSERT_EQ(render.status, 0) << render.output;
  const std::string consumerLog = loaderLog(work / "consumer-loader");
  EXPECT_TRUE(opened(consumerLog, prefix / GLINT_INSTALL_MODULE_DIR / moduleName()))
      << "the image I/O module was not loaded from the prefix";
  EXPECT_FALSE(opened(consumerLog, fs::path(GLINT_BINARY_DIR) / "src/image" / moduleName()));

  // 4. The picture: the lecture's triangle (tests/scenes/basics_test.cpp has the same
  //    arithmetic), centre pixel = barycentric blend of the vertex colours, and the
  //    reference image with the golden tests' tolerance (tests/scenes/golden_test.cpp).
  const Image img = loadImage(png);
  ASSERT_EQ(img.width(), 500);
  ASSERT_EQ(img.height(), 500);
  const vec2 L{50, 450}, M{450, 450}, N{250, 50}, P{250.5f, 250.5f};  // window coordinates
  const double total = area(L, M, N);
  const vec3 expected{float(area(P, M, N) / total), float(area(L, P, N) / total), float(area(L, M, P) / total)};
  for (int c = 0; c < 3; ++c) {
    // 8-bit output: half a code of rounding, one more for fixed-point interpolation.
    EXPECT_NEAR(img.at(250, 500 - 1 - 250, c), expected[c], 1.5 / 255.0) << "channel " << c;
  }
  const Image golden = loadImage(fs::path(GLINT_GOLDEN_DIR) / "basics/triangle/color.png");
  const auto diff = compareImages(golden, img);
  EXPECT_LE(diff.meanAbs, 0.5 / 255.0);
  EXPECT_LE(double(diff.differingPixels) / double(golden.pixelCount()), 0.002);

  // 5. The installed glint command, moved with its prefix, finds its own module too
  //    (RUNPATH $ORIGIN/../lib/glint).
  const fs::path depth = work / "depth.png";
  const auto command = run(fmt::format("{} {} render basics/triangle/depth --size 64x48 -o {}",
                                       logLoading(work / "glint-loader"), quote(prefix / GLINT_INSTALL_BINDIR / "glint"),
                                       quote(depth)));
  ASSERT_EQ(command.status, 0) << command.output;
  EXPECT_TRUE(opened(loaderLog(work / "glint-loader"), prefix / GLINT_INSTALL_MODULE_DIR / moduleName()))
      << "the installed glint did not load the module from its prefix";
  EXPECT_EQ(loadImage(depth).width(), 64);

  // 6. glint post through the installed FFmpeg module, found the same way (core/locations.h).
  const fs::path video = work / "bars.mkv";
  const auto post = run(fmt::format("{} {} -q post --input lavfi:testsrc2=size=64x48:rate=10:duration=0.5 -o {} "
                                    "--codec ffv1 -e sepia", logLoading(work / "post-loader"),
                                    quote(prefix / GLINT_INSTALL_BINDIR / "glint"), quote(video)));
  ASSERT_EQ(post.status, 0) << post.output;
  EXPECT_TRUE(opened(loaderLog(work / "post-loader"), prefix / GLINT_INSTALL_MODULE_DIR / "libglint_ffmpeg.so"))
      << "the installed glint did not load the video module from its prefix";
  EXPECT_TRUE(fs::is_regular_file(video));

  // 7. A tool's job through the library alone: the consumer's cut_scene (glint::cut) and
  //    the installed `glint cut` on the same scene give the same bytes and the same report
  //    fields (timings aside), and refuse the same bad output with the same exit code.
  const fs::path scene = work / "table.obj";
  writeTextAtomically(scene,
                "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n"           // the floor, y = 0
                "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"  // a table top above it
                "f 1 3 2\nf 1 4 3\nf 5 7 6\nf 5 8 7\n");
  const auto cutWith = [&](const std::string& program, const std::string& name) {
    return run(fmt::format("{} {} -o {} --light 0,3,0,key --json {}", program, quote(scene),
                           quote(work / (name + ".ply")), quote(work / (name + ".json"))));
  };
  const auto byCommand = cutWith(quote(prefix / GLINT_INSTALL_BINDIR / "glint") + " -q cut", "command");
  ASSERT_EQ(byCommand.status, 0) << byCommand.output;
  const auto byLibrary = cutWith(quote(build / "cut_scene"), "library");
  ASSERT_EQ(byLibrary.status, 0) << byLibrary.output;
  EXPECT_EQ(readTextFile(work / "command.ply"), readTextFile(work / "library.ply"));
  const auto commandReport = nlohmann::json::parse(readTextFile(work / "command.json"));
  const auto libraryReport = nlohmann::json::parse(readTextFile(work / "library.json"));
  EXPECT_EQ(libraryReport.at("output_polygons").get<int>(), commandReport.at("output_polygons").get<int>());
  EXPECT_GT(libraryReport.at("output_polygons").get<int>(), 4);  // the table's shadow is cut into the floor
  for (const char* key : {"input_triangles", "output_triangles", "output_vertices", "per_light", "lights", "cuts"}) {
    EXPECT_EQ(libraryReport.at(key), commandReport.at(key)) << key;
  }
  const auto badCommand = run(fmt::format("{} -q cut {} -o {} --light 0,3,0", quote(prefix / GLINT_INSTALL_BINDIR / "glint"),
                                          quote(scene), quote(work / "bad.xyz")));
  const auto badLibrary = run(fmt::format("{} {} -o {} --light 0,3,0", quote(build / "cut_scene"), quote(scene),
                                          quote(work / "bad.xyz")));
  EXPECT_EQ(badLibrary.status, badCommand.status);
  EXPECT_EQ(badLibrary.status, 2) << badLibrary.output;

  // 8. A batch of bakes through the library alone: the consumer's bake_batch (glint::bake)
  //    and the installed `glint bake --batch` give the same maps and the same report fields.
  writeTextAtomically(work / "low.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                        "vn 0 1 0\nf 1/1/1 3/3/1 2/2/1\nf 1/1/1 4/4/1 3/3/1\n");
  writeTextAtomically(work / "high.obj", "v -1 0 -1\nv 1 0.2 -1\nv 1 0 1\nv -1 0.2 1\nvn 0 1 0\n"
                                         "f 1//1 3//1 2//1\nf 1//1 4//1 3//1\n");
  const auto batchFor = [&](const std::string& name) {
    writeTextAtomically(work / (name + ".json"),
                        fmt::format(R"({{"defaults": {{"size": "32x32", "padding": 2}}, "bakes": [
                                      {{"low": "low.obj", "high": "high.obj", "output": "{0}_n.png", "ao": "{0}_ao.png"}},
                                      {{"low": "low.obj", "high": "high.obj", "output": "{0}_m.png", "directx": true}}]}})",
                                    name));
    return work / (name + ".json");
  };
  const auto bakeByCommand = run(fmt::format("{} -q bake --batch {} --samples 4 --json {}", quote(prefix / GLINT_INSTALL_BINDIR / "glint"),
                                             quote(batchFor("cmd")), quote(work / "cmd-report.json")));
  ASSERT_EQ(bakeByCommand.status, 0) << bakeByCommand.output;
  const auto bakeByLibrary = run(fmt::format("{} {} --samples 4 --json {}", quote(build / "bake_batch"),
                                             quote(batchFor("lib")), quote(work / "lib-report.json")));
  ASSERT_EQ(bakeByLibrary.status, 0) << bakeByLibrary.output;
  for (const char* map : {"_n.png", "_ao.png", "_m.png"})
    EXPECT_TRUE(readTextFile(work / (std::string("cmd") + map)) == readTextFile(work / (std::string("lib") + map))) << map;
  const auto cmdBatch = nlohmann::json::parse(readTextFile(work / "cmd-report.json"));
  const auto libBatch = nlohmann::json::parse(readTextFile(work / "lib-report.json"));
  ASSERT_EQ(libBatch.at("jobs").size(), 2u);
  for (std::size_t j = 0; j < 2; ++j)
    for (const char* key : {"status", "samples", "width", "height", "covered_texels", "rays", "hit_ratio"})
      EXPECT_EQ(libBatch["jobs"][j].at(key), cmdBatch["jobs"][j].at(key)) << "job " << j << " " << key;

#ifdef GLINT_PYTHON_INSTALL_DIR
  // 9. `import glint` from the prefix (issue 36): the installed Python package, its modules
  //    found relative to it in the moved prefix (glint/_locations.py), the same maps as the
  //    installed command's, and the Blender add-on's zip installed beside the data.
  const fs::path site = prefix / GLINT_PYTHON_INSTALL_DIR;
  EXPECT_TRUE(fs::is_regular_file(site / "glint" / "__init__.pyi"));
  EXPECT_TRUE(fs::is_regular_file(prefix / GLINT_INSTALL_DATA_DIR / "blender" / "glint_bake.zip"));
  writeTextAtomically(work / "use_glint.py", fmt::format(R"(import glint, sys
print(glint.__file__)
result = glint.bake("{0}/low.obj", "{0}/high.obj", size=32, maps=("normal", "ao"), padding=2, samples=4)
glint.write_image("{0}/py_n.png", result["normal"])
glint.write_image("{0}/py_ao.png", result["ao"])
glint.write_image("{0}/py_n.tga", result["normal"])  # TGA: through the image I/O module
)", work.string()));
  const auto python = run(fmt::format("cd / && PYTHONPATH={} {} {} {}", quote(site), logLoading(work / "python-loader"),
                                      GLINT_PYTHON_EXECUTABLE, quote(work / "use_glint.py")));
  ASSERT_EQ(python.status, 0) << python.output;
  EXPECT_NE(python.output.find((site / "glint" / "__init__.py").string()), std::string::npos)
      << "glint was not imported from the prefix: " << python.output;
  EXPECT_TRUE(readTextFile(work / "py_n.png") == readTextFile(work / "cmd_n.png")) << "the module's normal map";
  EXPECT_TRUE(readTextFile(work / "py_ao.png") == readTextFile(work / "cmd_ao.png")) << "the module's AO map";
  EXPECT_TRUE(opened(loaderLog(work / "python-loader"), prefix / GLINT_INSTALL_MODULE_DIR / moduleName()))
      << "the installed Python module did not load the image I/O module from its prefix";
#endif
}

// GLINT_OIIO_MODULE names the module explicitly: used when set, and the only candidate,
// so a wrong value is reported rather than silently replaced by another module. (TGA
// output needs the module; PNG is written through libspng without it.)
TEST(Install, TheImageIoModuleCanBeNamedAndAWrongNameIsAOneLineError) {
  const fs::path work = freshDir("install", "module-override");
  const fs::path module = work / moduleName();
  fs::copy_file(fs::path(GLINT_BINARY_DIR) / "src/image" / moduleName(), module);
  auto r = runGlint("render basics/triangle/color --size 32x32 -o " + quote(work / "t.tga"),
                    logLoading(work / "loader") + " GLINT_OIIO_MODULE=" + quote(module));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(opened(loaderLog(work / "loader"), module)) << "GLINT_OIIO_MODULE was not used";

  const fs::path missing = work / "nowhere" / moduleName();
  r = runGlint("render basics/triangle/color --size 32x32 -o " + quote(work / "u.tga"),
               "GLINT_OIIO_MODULE=" + quote(missing));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("GLINT_OIIO_MODULE=" + missing.string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(work / "u.tga"));
}

// Data that is not where glint looks is an input error that says where it looked.
TEST(Install, MissingDataIsAOneLineErrorNamingWhereGlintLooked) {
  const fs::path empty = freshDir("install", "no-data");
  const auto r = runGlint("render env/cube/front -o " + quote(empty / "env.png"), "GLINT_DATA_DIR=" + quote(empty));
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("env/courtyard.exr"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("GLINT_DATA_DIR=" + empty.string()), std::string::npos) << r.output;
}
