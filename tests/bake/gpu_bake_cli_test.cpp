// `glint bake --device` as a user runs it (issue 48): the option in the help and the report,
// UDIM tiles (each tile its own bake and upload) and the bunny card of docs/bake.md with every
// map, the GPU's files equal to the CPU's (llvmpipe here). The library-level equality tests
// are gpu_bake_test.cpp, which scripts/gpu-check also runs on a GPU.
#include "glint/bake/samples.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include "support/cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

using namespace glint;
namespace fs = std::filesystem;

namespace {

/// Two image files within `step` (of 1: 8-bit steps are 1/255) on all but `share` of the pixels.
void expectSameFiles(const fs::path& a, const fs::path& b, double step = 1.0 / 255.0 + 1e-6, double share = 0.001) {
  const Image x = loadImage(a).converted(PixelType::F32), y = loadImage(b).converted(PixelType::F32);
  ASSERT_EQ(x.width(), y.width()) << a;
  ASSERT_EQ(x.height(), y.height()) << a;
  ASSERT_EQ(x.channels(), y.channels()) << a;
  std::size_t beyond = 0;
  for (int row = 0; row < x.height(); ++row)
    for (int col = 0; col < x.width(); ++col) {
      bool differs = false;
      for (int c = 0; c < x.channels(); ++c) differs = differs || std::fabs(x.at(col, row, c) - y.at(col, row, c)) > step;
      beyond += differs ? 1 : 0;
    }
  const double part = double(beyond) / double(std::size_t(x.width()) * std::size_t(x.height()));
  std::printf("[figure] %s: %.4f %% of the pixels beyond %.3g\n", b.filename().c_str(), 100.0 * part, step);
  EXPECT_LE(part, share) << a << " and " << b;
}

}  // namespace

// UDIM tiles (each tile its own bake, its own upload) and the bunny card of docs/bake.md
// (scripts/bunny-painted.js: the scan in three materials with vertex colours, onto a card
// through a cage) with every map, through the command: the GPU's files are the CPU's.
TEST(GpuBake, UdimTilesAndTheBunnyCardBakeTheCpusFiles) {
  const fs::path d = glint::testing::freshDir("gpu_bake", "files");
  Mesh low = makeUvSphere(1.0f, 16, 8), high = makeUvSphere(1.0f, 64, 32);
  Mesh lowB = low, highB = makeUvSphere(1.0f, 8, 4);
  for (vec3& p : lowB.positions) p.x += 3.0f;
  for (vec3& p : highB.positions) p.x += 3.0f;
  for (vec2& uv : lowB.uvs) uv.x += 1.0f;  // tile 1002
  low.append(lowB);
  high.append(highB);
  bake::writeObj(low, d / "low.obj");
  bake::writeObj(high, d / "high.obj");
  for (const char* device : {"cpu", "gpu"}) {
    const auto r = glint::testing::runGlint(
        "bake " + (d / "low.obj").string() + " " + (d / "high.obj").string() + " -o '" + (d / device).string() +
        "-n.<UDIM>.png' --ao '" + (d / device).string() + "-ao.<UDIM>.png' --size 64x64 --samples 4 --max-front 0.2 "
        "--max-rear 0.2 --ao-distance 0.5 -q --device " + device);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  for (const char* file : {"n.1001.png", "n.1002.png", "ao.1001.png", "ao.1002.png"})
    expectSameFiles(d / (std::string("cpu-") + file), d / (std::string("gpu-") + file));

  const fs::path bunny = fs::path(GLINT_SOURCE_DIR) / "data/bunny/bunny.ply";
  ASSERT_TRUE(fs::exists(bunny)) << "no " << bunny << ": scripts/setup --test fetches it";
  const auto painted = glint::testing::runShell("node " + (fs::path(GLINT_SOURCE_DIR) / "scripts/bunny-painted.js").string() +
                                                " " + bunny.string() + " " + d.string());
  ASSERT_EQ(painted.status, 0) << painted.output;
  const char* maps[][2] = {{"-o", "normal.png"},        {"--ao", "ao.png"},           {"--bent-normal", "bent.png"},
                           {"--curvature", "curv.png"}, {"--thickness", "thick.png"},   {"--height", "height.exr"},
                           {"--position", "pos.exr"},   {"--material-id", "mat.png"}, {"--vertex-color", "colour.png"},
                           {"--opacity", "opacity.png"}, {"--miss-mask", "miss.png"}};
  for (const char* device : {"cpu", "gpu"}) {
    std::string command = "bake " + (d / "card.obj").string() + " " + (d / "bunny_painted.obj").string() + " --cage " +
                          (d / "card_cage.obj").string() + " --max-rear 4.5 --size 96x96 --samples 4 --ao-samples 16 "
                          "--ao-distance 3 --thickness-distance 3 --curvature-radius 3% -q --device " + device;
    for (const auto& [option, file] : maps) command += std::string(" ") + option + " " + (d / device).string() + "-" + file;
    const auto r = glint::testing::runGlint(command);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  for (const auto& [option, file] : maps) {
    const bool scene = std::string(file).ends_with(".exr");  // height and position, in scene units (the bunny: ~10)
    expectSameFiles(d / (std::string("cpu-") + file), d / (std::string("gpu-") + file), scene ? 1e-4 : 1.0 / 255.0 + 1e-6);
  }
}

// The command: --device in its help and report, a bad value a usage error.
TEST(GpuBake, TheCommandTakesDevice) {
  const fs::path dir = glint::testing::freshDir("gpu_bake", "command");
  bake::writeObj(makeTorus(1.0f, 0.35f, 24, 8), dir / "low.obj");
  bake::writeObj(makeTorus(1.0f, 0.36f, 48, 24), dir / "high.obj");
  const std::string pair = (dir / "low.obj").string() + " " + (dir / "high.obj").string();
  const auto gpu = glint::testing::runGlint("bake " + pair + " -o " + (dir / "n.png").string() + " --ao " +
                                            (dir / "ao.png").string() + " --size 64x64 --device gpu -q --json " +
                                            (dir / "r.json").string());
  ASSERT_EQ(gpu.status, 0) << gpu.output;
  nlohmann::json report;
  std::ifstream(dir / "r.json") >> report;
  EXPECT_EQ(report["device"], "gpu");
  EXPECT_EQ(report["device_reason"].get<std::string>().rfind("--device gpu", 0), 0u) << report["device_reason"];  // (+ the memory, where the driver says)
  EXPECT_GT(report["gpu_dispatches"].get<int>(), 0);
  EXPECT_TRUE(report.contains("gpu_renderer"));
  const auto cpu = glint::testing::runGlint("bake " + pair + " -o " + (dir / "c.png").string() + " --ao " +
                                            (dir / "cao.png").string() + " --size 64x64 --device cpu -q");
  ASSERT_EQ(cpu.status, 0) << cpu.output;
  EXPECT_EQ(glint::testing::readBytes(dir / "n.png"), glint::testing::readBytes(dir / "c.png"))
      << "a 64² normal map of two tori: the same bytes either way";
  const auto bad = glint::testing::runGlint("bake " + pair + " -o " + (dir / "x.png").string() + " --device tpu");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--device"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "x.png"));
  const auto help = glint::testing::runGlint("bake --help");
  EXPECT_NE(help.output.find("--device"), std::string::npos);
}
