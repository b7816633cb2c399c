// --max-memory: a job estimated to need more than the limit is refused before it starts,
// with one line naming both sizes and no output; one under it runs (the estimate is
// checked against the measured peak, which it must not undershoot by much).
#include "support/cli.h"

#include "glint/bake/samples.h"
#include "glint/mesh/mesh.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::oneLine;
using glint::testing::runGlint;

namespace {
constexpr auto q = glint::testing::shellQuote;  // a path as one shell word
}  // namespace

TEST(MaxMemory, BakeTooBigForTheLimitIsRefusedBeforeItStarts) {
  const fs::path d = glint::testing::freshDir("max-memory", "bake");
  bake::writeObj(makeTorus(1.0f, 0.35f, 24, 12), d / "low.obj");
  bake::writeObj(bake::makeStuddedTorus({.segments = 128, .sides = 64}), d / "high.obj");
  const std::string inputs = q(d / "low.obj") + " " + q(d / "high.obj") + " --max-front 0.06 --max-rear 0.06 -q";
  const auto refused = runGlint("bake " + inputs + " --size 16384x16384 --max-memory 2G -o " + q(d / "big.png"));
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_TRUE(oneLine(refused.output)) << refused.output;
  EXPECT_NE(refused.output.find("more than --max-memory 2G (2048 MiB)"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(d / "big.png"));

  const auto ran = runGlint("bake " + inputs + " --size 1024x1024 --max-memory 1G -o " + q(d / "small.png") + " --json " +
                            q(d / "report.json"));
  ASSERT_EQ(ran.status, 0) << ran.output;
  const auto report = nlohmann::json::parse(std::ifstream(d / "report.json"));
  const double estimate = report["memory_estimate_mib"], peak = report["peak_memory_mib"];
  EXPECT_GT(estimate, 0.8 * peak) << "the estimate must not undershoot the measured peak";
  EXPECT_LT(estimate, 4.0 * peak) << "nor refuse jobs for nothing";

  const auto bad = runGlint("bake " + inputs + " --size 64x64 --max-memory lots -o " + q(d / "x.png"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_TRUE(oneLine(bad.output)) << bad.output;
}

TEST(MaxMemory, CutTooBigForTheLimitIsRefused) {
  const fs::path d = glint::testing::freshDir("max-memory", "cut");
  Mesh scene = makeGrid(64, 64, 4.0f);
  scene.append(makeTorus(0.5f, 0.2f, 32, 16));
  bake::writeObj(scene, d / "scene.obj");
  // 9.2k triangles, one light: estimated 58 MiB on two threads (more on more), measured 25.
  const auto refused = runGlint("cut " + q(d / "scene.obj") + " --light 0,4,0 --max-memory 40M -q -o " + q(d / "out.ply"));
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("more than --max-memory 40M (40 MiB)"), std::string::npos) << refused.output;
  EXPECT_TRUE(oneLine(refused.output)) << refused.output;
  EXPECT_FALSE(fs::exists(d / "out.ply"));
  const auto ran = runGlint("cut " + q(d / "scene.obj") + " --light 0,4,0 --max-memory 2G -q -o " + q(d / "out.ply"));
  EXPECT_EQ(ran.status, 0) << ran.output;
}
