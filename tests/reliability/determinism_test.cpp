// Determinism across threads: `glint bake` and `glint cut` write byte-identical files at
// 1, 2 and 8 threads (--threads; the machine may have fewer cores: more threads than
// cores still split the work differently, which is what could change a result).
#include "support/cli.h"

#include "glint/bake/samples.h"
#include "glint/mesh/machine_room.h"
#include "glint/mesh/mesh.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::runGlint;

namespace {

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

constexpr int kThreads[] = {1, 2, 8};

}  // namespace

TEST(Determinism, BakeIsByteIdenticalAt1And2And8Threads) {
  const fs::path d = glint::testing::freshDir("determinism", "bake");
  bake::writeObj(makeTorus(1.0f, 0.35f, 24, 12), d / "low.obj");
  bake::writeObj(bake::makeStuddedTorus({.segments = 192, .sides = 96}), d / "high.obj");
  std::string first;
  for (int threads : kThreads) {
    const fs::path out = d / fmt::format("map-{}.png", threads);
    const auto run = runGlint(fmt::format("bake {} {} --size 384x384 --samples 4 --max-front 0.06 --max-rear 0.06 -q --threads {} -o {}",
                                          q(d / "low.obj"), q(d / "high.obj"), threads, q(out)));
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string bytes = readBytes(out);
    ASSERT_GT(bytes.size(), 1000u);
    if (first.empty()) first = bytes;
    EXPECT_TRUE(bytes == first) << threads << " threads: the map differs from 1 thread's";
  }
}

TEST(Determinism, CutIsByteIdenticalAt1And2And8Threads) {
  const fs::path d = glint::testing::freshDir("determinism", "cut");
  const MachineRoomOptions room{.modules = 4};
  bake::writeObj(makeMachineRoom(room), d / "room.obj");
  const auto lights = machineRoomLights(room);
  std::string firstGlb, firstPly;
  for (int threads : kThreads) {
    const fs::path glb = d / fmt::format("cut-{}.glb", threads), ply = d / fmt::format("cut-{}.ply", threads);
    const auto run = runGlint(fmt::format("cut {} --light {},{},{} --light {},{},{} -q --threads {} -o {} -o {}", q(d / "room.obj"),
                                          lights[0].x, lights[0].y, lights[0].z, lights[1].x, lights[1].y, lights[1].z,
                                          threads, q(glb), q(ply)));
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string g = readBytes(glb), p = readBytes(ply);
    ASSERT_GT(g.size(), 1000u);
    if (firstGlb.empty()) firstGlb = g, firstPly = p;
    EXPECT_TRUE(g == firstGlb) << threads << " threads: the glTF differs from 1 thread's";
    EXPECT_TRUE(p == firstPly) << threads << " threads: the PLY differs from 1 thread's";
  }
}
