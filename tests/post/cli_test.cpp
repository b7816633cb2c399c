// `glint post` as a user runs it: a lavfi test pattern through the command and back (frame
// count, timestamps, every frame against the CPU reference), images, --frames parts joined
// with --concat, Ctrl-C finishing a playable partial video, -q and --json, and bad input:
// one-line errors, the documented exit status, no file left behind.
#include "glint/image/image.h"
#include "glint/image/post.h"
#include "glint/video/source.h"

#include "post_test_util.h"
#include "support/cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::compareSteps;
using glint::testing::fileCount;
using glint::testing::oneLine;
using glint::testing::runGlint;

namespace {
fs::path dir(const char* name) { return glint::testing::freshDir("post-cli", name); }

const std::string kPattern = "lavfi:testsrc2=size=160x120:rate=24:duration=2";  // 48 frames

std::vector<video::Frame> readAll(const std::string& name) {
  video::Source source = video::Source::open(name);
  std::vector<video::Frame> frames;
  video::Frame f;
  while (source.read(f)) frames.push_back(f);
  return frames;
}

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}
}  // namespace

TEST(PostCli, LavfiPatternRoundTripMatchesTheReference) {
  const fs::path d = dir("roundtrip");
  const auto out = d / "sepia.mkv";
  const auto r = runGlint("post --input " + kPattern + " -o " + out.string() + " --codec ffv1 -e sepia -e sobel:output=dx "
                          "--json " + (d / "r.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto input = readAll(kPattern);
  const auto output = readAll(out.string());
  ASSERT_EQ(input.size(), 48u);
  ASSERT_EQ(output.size(), input.size()) << "every frame, none dropped";
  for (std::size_t i = 0; i < output.size(); ++i) {
    EXPECT_EQ(output[i].index, std::int64_t(i));
    EXPECT_NEAR(output[i].seconds, double(i) / 24.0, 1e-3) << "timestamps kept";
    // FFV1 is lossless: the file holds the GPU's 8-bit result; the reference chain rounds to
    // 8 bits between the effects as the GPU chain does.
    const Image expected = sobelReference(quantizeToU8(sepiaReference(input[i].image)), {.output = SobelOutput::SignedX});
    EXPECT_LE(compareSteps(output[i].image, expected).maxSteps, 1) << "frame " << i;
  }
  const auto report = readJson(d / "r.json");
  EXPECT_EQ(report["frames_written"], 48);
  EXPECT_EQ(report["dropped_frames"], 0);
  EXPECT_EQ(report["partial"], false);
  EXPECT_EQ(report["effects"], "sepia(i=0.2,q=0) → sobel(output=dx,scale=1)");
  EXPECT_GT(report["fps"].get<double>(), 0.0);
  EXPECT_EQ(fileCount(d), 2u) << "the video and the report, no temporary files";

  // H.264: lossy, but every frame is there at its time.
  const auto mp4 = d / "sepia.mp4";
  ASSERT_EQ(runGlint("-q post --input " + kPattern + " -o " + mp4.string() + " -e sepia --preset ultrafast").status, 0);
  const auto lossy = readAll(mp4.string());
  ASSERT_EQ(lossy.size(), 48u);
  for (std::size_t i = 0; i < lossy.size(); ++i) EXPECT_NEAR(lossy[i].seconds, double(i) / 24.0, 1e-3);
}

TEST(PostCli, ImagesAndStills) {
  const fs::path d = dir("images");
  const Image photo = glint::testing::photograph();
  saveImage(photo, d / "photo.png");
  const auto r = runGlint("-q post " + (d / "photo.png").string() + " -o " + (d / "k.png").string() +
                          " -e kuwahara --set size=4");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(r.output.empty()) << "-q: silent, got: " << r.output;
  EXPECT_LE(compareSteps(loadImage(d / "k.png"), kuwaharaReference(photo, {.size = 4}).image).maxSteps, 1);
  // A still from a video: the first frame of --frames.
  ASSERT_EQ(runGlint("-q post --input " + kPattern + " --frames 5:6 -o " + (d / "still.png").string()).status, 0);
  EXPECT_EQ(loadImage(d / "still.png"), readAll(kPattern)[5].image);
}

TEST(PostCli, FramePartsConcatenateLosslessly) {
  const fs::path d = dir("parts");
  // A source file first: --frames seeks in files.
  ASSERT_EQ(runGlint("-q post --input " + kPattern + " -o " + (d / "src.mkv").string() + " --codec ffv1").status, 0);
  const std::string common = " --codec ffv1 -e posterize -q";
  ASSERT_EQ(runGlint("post " + (d / "src.mkv").string() + " -o " + (d / "whole.mkv").string() + common).status, 0);
  ASSERT_EQ(runGlint("post " + (d / "src.mkv").string() + " --frames 0:20 -o " + (d / "a.mkv").string() + common).status, 0);
  ASSERT_EQ(runGlint("post " + (d / "src.mkv").string() + " --frames 20: -o " + (d / "b.mkv").string() + common).status, 0);
  const auto r = runGlint("-q post --concat " + (d / "a.mkv").string() + " " + (d / "b.mkv").string() + " -o " +
                          (d / "joined.mkv").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto whole = readAll((d / "whole.mkv").string()), joined = readAll((d / "joined.mkv").string());
  ASSERT_EQ(joined.size(), 48u);
  ASSERT_EQ(whole.size(), 48u);
  for (std::size_t i = 0; i < whole.size(); ++i) {
    EXPECT_NEAR(joined[i].seconds, whole[i].seconds, 1e-3);
    EXPECT_EQ(joined[i].image, whole[i].image) << "frame " << i << ": the parts are the whole, bit for bit";
  }
  // H.264 parts (no B-frames) join too: all frames, in time.
  const std::string h264 = " -e sepia -q --preset ultrafast";
  ASSERT_EQ(runGlint("post " + (d / "src.mkv").string() + " --frames 0:30 -o " + (d / "a.mp4").string() + h264).status, 0);
  ASSERT_EQ(runGlint("post " + (d / "src.mkv").string() + " --frames 30:48 -o " + (d / "b.mp4").string() + h264).status, 0);
  ASSERT_EQ(runGlint("-q post --concat " + (d / "a.mp4").string() + " " + (d / "b.mp4").string() + " -o " +
                     (d / "joined.mp4").string()).status, 0);
  const auto joinedH264 = readAll((d / "joined.mp4").string());
  ASSERT_EQ(joinedH264.size(), 48u);
  for (std::size_t i = 0; i < joinedH264.size(); ++i) EXPECT_NEAR(joinedH264[i].seconds, double(i) / 24.0, 1e-3);
  // Parts in the wrong order: refused, nothing written.
  const auto wrong = runGlint("post --concat " + (d / "b.mkv").string() + " " + (d / "a.mkv").string() + " -o " +
                              (d / "wrong.mkv").string());
  EXPECT_EQ(wrong.status, 3) << wrong.output;
  EXPECT_TRUE(oneLine(wrong.output)) << wrong.output;
  EXPECT_FALSE(fs::exists(d / "wrong.mkv"));

  // A truncated file: the frames before the cut are processed, and the shortfall is said.
  fs::copy_file(d / "src.mkv", d / "cut.mkv");
  fs::resize_file(d / "cut.mkv", fs::file_size(d / "src.mkv") / 2);
  const auto cut = runGlint("post " + (d / "cut.mkv").string() + " -o " + (d / "cut-out.mkv").string() + " --codec ffv1");
  EXPECT_EQ(cut.status, 0) << cut.output;
  EXPECT_NE(cut.output.find("of the 48 frames its container announces"), std::string::npos) << cut.output;
  const auto cutFrames = readAll((d / "cut-out.mkv").string()).size();
  EXPECT_GT(cutFrames, 0u);
  EXPECT_LT(cutFrames, 48u);

  // Damage inside a frame (FFV1 slices carry CRCs): the decoder conceals it and flags nothing
  // on the frame, so its error log is counted, and said.
  {
    std::fstream damaged((d / "src.mkv").string(), std::ios::in | std::ios::out | std::ios::binary);
    damaged.seekp(std::streamoff(fs::file_size(d / "src.mkv") / 2));
    for (int i = 0; i < 4000; ++i) damaged.put(char(i * 131));
  }
  const auto hurt = runGlint("post " + (d / "src.mkv").string() + " -o " + (d / "hurt.mkv").string() +
                             " --codec ffv1 --json " + (d / "hurt.json").string());
  EXPECT_EQ(hurt.status, 0) << hurt.output;
  EXPECT_NE(hurt.output.find("the decoder reported 1 error(s), the first 'slice CRC mismatch"), std::string::npos)
      << hurt.output;
  EXPECT_EQ(readJson(d / "hurt.json")["decoder_errors"], 1);
  EXPECT_EQ(readAll((d / "hurt.mkv").string()).size(), 48u) << "concealed, not dropped";
}

TEST(PostCli, AudioIsCopiedDroppedWithAWarningOrDroppedOnRequest) {
  const fs::path d = dir("audio");
  // Video and a sine tone (PCM) from one lavfi graph: the audio is copied into Matroska.
  const std::string av = "lavfi:testsrc2=size=160x120:rate=24:duration=1[out0];sine=frequency=440:duration=1[out1]";
  const auto mkv = d / "av.mkv";
  ASSERT_EQ(runGlint("-q post --input '" + av + "' -o " + mkv.string() + " --codec ffv1 -e sepia --json " +
                     (d / "mkv.json").string()).status, 0);
  const auto copied = readJson(d / "mkv.json");
  EXPECT_EQ(copied["audio"], "copied");
  EXPECT_GT(copied["audio_packets"].get<int>(), 0);
  EXPECT_TRUE(video::Source::open(mkv.string()).info().hasAudio);
  // PCM cannot go into MP4: the video is made, the audio dropped, and a warning says so.
  const auto mp4 = runGlint("post " + mkv.string() + " -o " + (d / "v.mp4").string() + " --preset ultrafast --json " +
                            (d / "mp4.json").string());
  ASSERT_EQ(mp4.status, 0) << mp4.output;
  EXPECT_NE(mp4.output.find("warning: pcm_s16le audio cannot go into a .mp4 file: dropped"), std::string::npos) << mp4.output;
  EXPECT_EQ(readJson(d / "mp4.json")["audio"], "dropped");
  // --no-audio: dropped quietly, and the report says why.
  const auto quiet = runGlint("post " + mkv.string() + " -o " + (d / "n.mkv").string() + " --codec ffv1 --no-audio --json " +
                              (d / "n.json").string());
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find("warning"), std::string::npos) << quiet.output;
  EXPECT_EQ(readJson(d / "n.json")["audio"], "dropped (--no-audio)");
  EXPECT_FALSE(video::Source::open((d / "n.mkv").string()).info().hasAudio);
}

TEST(PostCli, CtrlCFinishesAPlayablePartialVideo) {
  const fs::path d = dir("interrupt");
  const fs::path out = d / "live.mp4", json = d / "r.json";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string input = "lavfi:testsrc2=size=320x240:rate=25";  // endless
    execl(GLINT_EXE, GLINT_EXE, "post", "--input", input.c_str(), "-o", out.c_str(), "-e", "sepia", "--preset",
          "ultrafast", "--json", json.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until frames are being written (the temporary file grows), then Ctrl-C.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool writing = false;
  while (!writing && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    for (const auto& e : fs::directory_iterator(d))
      if (e.path().filename().string().starts_with(".live.tmp") && e.file_size() > 20000) writing = true;
  }
  ASSERT_TRUE(writing) << "glint post never started writing";
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  ASSERT_TRUE(fs::exists(out)) << "the partial video is finished and put in place";
  const auto report = readJson(json);
  EXPECT_EQ(report["partial"], true);
  EXPECT_EQ(report["interrupted"], true);
  const auto frames = readAll(out.string());
  EXPECT_GT(frames.size(), 0u);
  EXPECT_EQ(std::int64_t(frames.size()), report["frames_written"].get<std::int64_t>()) << "playable to its last frame";
  EXPECT_EQ(fileCount(d), 2u) << "no temporary file left";
}

TEST(PostCli, BadInputIsOneLineWithTheRightStatus) {
  const fs::path d = dir("bad");
  { std::ofstream(d / "garbage.mp4") << "not a video at all"; }
  { std::ofstream(d / "empty.png"); }
  saveImage(Image(16400, 4, 4), d / "wide.png");  // wider than llvmpipe's (and most GPUs') 16384
  const std::string o = " -o " + (d / "out.mp4").string();
  const std::string png = " -o " + (d / "out.png").string();
  struct Case {
    std::string args;
    int status;
  };
  const std::vector<Case> cases = {
      {"post " + (d / "missing.mp4").string() + o, 3},
      {"post " + (d / "garbage.mp4").string() + o, 3},
      {"post " + (d / "empty.png").string() + png, 3},
      {"post " + (d / "wide.png").string() + png + " -e sepia", 3},
      {"post --camera /dev/video-none" + o, 3},
      {"post --input lavfi:nosuchsource" + o, 2},
      {"post --input " + kPattern + o + " -e sharpen", 2},
      {"post --input " + kPattern + o + " -e sepia:x=1", 2},
      {"post --input " + kPattern + o + " -e sepia --set cutoff=0.1", 2},
      {"post --input " + kPattern + o + " -e kuwahara:size=20", 2},
      {"post --input " + kPattern + o + " --frames 9:3", 2},
      {"post --input " + kPattern + o + " --codec vp9", 2},
      {"post --input lavfi:testsrc2=size=160x120:duration=1,scale=161:121" + o, 2},  // odd size for H.264
      {"post --input " + kPattern + " -o " + (d / "x.mp4").string() + " --codec ffv1", 2},
      {"post --input " + kPattern + " -o " + (d / "no/dir/out.mp4").string(), 4},
      {"post " + (d / "wide.png").string() + o, 2},  // image in, video out
      {"post" + o, 2},
  };
  for (const auto& c : cases) {
    const auto r = runGlint(c.args);
    EXPECT_EQ(r.status, c.status) << c.args << "\n" << r.output;
    EXPECT_TRUE(oneLine(r.output)) << c.args << "\n" << r.output;
  }
  EXPECT_EQ(fileCount(d), 3u) << "only the three inputs: no output, no temporary file";
}

TEST(PostCli, TheViewerShowsTheCameraSceneWithOptionsFromTheCommandLine) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run not installed (scripts/setup --test)";
  const fs::path d = dir("viewer");
  const fs::path shot = d / "view.png";
  // --set effect=0 (no effect) and a split: the right part of the window is the test pattern
  // itself; the panel covers the top left.
  const auto r = runGlint("view post/camera/sepia --size 640x480 --set effect=0 --set before-after=1 --frames 3 "
                          "--screenshot " + shot.string(),
                          "xvfb-run -a -s '-screen 0 1024x768x24'");
  ASSERT_EQ(r.status, 0) << r.output;
  const Image window = loadImage(shot);
  ASSERT_EQ(window.width(), 640);
  // The bottom-right corner of testsrc2 is its cyan bar: unprocessed (effect 0), not sepia.
  EXPECT_NEAR(window.at(630, 470, 0), 0.0f, 0.05f);
  EXPECT_NEAR(window.at(630, 470, 1), 1.0f, 0.05f);
  EXPECT_NEAR(window.at(630, 470, 2), 1.0f, 0.05f);
}
