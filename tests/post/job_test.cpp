// A program linking glint::post runs `glint post`'s job (post/job.h): the same checks,
// the same output and the same report as the command.
#include "glint/core/error.h"
#include "glint/core/tool.h"
#include "glint/image/image.h"
#include "glint/post/job.h"

#include "post_test_util.h"
#include "support/cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using namespace glint::post;

namespace {
nlohmann::ordered_json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::ordered_json::parse(in);
}

std::vector<std::string> keys(const nlohmann::ordered_json& j) {
  std::vector<std::string> k;
  for (const auto& [key, value] : j.items()) k.push_back(key);
  return k;
}

PostJob imageJob(const fs::path& in, const fs::path& out, std::vector<std::string> specs) {
  PostJob job;
  job.input = in.string();
  job.output = out.string();
  job.effects = parseEffects(specs);
  return job;
}

// Error(kind) from runJob, with a one-line message.
ErrorKind refusal(const PostJob& job, const ToolSettings& settings = {}) {
  try {
    ToolRun run("post", settings);
    runJob(job, run);
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.kind();
  }
  ADD_FAILURE() << "the job ran";
  return ErrorKind::Internal;
}
}  // namespace

TEST(PostJob, ALinkedProgramWritesWhatTheCommandWritesAndTheSameReport) {
  const fs::path d = glint::testing::freshDir("post-job", "same");
  saveImage(glint::testing::noiseImage(64, 48, 7), d / "in.png");
  const auto cli = glint::testing::runGlint("post " + (d / "in.png").string() + " -o " + (d / "cli.png").string() +
                                            " -e posterize -e sepia:i=0.3 -q --json " + (d / "cli.json").string());
  ASSERT_EQ(cli.status, 0) << cli.output;

  ToolRun run("post", {.quiet = true, .json = (d / "lib.json").string()});
  const PostStats stats = runJob(imageJob(d / "in.png", d / "lib.png", {"posterize", "sepia:i=0.3"}), run);
  EXPECT_EQ(finishJob(stats, run), 0);

  EXPECT_EQ(loadImage(d / "lib.png"), loadImage(d / "cli.png"));
  const auto a = readJson(d / "cli.json"), b = readJson(d / "lib.json");
  EXPECT_EQ(keys(a), keys(b));
  for (const char* key : {"memory_estimate_mib", "effects", "width", "height", "frames", "tool", "warnings"}) {
    EXPECT_EQ(a[key], b[key]) << key;
  }
  EXPECT_EQ(b["effects"], "kuwahara(size=3) → edges(scale=2,threshold=0.25) → sepia(i=0.3,q=0)");
  EXPECT_EQ(b["input"], (d / "in.png").string());
  EXPECT_EQ(b["frames"], 1);
  EXPECT_EQ(b["memory_estimate_mib"], std::round(estimatePeakMemoryMiB({64, 48}, true)));
}

TEST(PostJob, TheInputKindIsDecidedInOnePlace) {
  PostJob job;
  job.input = "photo.exr";
  EXPECT_EQ(inputKind(job), InputKind::Image);
  job.input = "clip.mkv";
  EXPECT_EQ(inputKind(job), InputKind::Video);
  job.input = "lavfi:testsrc2";
  EXPECT_EQ(inputKind(job), InputKind::Lavfi);
  job.input.clear();
  job.lavfi = "lavfi:testsrc2";
  EXPECT_EQ(inputKind(job), InputKind::Lavfi);
  job.lavfi.clear();
  job.camera = "/dev/video0";
  EXPECT_EQ(inputKind(job), InputKind::Camera);
  job.camera.clear();
  job.parts = {"a.mkv", "b.mkv"};
  EXPECT_EQ(inputKind(job), InputKind::Parts);
}

TEST(PostJob, TheChecksComeBeforeAnythingIsOpened) {
  const fs::path d = glint::testing::freshDir("post-job", "checks");
  saveImage(glint::testing::noiseImage(64, 48, 7), d / "in.png");
  EXPECT_EQ(refusal(PostJob{.output = (d / "o.png").string()}), ErrorKind::Usage);  // no input
  EXPECT_EQ(refusal(imageJob(d / "in.png", d / "o.mp4", {"sepia"})), ErrorKind::Usage);  // image in, video out
  EXPECT_EQ(refusal(imageJob(d / "in.png", d / "no/dir/o.png", {"sepia"})), ErrorKind::Output);
  PostJob sized = imageJob(d / "in.png", d / "o.png", {});
  sized.cameraSize = ivec2(640, 480);
  EXPECT_EQ(refusal(sized), ErrorKind::Usage);  // --size is for cameras
  PostJob lavfi{.lavfi = "lavfi:testsrc2", .output = (d / "o.mp4").string(), .frames = FrameRange{9, 3}};
  EXPECT_EQ(refusal(lavfi), ErrorKind::Usage);  // --frames 9:3 selects no frames
  // The memory estimate, against --max-memory: refused before the GPU starts.
  EXPECT_EQ(refusal(imageJob(d / "in.png", d / "o.png", {"sepia"}), {.maxMemory = "100"}), ErrorKind::Usage);
  EXPECT_EQ(glint::testing::fileCount(d), 1u) << "nothing written";
}

// glint::post is GL-free: a program that hands runJob no GPU backend (scenes/post_gpu.h)
// runs every effect on the CPU, and asking for the GPU is a usage error that says why.
TEST(PostJob, WithoutAGpuBackendTheJobRunsOnTheCpuAndRefusesGpu) {
  const fs::path d = glint::testing::freshDir("post-job", "no-gpu");
  saveImage(glint::testing::noiseImage(64, 48, 7), d / "in.png");
  PostJob gpu = imageJob(d / "in.png", d / "gpu.png", {"sepia"});
  gpu.backend = Backend::Gpu;
  EXPECT_EQ(refusal(gpu), ErrorKind::Usage);
  EXPECT_FALSE(fs::exists(d / "gpu.png"));
  ToolRun run("post", {.quiet = true});
  const PostStats stats = runJob(imageJob(d / "in.png", d / "auto.png", {"kuwahara", "spectrum"}), run);
  EXPECT_EQ(stats.backend, "cpu");
  EXPECT_EQ(finishJob(stats, run), 0);
  EXPECT_TRUE(fs::is_regular_file(d / "auto.png"));
}

TEST(PostJob, AVideoReportHasTheCommandsFields) {
  PostStats video{.kind = InputKind::Lavfi, .input = "lavfi:testsrc2", .output = "o.mkv", .size = {160, 120},
                  .frameRate = 24.0, .codec = "ffv1", .framesRead = 48, .framesWritten = 48,
                  .inputError = "the camera stopped answering"};
  const auto j = video.toJson();
  EXPECT_EQ(keys(j), (std::vector<std::string>{"input", "output", "width", "height", "frame_rate", "codec", "effects",
                                               "live", "first_frame", "frames_read", "frames_written",
                                               "frames_expected", "dropped_frames", "corrupt_packets",
                                               "decoder_errors", "audio", "audio_packets", "rotation",
                                               "rotation_applied", "fps", "partial",
                                               "interrupted", "input_error"}));
  EXPECT_EQ(j["partial"], true);
  EXPECT_EQ(j["frames_written"], 48);
  EXPECT_EQ(keys(PostStats{.kind = InputKind::Parts}.toJson()), (std::vector<std::string>{"parts", "output", "frames"}));
  EXPECT_EQ(keys(PostStats{.kind = InputKind::Video, .still = true}.toJson()),
            (std::vector<std::string>{"input", "output", "frame", "effects", "rotation", "rotation_applied"}));
}

// Ctrl-C before the first frame is processed: no video is made, and a file already at the
// output path keeps its bytes (it used to be replaced by a 225-byte file without a stream,
// reported as "complete, playable").
TEST(PostJob, InterruptedBeforeTheFirstFrameLeavesTheExistingFileAlone) {
  const fs::path d = glint::testing::freshDir("post-job", "interrupt-first");
  const std::string before = "an existing video a user cares about";
  {
    std::ofstream(d / "keep.mkv") << before;
  }
  PostJob job;
  job.lavfi = "lavfi:testsrc2=size=160x120:rate=24:duration=2";
  job.output = (d / "keep.mkv").string();
  job.codec = video::Codec::Ffv1;
  job.effects = parseEffects(std::vector<std::string>{"sepia"});
  try {
    ToolRun run("post", {.quiet = true});
    ::raise(SIGINT);  // the handler ToolRun installed sets its cancel flag: nothing is read
    ASSERT_TRUE(run.interrupted());
    runJob(job, run);
    ADD_FAILURE() << "an interrupted job with no frame returned normally";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Interrupted) << e.what();
    EXPECT_NE(std::string(e.what()).find("before the first frame; '" + job.output + "' was left as it was"),
              std::string::npos) << e.what();
  }
  EXPECT_EQ(glint::testing::readBytes(d / "keep.mkv"), before);
  EXPECT_EQ(glint::testing::fileCount(d), 1u) << "no temporary left";
}
