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
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

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
  EXPECT_EQ(loadImage(d / "still.png"), readAll(kPattern)[5].image.withChannels(3));  // a video's frames are RGB
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
  ASSERT_TRUE(glint::testing::waitUntilWriting(d, ".live.tmp", 20000)) << "glint post never started writing";
  EXPECT_EQ(glint::testing::interruptAndWait(pid), 130);
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
      // Wider than the GPU's largest texture: an input error on the GPU (the CPU backend,
      // auto's choice on llvmpipe, has no such limit: backend_test.cpp).
      {"post " + (d / "wide.png").string() + png + " -e sepia --backend gpu", 3},
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

// A --frames range that selects no frame of the input is an input error naming its length,
// and writes nothing (it used to exit 0 with a stream-less MP4, or an FFV1 file ffprobe
// calls corrupt); one that runs past the end is a warning with the count written, and the
// report's expected count is what the container says.
TEST(PostCli, FrameRangesBeyondTheClipAreAnErrorOrAWarning) {
  const fs::path d = dir("ranges");
  const fs::path clip = d / "clip.mkv";
  ASSERT_EQ(runGlint("-q post --input " + kPattern + " --codec ffv1 -o " + clip.string()).status, 0);  // 48 frames
  for (const char* range : {"100:200", "48:", "60:"}) {
    const auto none = runGlint("post " + clip.string() + " --frames " + range + " -e sepia -o " +
                               (d / "none.mkv").string() + " --codec ffv1 -q");
    EXPECT_EQ(none.status, 3) << range << ": " << none.output;
    EXPECT_TRUE(oneLine(none.output)) << none.output;
    EXPECT_NE(none.output.find(std::string("--frames ") + range + " selects no frame of"), std::string::npos) << none.output;
    EXPECT_NE(none.output.find("48 frames, 0..47"), std::string::npos) << none.output;
    EXPECT_FALSE(fs::exists(d / "none.mkv")) << range;
  }
  const auto past = runGlint("post " + clip.string() + " --frames 40:100 -e sepia --codec ffv1 -o " +
                             (d / "tail.mkv").string() + " --json " + (d / "tail.json").string());
  ASSERT_EQ(past.status, 0) << past.output;
  EXPECT_NE(past.output.find("warning: --frames 40:100 runs past the end of '" + clip.string() +
                             "' (it has 48 frames, 0..47): 8 frame(s) written (40..47)"), std::string::npos)
      << past.output;
  const auto report = readJson(d / "tail.json");
  EXPECT_EQ(report["frames_written"], 8);
  EXPECT_EQ(report["frames_expected"], 8);
  EXPECT_EQ(readAll((d / "tail.mkv").string()).size(), 8u);
  ASSERT_EQ(runGlint("-q post " + clip.string() + " --frames 10: -e sepia --codec ffv1 -o " + (d / "rest.mkv").string() +
                     " --json " + (d / "rest.json").string()).status, 0);
  EXPECT_EQ(readJson(d / "rest.json")["frames_expected"], 38);
}

namespace {
/// The decoded audio of a file's first audio stream, as FFmpeg's command-line tool gives
/// it (an independent decoder path): raw float samples.
std::string decodedAudio(const fs::path& file) {
  return glint::testing::runShell("ffmpeg -v error -i " + glint::testing::shellQuote(file) +
                                  " -map 0:a:0 -f f32le -").output;
}
std::string audioPackets(const fs::path& file) {
  return glint::testing::runShell("ffprobe -v error -select_streams a -show_entries packet=pts,duration,size -of csv " +
                                  glint::testing::shellQuote(file)).output;
}
}  // namespace

// Audio is copied whole: AAC's first (priming) packet has a negative timestamp and was lost
// (88 packets in, 87 out, the first 1024 samples different); Opus's pre-skip packet too.
// Copied audio must decode to the same samples, bit for bit.
TEST(PostCli, CopiedAudioDecodesToTheSameSamples) {
  ASSERT_EQ(glint::testing::runShell("command -v ffmpeg ffprobe").status, 0)
      << "ffmpeg and ffprobe (Debian package ffmpeg) make and decode the test's files: scripts/setup --test installs them";
  const fs::path d = dir("audio-exact");
  struct Case {
    const char* file;
    const char* codec;
  };
  for (const Case c : {Case{"aac.mp4", "aac"}, Case{"opus.mkv", "libopus"}, Case{"aac.mkv", "aac"}}) {
    const fs::path in = d / c.file, out = d / (std::string("out-") + c.file);
    const auto made = glint::testing::runShell(
        "ffmpeg -v error -y -f lavfi -i testsrc2=size=160x120:rate=25:duration=2 -f lavfi -i sine=f=440:duration=2 "
        "-c:v libx264 -preset ultrafast -c:a " + std::string(c.codec) + " -shortest " + in.string());
    ASSERT_EQ(made.status, 0) << made.output;
    const auto run = runGlint("-q post " + in.string() + " -e sepia --preset ultrafast -o " + out.string() +
                              " --json " + (d / "r.json").string());
    ASSERT_EQ(run.status, 0) << c.file << ": " << run.output;
    EXPECT_EQ(readJson(d / "r.json")["audio"], "copied");
    const std::string original = decodedAudio(in), copied = decodedAudio(out);
    EXPECT_GT(original.size(), 2 * 44100u) << c.file;
    EXPECT_TRUE(original == copied) << c.file << ": decoded audio differs (" << original.size() << " against "
                                    << copied.size() << " bytes)";
    EXPECT_EQ(audioPackets(in), audioPackets(out)) << c.file << ": packets (timestamps, durations, sizes)";
  }
}

// '-' reads stdin and writes stdout: images both ways, video as a stream (NUT); MP4 cannot
// stream, and the errors say so.
TEST(PostCli, DashIsStdinAndStdout) {
  const fs::path d = dir("stdio");
  const fs::path photo = d / "photo.png";
  saveImage(glint::testing::noiseImage(64, 48, 3), photo);
  const auto file = runGlint("-q post " + photo.string() + " -e sobel -o " + (d / "file.png").string());
  ASSERT_EQ(file.status, 0) << file.output;
  const auto piped = glint::testing::runShell(std::string(GLINT_EXE) + " -q post - -e sobel -o - < " + photo.string() +
                                              " > " + (d / "piped.png").string());
  ASSERT_EQ(piped.status, 0) << piped.output;
  EXPECT_EQ(loadImage(d / "piped.png"), loadImage(d / "file.png"));
  const auto jpg = glint::testing::runShell(std::string(GLINT_EXE) + " -q post - -e sobel -o - --format jpg < " +
                                            photo.string() + " > " + (d / "piped.jpg").string());
  ASSERT_EQ(jpg.status, 0) << jpg.output;
  EXPECT_EQ(glint::testing::readBytes(d / "piped.jpg").substr(0, 3), "\xFF\xD8\xFF");

  const fs::path clip = d / "clip.mkv";
  ASSERT_EQ(runGlint("-q post --input " + kPattern + " --codec ffv1 -o " + clip.string()).status, 0);
  const auto stream = glint::testing::runShell("cat " + clip.string() + " | " + GLINT_EXE +
                                               " -q post - -e sepia --codec ffv1 -o - --format nut > " +
                                               (d / "piped.nut").string());
  ASSERT_EQ(stream.status, 0) << stream.output;
  ASSERT_EQ(runGlint("-q post " + clip.string() + " -e sepia --codec ffv1 -o " + (d / "file.nut").string()).status, 0);
  const auto a = readAll((d / "piped.nut").string()), b = readAll((d / "file.nut").string());
  ASSERT_EQ(a.size(), 48u);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].image, b[i].image) << "frame " << i;

  const auto mp4Out = runGlint("post " + clip.string() + " -e sepia -o - --format mp4");
  EXPECT_EQ(mp4Out.status, 2) << mp4Out.output;
  EXPECT_TRUE(oneLine(mp4Out.output)) << mp4Out.output;
  EXPECT_NE(mp4Out.output.find("cannot be written to stdout"), std::string::npos) << mp4Out.output;
  // An MP4 as FFmpeg writes it by default: its index (moov) after the frames.
  const auto mp4 = glint::testing::runShell("ffmpeg -v error -y -f lavfi -i testsrc2=size=320x240:rate=25:duration=2 "
                                            "-c:v libx264 -preset ultrafast " + (d / "clip.mp4").string());
  ASSERT_EQ(mp4.status, 0) << mp4.output << " (scripts/setup --test installs ffmpeg)";
  const auto mp4In = glint::testing::runShell("cat " + (d / "clip.mp4").string() + " | " + GLINT_EXE + " post - -o " +
                                              (d / "x.mkv").string());
  EXPECT_EQ(mp4In.status, 3) << mp4In.output;
  EXPECT_TRUE(oneLine(mp4In.output)) << mp4In.output;
  EXPECT_NE(mp4In.output.find("an MP4 cannot be read from stdin unless its index comes first"), std::string::npos)
      << mp4In.output;
  EXPECT_FALSE(fs::exists(d / "x.mkv"));
}

// An image keeps its channels: grey stays grey, RGB stays RGB (they all came out RGBA);
// an effect that colours a grey image writes RGB and says so; --channels asks otherwise.
TEST(PostCli, AnImageKeepsItsChannelCount) {
  const fs::path d = dir("channels");
  const Image rgba = glint::testing::noiseImage(64, 48, 5);
  saveImage(rgba.withChannels(1), d / "grey.png");
  saveImage(rgba.withChannels(3), d / "rgb.png");
  saveImage(rgba, d / "rgba.png");
  const auto channels = [&](const std::string& in, const std::string& args) {
    const auto r = runGlint("post " + (d / in).string() + " " + args + " -o " + (d / "out.png").string());
    EXPECT_EQ(r.status, 0) << r.output;
    return std::make_pair(loadImage(d / "out.png").channels(), r.output);
  };
  EXPECT_EQ(channels("grey.png", "-e sobel").first, 1);
  EXPECT_EQ(channels("rgb.png", "-e sobel").first, 3);
  EXPECT_EQ(channels("rgba.png", "-e sobel").first, 4);
  EXPECT_EQ(channels("rgb.png", "-e sepia").first, 3);
  const auto [sepia, said] = channels("grey.png", "-e sepia");
  EXPECT_EQ(sepia, 3);
  EXPECT_NE(said.find("the input is grey but sepia"), std::string::npos) << said;
  EXPECT_EQ(channels("rgb.png", "-e sepia --channels 1").first, 1);
  EXPECT_EQ(channels("grey.png", "-e sobel --channels 4").first, 4);
}

// One line and exit 2 for each bad option a user tried: no raw x264 line, no 309-digit range.
TEST(PostCli, BadOptionsAreOneLineAndExitTwo) {
  const fs::path d = dir("bad-options");
  const fs::path clip = d / "clip.mkv";
  ASSERT_EQ(runGlint("-q post --input " + kPattern + " --codec ffv1 -o " + clip.string()).status, 0);
  for (const std::string args : {"--preset turbo", "--threads -3", "--crf 60", "--set sigma=1e40 -e lowpass"}) {
    const auto r = runGlint("post " + clip.string() + " -e sepia -o " + (d / "o.mp4").string() + " " + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << args << ": " << r.output;
    EXPECT_EQ(r.output.find("x264 ["), std::string::npos) << r.output;
    EXPECT_LT(r.output.size(), 200u) << r.output;
  }
  EXPECT_FALSE(fs::exists(d / "o.mp4"));
}
