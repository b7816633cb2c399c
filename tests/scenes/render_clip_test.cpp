// `glint render SCENE -o clip.mkv --frames A:B` as a user runs it: a scene's animation to a
// video (scenes/clip.h). Frame i is the picture `--time i/fps` gives, parts join with
// `glint post --concat` into the bytes of one run, H.264 has its frames and rate, usage
// errors are one line with exit 2, and Ctrl-C leaves an existing file as it was (exit 130).
#include "glint/image/image.h"
#include "glint/video/source.h"

#include "support/cli.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::fileCount;
using glint::testing::oneLine;
using glint::testing::readBytes;
using glint::testing::runGlint;
using glint::testing::runShell;

namespace {
fs::path dir(const char* name) { return glint::testing::freshDir("render-clip", name); }

// A cheap animated scene: a textured cube spinning with the time.
const std::string kScene = "rtt/texture/fbo";

std::vector<video::Frame> readAll(const fs::path& path) {
  video::Source source = video::Source::open(path.string());
  std::vector<video::Frame> frames;
  video::Frame f;
  while (source.read(f)) frames.push_back(f);
  return frames;
}

bool haveFfprobe() { return std::system("command -v ffprobe >/dev/null 2>&1") == 0; }

/// ffprobe's count of decoded frames and the stream's r_frame_rate, "12,24/1".
std::string probe(const fs::path& video) {
  auto r = runShell("ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames,r_frame_rate "
                    "-of csv=p=0 " + video.string());
  while (!r.output.empty() && (r.output.back() == '\n' || r.output.back() == ' ')) r.output.pop_back();
  return r.output;
}
}  // namespace

TEST(RenderClip, PartsJoinIntoTheWholeAndFrameIIsTimeIOverFps) {
  const fs::path d = dir("ffv1");
  const std::string common = " --codec ffv1 --size 64x48 --fps 10 -q";
  const auto render = [&](const char* frames, const fs::path& out) {
    const auto r = runGlint("render " + kScene + " -o " + out.string() + " --frames " + frames + common);
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(r.output.empty()) << "-q: silent, got: " << r.output;
  };
  render("0:6", d / "whole.mkv");
  render("0:3", d / "a.mkv");
  render("3:6", d / "b.mkv");
  const auto r = runGlint("-q post --concat " + (d / "a.mkv").string() + " " + (d / "b.mkv").string() + " -o " +
                          (d / "joined.mkv").string());
  ASSERT_EQ(r.status, 0) << r.output;
  // FFV1 parts (every frame a keyframe, timestamps i in 1/fps, bit-exact muxing) join into
  // the very file one run writes.
  const std::string whole = readBytes(d / "whole.mkv");
  ASSERT_FALSE(whole.empty());
  EXPECT_TRUE(whole == readBytes(d / "joined.mkv")) << "the joined parts are the whole, byte for byte";

  const auto frames = readAll(d / "whole.mkv"), joined = readAll(d / "joined.mkv");
  ASSERT_EQ(frames.size(), 6u);
  ASSERT_EQ(joined.size(), 6u);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].index, std::int64_t(i));
    EXPECT_NEAR(frames[i].seconds, double(i) / 10.0, 1e-6);
    EXPECT_EQ(joined[i].image, frames[i].image) << "frame " << i;
    if (i > 0) {
      EXPECT_NE(frames[i].image, frames[i - 1].image) << "frame " << i << ": the animation does not move";
    }
  }
  // The picture at time i / fps, as an image render gives it (FFV1 is lossless RGB): the
  // first and last frames and both sides of the split.
  for (const std::size_t i : {0u, 2u, 3u, 5u}) {
    const fs::path png = d / fmt::format("t{}.png", i);
    const auto still = runGlint(fmt::format("-q render {} -o {} --size 64x48 --time {}", kScene, png.string(), double(i) / 10.0));
    ASSERT_EQ(still.status, 0) << still.output;
    EXPECT_EQ(loadImage(png).withChannels(3), frames[i].image.withChannels(3)) << "frame " << i;
  }
}

TEST(RenderClip, H264HasEveryFrameAtItsRateAndItsPartsJoin) {
  if (!haveFfprobe()) GTEST_SKIP() << "ffprobe not installed (scripts/setup --test)";
  const fs::path d = dir("h264");
  const std::string common = " --size 64x48 --fps 24 --preset ultrafast -q";
  ASSERT_EQ(runGlint("render " + kScene + " -o " + (d / "clip.mp4").string() + " --frames 0:12" + common).status, 0);
  EXPECT_EQ(probe(d / "clip.mp4"), "24/1,12");
  ASSERT_EQ(runGlint("render " + kScene + " -o " + (d / "a.mp4").string() + " --frames 0:5" + common).status, 0);
  ASSERT_EQ(runGlint("render " + kScene + " -o " + (d / "b.mp4").string() + " --frames 5:12" + common).status, 0);
  const auto r = runGlint("-q post --concat " + (d / "a.mp4").string() + " " + (d / "b.mp4").string() + " -o " +
                          (d / "joined.mp4").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(probe(d / "joined.mp4"), "24/1,12");
  const auto frames = readAll(d / "joined.mp4");
  ASSERT_EQ(frames.size(), 12u);
  for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_NEAR(frames[i].seconds, double(i) / 24.0, 1e-3);
}

TEST(RenderClip, UsageErrorsAreOneLineAndWriteNothing) {
  const fs::path d = dir("usage");
  const std::string mp4 = " -o " + (d / "x.mp4").string(), mkv = " -o " + (d / "x.mkv").string();
  struct Case {
    std::string args;
    int status;
    std::string says;
  };
  const std::vector<Case> cases = {
      {mp4, 2, "needs --frames"},
      {mp4 + " --frames 0:3 --time 1", 2, "--time is for an image"},
      {mkv + " --frames 5:5", 2, "selects no frame"},
      {mkv + " --frames 9:3", 2, "selects no frame"},
      {mkv + " --frames 3:", 2, "needs an END"},
      {mkv + " --frames 0-3", 2, "FIRST:END"},
      {mkv + " --frames 0:3 --codec vp9", 2, "unknown codec 'vp9'"},
      {mp4 + " --frames 0:3 --preset warp", 2, "unknown --preset 'warp'"},
      {mp4 + " --frames 0:3 --crf 99", 2, "--crf must be 0..51"},
      {mp4 + " --frames 0:3 --fps 0", 2, "--fps must be 1..1000"},
      {mp4 + " --frames 0:3 --size 65x48", 2, "even width and height"},
      {" -o " + (d / "x.png").string() + " --frames 0:3", 2, "--frames is for a video output"},
      {" -o " + (d / "no/dir/x.mkv").string() + " --frames 0:3 --codec ffv1", 4, "cannot write"},
  };
  for (const auto& c : cases) {
    const auto r = runGlint("render " + kScene + c.args);
    EXPECT_EQ(r.status, c.status) << c.args << "\n" << r.output;
    EXPECT_TRUE(oneLine(r.output)) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
  }
  EXPECT_EQ(fileCount(d), 0u) << "no output, no temporary file";
}

TEST(RenderClip, CtrlCLeavesAnExistingFileAsItWas) {
  const fs::path d = dir("interrupt");
  const fs::path out = d / "clip.mkv";
  { std::ofstream(out) << "the previous clip"; }
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(GLINT_EXE, GLINT_EXE, "render", kScene.c_str(), "-o", out.c_str(), "--frames", "0:100000", "--codec", "ffv1",
          "--size", "256x192", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until frames are being written (the temporary file grows), then Ctrl-C.
  ASSERT_TRUE(glint::testing::waitUntilWriting(d, ".clip.tmp", 20000)) << "glint render never started writing";
  EXPECT_EQ(glint::testing::interruptAndWait(pid), 130);
  EXPECT_EQ(readBytes(out), "the previous clip") << "the existing file is untouched";
  EXPECT_EQ(fileCount(d), 1u) << "no temporary file left";
}
