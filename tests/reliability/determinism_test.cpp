// Determinism across threads: `glint bake` and `glint cut` write byte-identical files at
// 1, 2 and 8 threads (--threads; the machine may have fewer cores: more threads than
// cores still split the work differently, which is what could change a result).
#include "support/cli.h"

#include "glint/bake/samples.h"
#include "glint/pipedream/machine_room.h"
#include "glint/mesh/mesh.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::readBytes;
using glint::testing::runGlint;

namespace {

constexpr auto q = glint::testing::shellQuote;  // a path as one shell word

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

// glint post is a GPU pass chain: the same input gives the same bytes on every run (an
// image and a lossless video; H.264's encoder is deterministic too at a fixed thread count).
TEST(Determinism, PostIsByteIdenticalRunToRun) {
  const fs::path d = glint::testing::freshDir("determinism", "post");
  ASSERT_EQ(runGlint("post --input lavfi:testsrc2=size=320x240:rate=25:duration=1 --codec ffv1 -q -o " + q(d / "clip.mkv")).status, 0);
  ASSERT_EQ(runGlint("post --input lavfi:testsrc2=size=640x480 --frames 0:1 -q -o " + q(d / "photo.png")).status, 0);
  for (const char* effect : {"posterize", "lowpass", "sepia"}) {
    std::string firstImage, firstVideo;
    for (int run = 0; run < 2; ++run) {
      const fs::path image = d / fmt::format("{}-{}.png", effect, run), video = d / fmt::format("{}-{}.mkv", effect, run);
      const auto a = runGlint(fmt::format("post {} -e {} -q -o {}", q(d / "photo.png"), effect, q(image)));
      ASSERT_EQ(a.status, 0) << a.output;
      const auto b = runGlint(fmt::format("post {} -e {} --codec ffv1 -q -o {}", q(d / "clip.mkv"), effect, q(video)));
      ASSERT_EQ(b.status, 0) << b.output;
      if (run == 0) {
        firstImage = readBytes(image), firstVideo = readBytes(video);
        continue;
      }
      EXPECT_TRUE(readBytes(image) == firstImage) << effect << ": the image differs between runs";
      EXPECT_TRUE(readBytes(video) == firstVideo) << effect << ": the video differs between runs";
    }
  }
}
