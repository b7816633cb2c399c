// `glint farm` against a real Slurm cluster (issue 22): munged, slurmctld and slurmd from
// Debian's packages, started by the test on this machine (support/slurm_cluster.h). Every
// farmed output is compared with one local run of the same tool: byte for byte for cut,
// bake and FFV1 video; frame count and the decoded frames for lossless H.264. Faults: a
// cancelled task and a failing one stop the join, are reported with their exit code and log,
// and a rerun redoes only them.
#include "glint/bake/samples.h"
#include "glint/farm/farm.h"
#include "glint/pipedream/machine_room.h"
#include <algorithm>
#include "glint/mesh/mesh.h"
#include "support/cli.h"
#include "support/slurm_cluster.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::oneLine;
using glint::testing::readBytes;
using glint::testing::runGlint;
using glint::testing::runShell;
using glint::testing::SlurmCluster;

namespace {

constexpr auto q = glint::testing::shellQuote;

/// One cluster for the whole test program (started before the first test, stopped after
/// the last).
SlurmCluster* cluster = nullptr;

class ClusterEnvironment : public ::testing::Environment {
public:
  void SetUp() override {
    if (geteuid() != 0 && !std::getenv("CI")) return;  // slurmd runs jobs as root; tests below skip
    m_cluster = std::make_unique<SlurmCluster>(fs::path(GLINT_TEST_OUTPUT_DIR) / "farm" /
                                               fmt::format("cluster-{}", getpid()));
    cluster = m_cluster.get();
  }
  void TearDown() override {
    cluster = nullptr;
    m_cluster.reset();
  }

private:
  std::unique_ptr<SlurmCluster> m_cluster;
};
const auto* const registered = ::testing::AddGlobalTestEnvironment(new ClusterEnvironment);

#define NEED_CLUSTER() \
  if (!cluster) GTEST_SKIP() << "the Slurm fixture runs as root (slurmd starts the jobs)"

fs::path dir(const char* name) { return glint::testing::freshDir("farm", name); }

constexpr const char* kLights = " --light -1.1,10.9,2.2,key --light 2.4,7.1,0.6,fill";

/// A 4-second 320×240 H.264 clip with a keyframe every second and AAC audio (made by ffmpeg).
fs::path clip(const fs::path& d, int seconds = 4, const char* size = "320x240") {
  const fs::path path = d / "clip.mp4";
  const auto r = runShell(fmt::format("ffmpeg -nostdin -loglevel error -f lavfi -i testsrc2=size={}:rate=25:duration={} "
                                      "-f lavfi -i sine=frequency=440:duration={} -c:v libx264 -g 25 -pix_fmt yuv420p "
                                      "-c:a aac -shortest {}",
                                      size, seconds, seconds, q(path)));
  EXPECT_EQ(r.status, 0) << r.output;
  return path;
}

/// Files in `d` (not recursive) whose name ends in `suffix`.
int countFiles(const fs::path& d, const std::string& suffix) {
  int n = 0;
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(d, ec)) {
    const std::string name = e.path().filename().string();
    if (name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) ++n;
  }
  return n;
}

std::string squeue() { return SlurmCluster::shell("squeue -h -o '%i %T'"); }

/// A video's decoded frames, one MD5 per frame (ffmpeg's framemd5, timestamps dropped).
std::vector<std::string> frameHashes(const fs::path& video) {
  const auto r = runShell(fmt::format("ffmpeg -nostdin -loglevel error -i {} -map 0:v -f framemd5 -", q(video)));
  std::vector<std::string> hashes;
  std::stringstream lines(r.output);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    hashes.push_back(line.substr(line.rfind(',') + 1));
  }
  return hashes;
}

}  // namespace

TEST(FarmSlurm, CutShardsMergeToTheSameBytesAsOneLocalRun) {
  NEED_CLUSTER();
  const fs::path d = dir("cut");
  bake::writeObj(makeMachineRoom({.modules = 1}), d / "stage.obj");
  const std::string in = q(d / "stage.obj");
  ASSERT_EQ(runGlint("-q cut " + in + " -o " + q(d / "local.glb") + " -o " + q(d / "local.ply") + kLights).status, 0);

  const std::string command = "farm cut " + in + " -o " + q(d / "farm.glb") + " -o " + q(d / "farm.ply") + kLights +
                              " --shards 3 --work-dir " + q(d / "work");
  // Without --wait: the job ids, and how to follow them.
  const auto submitted = runGlint(command);
  ASSERT_EQ(submitted.status, 0) << submitted.output;
  EXPECT_NE(submitted.output.find("submitted 3 pieces"), std::string::npos) << submitted.output;
  EXPECT_NE(submitted.output.find("follow it: squeue -j "), std::string::npos) << submitted.output;
  // The same command with --wait follows that job: nothing is submitted twice.
  const auto r = runGlint(command + " --wait");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("submitted 0 pieces (3 of 3 already done or still running"), std::string::npos) << r.output;
  EXPECT_EQ(readBytes(d / "farm.glb"), readBytes(d / "local.glb"));
  EXPECT_EQ(readBytes(d / "farm.ply"), readBytes(d / "local.ply"));
  // The intermediates went after the join; the scripts and logs stay.
  EXPECT_EQ(countFiles(d / "work", ".shard"), 0);
  EXPECT_EQ(countFiles(d / "work", ".log"), 4);

  // The same command again: the job is done, nothing is submitted.
  const auto again = runGlint(command);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("already made"), std::string::npos) << again.output;
  EXPECT_EQ(squeue(), "");
}

TEST(FarmSlurm, PostChunksStartOnKeyframesAndJoinToOneLocalRun) {
  NEED_CLUSTER();
  const fs::path d = dir("post");
  const fs::path in = clip(d);
  // FFV1: the farmed video is the local one, byte for byte (audio included).
  ASSERT_EQ(runGlint("-q post " + q(in) + " -o " + q(d / "local.mkv") + " --codec ffv1 -e sepia").status, 0);
  const std::string farm = "farm post " + q(in) + " -o " + q(d / "farm.mkv") + " --codec ffv1 -e sepia --chunks 3";
  const auto dry = runGlint(farm + " --dry-run");
  ASSERT_EQ(dry.status, 0) << dry.output;
  // 100 frames, keyframes every 25: chunks at the keyframes nearest 33 and 66.
  EXPECT_NE(dry.output.find("--frames 0:25 "), std::string::npos) << dry.output;
  EXPECT_NE(dry.output.find("--frames 25:75 "), std::string::npos) << dry.output;
  EXPECT_NE(dry.output.find("--frames 75:100 "), std::string::npos) << dry.output;
  EXPECT_NE(dry.output.find("post --concat"), std::string::npos) << dry.output;
  EXPECT_EQ(squeue(), "") << "--dry-run submits nothing";
  EXPECT_FALSE(fs::exists(d / "farm.mkv"));

  const auto r = runGlint(farm + " --wait");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readBytes(d / "farm.mkv"), readBytes(d / "local.mkv"));

  // H.264, lossless: the frame count, and every decoded frame, as one local run.
  ASSERT_EQ(runGlint("-q post " + q(in) + " -o " + q(d / "local.mp4") + " --crf 0 -e sepia").status, 0);
  const auto h264 = runGlint("farm post " + q(in) + " -o " + q(d / "farm.mp4") + " --crf 0 -e sepia --chunks 2 --wait");
  ASSERT_EQ(h264.status, 0) << h264.output;
  const auto local = frameHashes(d / "local.mp4"), farmed = frameHashes(d / "farm.mp4");
  EXPECT_EQ(farmed.size(), 100u);
  EXPECT_EQ(farmed, local);
}

TEST(FarmSlurm, ACancelledTaskStopsTheJoinAndARerunRedoesOnlyIt) {
  NEED_CLUSTER();
  const fs::path d = dir("cancel");
  const fs::path in = clip(d, 8, "640x360");
  const fs::path out = d / "out.mkv";
  const std::string command = "farm post " + q(in) + " -o " + q(out) + " --codec ffv1 -e kuwahara --chunks 2 --wait "
                              "--work-dir " + q(d / "work");
  auto first = std::async(std::launch::async, [&] { return runGlint(command); });
  // Cancel piece 1 once it runs.
  std::string job;
  for (int i = 0; i < 600 && job.empty(); ++i) {
    std::stringstream lines(squeue());
    std::string id, state;
    while (lines >> id >> state)
      if (id.size() > 2 && id.substr(id.size() - 2) == "_1" && state == "RUNNING") job = id;
    if (job.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_FALSE(job.empty()) << "piece 1 never ran: " << squeue();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_EQ(runShell("scancel " + job).status, 0);
  const auto r = first.get();
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("piece 1 (frames 100:200): CANCELLED"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("piece-1.log"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "the join must not run";
  EXPECT_EQ(squeue(), "") << "nothing left queued";

  // Piece 0 finished; a rerun submits piece 1 only, then the join.
  fs::path log0;
  for (const auto& e : fs::recursive_directory_iterator(d / "work"))
    if (e.path().filename() == "piece-0.log") log0 = e.path();
  ASSERT_FALSE(log0.empty());
  const auto before = fs::last_write_time(log0);
  const auto again = runGlint(command);
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("submitted 1 piece (1 of 2 already done"), std::string::npos) << again.output;
  EXPECT_EQ(fs::last_write_time(log0), before) << "piece 0 ran again";
  ASSERT_EQ(runGlint("-q post " + q(in) + " -o " + q(d / "local.mkv") + " --codec ffv1 -e kuwahara").status, 0);
  EXPECT_EQ(readBytes(out), readBytes(d / "local.mkv"));
}

TEST(FarmSlurm, AFailingTaskIsNamedWithItsExitCodeAndLog) {
  NEED_CLUSTER();
  const fs::path d = dir("fail");
  bake::writeObj(makeMachineRoom({.modules = 1}), d / "stage.obj");
  // 1 MiB is far below the cut's estimate: every piece refuses (exit 2) before it starts.
  const auto r = runGlint("farm cut " + q(d / "stage.obj") + " -o " + q(d / "out.glb") + kLights +
                          " --shards 2 --mem 1 --wait");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("piece 0 (shard 1/2): FAILED, exit code 2; log: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run the same command again"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "out.glb"));
  // The log says why.
  const std::size_t at = r.output.find("log: ");
  const std::string log = r.output.substr(at + 5, r.output.find('\n', at) - at - 5);
  EXPECT_NE(readBytes(log).find("--max-memory"), std::string::npos) << readBytes(log);
}

TEST(FarmSlurm, RenderChunksJoinToTheVideoOfOneLocalRun) {
  NEED_CLUSTER();
  const fs::path d = dir("render");
  const std::string scene = "rtt/texture/fbo --fps 10 --size 64x48";  // a spinning cube
  ASSERT_EQ(runGlint("-q render " + scene + " --frames 0:12 --codec ffv1 -o " + q(d / "local.mkv")).status, 0);
  const auto r = runGlint("farm render " + scene + " --frames 0:12 --codec ffv1 -o " + q(d / "farm.mkv") +
                          " --chunks 3 --wait");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readBytes(d / "farm.mkv"), readBytes(d / "local.mkv"));
  // H.264, lossless: every frame, each the frame of one local run.
  ASSERT_EQ(runGlint("-q render " + scene + " --frames 0:12 --crf 0 -o " + q(d / "local.mp4")).status, 0);
  const auto h264 = runGlint("farm render " + scene + " --frames 0:12 --crf 0 -o " + q(d / "farm.mp4") +
                             " --chunks 2 --wait");
  ASSERT_EQ(h264.status, 0) << h264.output;
  const auto local = frameHashes(d / "local.mp4"), farmed = frameHashes(d / "farm.mp4");
  EXPECT_EQ(farmed.size(), 12u);
  EXPECT_EQ(farmed, local);
}

TEST(FarmSlurm, BakeRunsOneTaskPerBakeWithTheBytesOfLocalBakes) {
  NEED_CLUSTER();
  const fs::path d = dir("bake");
  bake::writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  bake::writeObj(makeUvSphere(1.0f, 64, 32), d / "high.obj");
  // Relative paths: from the batch file's folder, wherever the tasks run. The third bake
  // traces on the GPU (--device gpu; llvmpipe here), in the task as at home.
  std::ofstream(d / "jobs.json") << R"({
  "defaults": {"size": "32x32", "padding": 2, "quiet": true},
  "bakes": [
    {"low": "low.obj", "high": "high.obj", "output": "out/a.png"},
    {"low": "low.obj", "high": "high.obj", "output": "out/b.png", "directx": true, "size": "48x24"},
    {"low": "low.obj", "high": "high.obj", "output": "out/c.png", "samples": 4, "ao": "out/c_ao.png", "ao-samples": 4,
     "device": "gpu"}
  ]
})";
  fs::create_directories(d / "out");
  fs::create_directories(d / "local");
  ASSERT_EQ(runGlint("bake --batch " + q(d / "jobs.json")).status, 0);
  for (const char* f : {"a.png", "b.png", "c.png", "c_ao.png"}) fs::rename(d / "out" / f, d / "local" / f);

  const auto r = runGlint("farm bake " + q(d / "jobs.json") + " --wait");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("submitted 3 pieces"), std::string::npos) << r.output;
  for (const char* f : {"a.png", "b.png", "c.png", "c_ao.png"}) {
    EXPECT_FALSE(readBytes(d / "out" / f).empty()) << f;
    EXPECT_TRUE(readBytes(d / "out" / f) == readBytes(d / "local" / f)) << f;
  }
  // One bake's output lost: only that bake runs again.
  fs::remove(d / "out" / "b.png");
  const auto again = runGlint("farm bake " + q(d / "jobs.json") + " --wait");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("submitted 1 piece (2 of 3 already done"), std::string::npos) << again.output;
  EXPECT_TRUE(readBytes(d / "out" / "b.png") == readBytes(d / "local" / "b.png"));
}

TEST(FarmSlurm, AFileNameWithALineBreakRunsNoCommandOnTheCluster) {
  NEED_CLUSTER();
  const fs::path d = dir("evil");
  const std::string evil = "b\ntouch PWNED #.mp4";
  fs::copy_file(clip(d, 2), d / evil);
  // A work directory with quotes, a dollar and a percent sign: sbatch reads every directive.
  const fs::path work = d / "work $(x) 'q' 100%";
  fs::create_directories(work);
  const auto r = runShell("cd " + q(d) + " && " GLINT_EXE " farm post " + q(evil) + " -o ok.mkv --codec ffv1 -e sepia "
                          "--chunks 2 --wait --work-dir " + q(work));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(d / "PWNED"));
  EXPECT_FALSE(fs::exists(work / "PWNED"));
  ASSERT_EQ(runShell("cd " + q(d) + " && " GLINT_EXE " -q post " + q(evil) + " -o local.mkv --codec ffv1 -e sepia").status, 0);
  EXPECT_TRUE(readBytes(d / "ok.mkv") == readBytes(d / "local.mkv"));
  // The logs went where --output said (the directives were all read): work/post-*/logs/.
  EXPECT_EQ(countFiles(work, ".log"), 3);
}

TEST(FarmSlurm, ATaskThatCanNeverStartIsNamedAndCancelled) {
  NEED_CLUSTER();
  const fs::path d = dir("never");
  const fs::path in = clip(d, 2);
  const auto r = runGlint("farm post " + q(in) + " -o " + q(d / "out.mkv") + " --codec ffv1 -e sepia --chunks 2 "
                          "--cpus-per-task 64 --wait");
  // Slurm either refuses the job at once or keeps it pending for PartitionConfig: both are
  // said in words, and nothing is left queued.
  EXPECT_NE(r.status, 0) << r.output;
  const bool refused = r.output.find("Slurm refused the job") != std::string::npos;
  const bool never = r.output.find("can never start") != std::string::npos;
  EXPECT_TRUE(refused || never) << r.output;
  std::printf("%s", r.output.c_str());  // which of the two this Slurm did, for the log
  EXPECT_EQ(squeue(), "") << "nothing left queued";
}

TEST(Farm, WithoutSlurmItSaysWhatToInstall) {
  const fs::path d = dir("no-slurm");
  bake::writeObj(makeMachineRoom({.modules = 1}), d / "stage.obj");
  const auto r = runGlint("farm cut " + q(d / "stage.obj") + " -o " + q(d / "out.glb") + kLights + " --shards 2",
                          "PATH=/nonexistent");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("slurm-client"), std::string::npos) << r.output;
}

TEST(Farm, SplitsFramesAtTheKeyframesNearestAnEvenSplit) {
  EXPECT_EQ(farm::splitAtKeyframes({0, 25, 50, 75}, 0, 100, 3),
            (std::vector<std::pair<std::int64_t, std::int64_t>>{{0, 25}, {25, 75}, {75, 100}}));
  EXPECT_EQ(farm::splitAtKeyframes({0, 25, 50, 75}, 0, 100, 4),
            (std::vector<std::pair<std::int64_t, std::int64_t>>{{0, 25}, {25, 50}, {50, 75}, {75, 100}}));
  // Fewer keyframes than chunks: fewer chunks.
  EXPECT_EQ(farm::splitAtKeyframes({0, 50}, 0, 100, 4),
            (std::vector<std::pair<std::int64_t, std::int64_t>>{{0, 50}, {50, 100}}));
  // A range that starts between keyframes starts there (the source seeks back).
  EXPECT_EQ(farm::splitAtKeyframes({0, 25, 50, 75}, 10, 60, 2),
            (std::vector<std::pair<std::int64_t, std::int64_t>>{{10, 25}, {25, 60}}));
  EXPECT_EQ(farm::splitEvenly(0, 10, 3), (std::vector<std::pair<std::int64_t, std::int64_t>>{{0, 3}, {3, 6}, {6, 10}}));
  EXPECT_EQ(farm::splitEvenly(0, 2, 5), (std::vector<std::pair<std::int64_t, std::int64_t>>{{0, 1}, {1, 2}}));
}

// ------------------------------------------------------------------ measurements
// Not tests (no assertion on time): the figures of docs/farm.md, on this machine's one-node
// cluster. Run by hand:
//   build/tests/farm/farm_test --gtest_also_run_disabled_tests --gtest_filter='FarmMeasure.*'
namespace {
double now() { return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count(); }

template <class F>
double seconds(F&& f) {
  const double t0 = now();
  f();
  return now() - t0;
}
}  // namespace

TEST(FarmMeasure, DISABLED_SlurmOverheadPerTask) {
  NEED_CLUSTER();
  const fs::path d = dir("measure-overhead");
  std::ofstream(d / "task.sh") << "#!/bin/bash\ndate +%s.%N > " << (d / "start-").string() << "$SLURM_ARRAY_TASK_ID\n";
  // One task at a time: submit → start latency.
  std::vector<double> latency;
  for (int i = 0; i < 5; ++i) {
    fs::remove(d / "start-0");
    const double t0 = now();
    ASSERT_EQ(runShell("sbatch -Q --array=0 -o /dev/null " + q(d / "task.sh")).status, 0);
    while (!fs::exists(d / "start-0") || readBytes(d / "start-0").empty()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    latency.push_back(std::stod(readBytes(d / "start-0")) - t0);
    while (!squeue().empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::sort(latency.begin(), latency.end());
  // 64 trivial tasks: throughput of the array on this node.
  const double wall = seconds([&] {
    ASSERT_EQ(runShell("sbatch -Q --array=0-63 -o /dev/null " + q(d / "task.sh")).status, 0);
    while (!squeue().empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  });
  std::printf("slurm: submit→start %.3f s median (%.3f–%.3f, 5 runs); 64 trivial tasks in %.2f s (%.3f s each, %ld CPUs)\n",
              latency[2], latency.front(), latency.back(), wall, wall / 64, sysconf(_SC_NPROCESSORS_ONLN));
}

TEST(FarmMeasure, DISABLED_Cut550kTwoShards) {
  NEED_CLUSTER();
  const fs::path d = dir("measure-cut");
  const MachineRoomOptions options{.modules = machineRoomModulesFor(550000)};
  const Mesh stage = makeMachineRoom(options);
  bake::writeObj(stage, d / "stage.obj");
  std::string lights;
  for (const auto& l : machineRoomLights(options))
    lights += fmt::format(" --light {},{},{}", l.x, l.y, l.z);
  const std::string in = q(d / "stage.obj");
  const double local = seconds([&] { ASSERT_EQ(runGlint("-q cut " + in + " -o " + q(d / "local.glb") + lights).status, 0); });
  const double farmed = seconds([&] {
    const auto r = runGlint("farm cut " + in + " -o " + q(d / "farm.glb") + lights + " --shards 2 --cpus-per-task 1 --wait");
    ASSERT_EQ(r.status, 0) << r.output;
  });
  EXPECT_EQ(readBytes(d / "farm.glb"), readBytes(d / "local.glb"));
  std::printf("cut %zu triangles: local %.1f s, farm (2 shards, 1 CPU each) %.1f s\n", stage.triangleCount(), local, farmed);
}

TEST(FarmMeasure, DISABLED_Post1080pTwentySecondsFourChunks) {
  NEED_CLUSTER();
  const fs::path d = dir("measure-post");
  const fs::path in = clip(d, 20, "1920x1080");
  const double local = seconds([&] {
    ASSERT_EQ(runGlint("-q post " + q(in) + " -o " + q(d / "local.mp4") + " -e sepia").status, 0);
  });
  const double farmed = seconds([&] {
    const auto r = runGlint("farm post " + q(in) + " -o " + q(d / "farm.mp4") + " -e sepia --chunks 4 --wait");
    ASSERT_EQ(r.status, 0) << r.output;
  });
  const double concat = seconds([&] {
    ASSERT_EQ(runGlint("-q post --concat " + q(d / "farm.mp4") + " -o " + q(d / "again.mp4")).status, 0);
  });
  std::printf("post 1080p 20 s (500 frames, sepia, H.264): local %.1f s, farm (4 chunks) %.1f s; a concat of the "
              "whole %.2f s\n", local, farmed, concat);
}

TEST(FarmMeasure, DISABLED_PipeDream600FramesFourChunks) {
  NEED_CLUSTER();
  const fs::path d = dir("measure-render");
  const std::string scene = "pipedream --fps 30 --size 320x180 --frames 0:600";
  const double local = seconds([&] { ASSERT_EQ(runGlint("-q render " + scene + " -o " + q(d / "local.mp4")).status, 0); });
  const double farmed = seconds([&] {
    const auto r = runGlint("farm render " + scene + " -o " + q(d / "farm.mp4") + " --chunks 4 --wait");
    ASSERT_EQ(r.status, 0) << r.output;
  });
  const double concat = seconds([&] {
    ASSERT_EQ(runGlint("-q post --concat " + q(d / "farm.mp4") + " -o " + q(d / "again.mp4")).status, 0);
  });
  EXPECT_EQ(frameHashes(d / "farm.mp4").size(), 600u);
  std::printf("render pipedream 600 frames 320x180 H.264: local %.1f s, farm (4 chunks) %.1f s; a concat of the "
              "whole %.2f s\n", local, farmed, concat);
}
