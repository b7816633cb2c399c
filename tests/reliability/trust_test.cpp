// Trust on the farm and at the edges (issue 33): every case a new user found broken, run as
// that user ran it, through the glint command.
//
//   farm       no file name runs a command or cuts a batch script's directives short; the
//              farm makes the tool's own checks before submitting; "already made" means the
//              very files the join wrote; Ctrl-C stops following and says the jobs go on
//   outputs    all of a run's outputs or none (a full disk: a small tmpfs, as root); an
//              interrupted run never replaces an existing video
//   colour     float images come back linear; a rotated clip keeps (or applies) its rotation
//   messages   a variable-frame-rate file is not "damaged"; a bake bigger than the machine is
//              refused; bake groups fall back without part names; --bits where it fits
//
// The farm cases run on the local scheduler (`--scheduler local`: the same batch scripts,
// run as child processes), so they need neither root nor a cluster; tests/farm/farm_test.cpp
// runs the Slurm side.
#include "support/cli.h"

#include "glint/bake/samples.h"
#include "glint/farm/scheduler.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <fcntl.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using namespace glint::testing;

namespace {

constexpr auto q = shellQuote;

fs::path dir(const std::string& name) { return glint::testing::freshDir("trust", name); }

/// A 25 fps 320x240 FFV1 clip, `seconds` long, a keyframe every frame (made by ffmpeg).
void makeClip(const fs::path& path, int seconds = 2) {
  const auto r = runShell(fmt::format("ffmpeg -nostdin -loglevel error -y -f lavfi -i testsrc2=size=320x240:rate=25:duration={} "
                                      "-c:v ffv1 {}", seconds, q(path)));
  ASSERT_EQ(r.status, 0) << r.output;
}

/// `glint ARGS` run in folder `d` (so that a command a file name smuggled in would land there).
glint::testing::CliRun glintIn(const fs::path& d, const std::string& args) {
  return runShell("cd " + q(d) + " && " GLINT_EXE " " + args);
}

bool pwnedUnder(const fs::path& d) {
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(d, ec))
    if (e.path().filename() == "PWNED") return true;  // what the smuggled command would make
  return false;
}

/// The batch scripts `--dry-run` prints, each from its "#!/bin/bash".
std::vector<std::string> scriptsOf(const std::string& output) {
  std::vector<std::string> scripts;
  for (std::size_t at = output.find("#!/bin/bash"); at != std::string::npos;) {
    const std::size_t next = output.find("#!/bin/bash", at + 1);
    scripts.push_back(output.substr(at, next == std::string::npos ? std::string::npos : next - at));
    at = next;
  }
  return scripts;
}

nlohmann::json readJson(const fs::path& path) { return nlohmann::json::parse(readBytes(path)); }

/// A small tmpfs mounted for one test (as root; skipped otherwise), filled on request.
class SmallDisk {
public:
  SmallDisk(const fs::path& where, std::size_t bytes) : m_dir(where) {
    fs::create_directories(m_dir);
    m_mounted = ::mount("tmpfs", m_dir.c_str(), "tmpfs", 0, fmt::format("size={}", bytes).c_str()) == 0;
  }
  ~SmallDisk() {
    if (m_mounted) ::umount2(m_dir.c_str(), MNT_DETACH);
  }
  bool mounted() const { return m_mounted; }
  const fs::path& dir() const { return m_dir; }
  std::size_t freeBytes() const {
    struct statvfs st {};
    ::statvfs(m_dir.c_str(), &st);
    return std::size_t(st.f_bavail) * st.f_frsize;
  }
  /// Fills the disk until `leave` bytes (rounded down to its blocks) are free.
  void leave(std::size_t bytes) {
    const std::size_t free = freeBytes();
    ASSERT_GT(free, bytes);
    std::ofstream(m_dir / "filler", std::ios::app) << std::string(free - bytes, 'x');
  }

private:
  fs::path m_dir;
  bool m_mounted = false;
};

#define NEED_ROOT_MOUNT(disk) \
  if (!(disk).mounted()) GTEST_SKIP() << "mounting a small tmpfs needs root (CI runs the suite as root)"

/// Files in `d` whose name says they are glint's temporaries.
int temporaries(const fs::path& d) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(d))
    if (e.path().filename().string().find(".tmp") != std::string::npos) ++n;
  return n;
}

}  // namespace

// ---------------------------------------------------------------------------------- farm

TEST(TrustFarm, AFileNameWithALineBreakRunsNoCommandAndKeepsEveryDirective) {
  const fs::path d = dir("evil-name");
  const std::string evil = "b\ntouch PWNED #.mkv";
  makeClip(d / evil);
  const std::string farm = "farm post " + q(evil) + " -o ok.mkv --codec ffv1 -e sepia --chunks 2";
  const auto dry = glintIn(d, farm + " --dry-run --partition \"night's\" --time 1:00:00");
  ASSERT_EQ(dry.status, 0) << dry.output;
  const auto scripts = scriptsOf(dry.output);
  ASSERT_EQ(scripts.size(), 2u) << dry.output;
  for (const std::string& script : scripts) {
    std::map<std::string, std::string> directives;
    for (const auto& [name, value] : farm::readDirectives(script)) directives[name] = value;
    for (const char* kept : {"job-name", "output", "chdir", "partition", "time", "mem"})
      EXPECT_TRUE(directives.count(kept)) << kept << " was cut off:\n" << script;
    EXPECT_EQ(directives["partition"], "night's");
    std::stringstream lines(script);
    std::string line;
    while (std::getline(lines, line)) EXPECT_FALSE(line.starts_with("touch")) << "a line of its own: " << line;
  }
  // Submitted (this machine's scheduler runs the same scripts): the clip is processed, no
  // command ran, the logs are where --output says.
  const auto run = glintIn(d, farm + " --scheduler local --wait");
  ASSERT_EQ(run.status, 0) << run.output;
  ASSERT_EQ(glintIn(d, "-q post " + q(evil) + " -o local.mkv --codec ffv1 -e sepia").status, 0);
  EXPECT_TRUE(readBytes(d / "ok.mkv") == readBytes(d / "local.mkv"));
  EXPECT_FALSE(pwnedUnder(d));
  int logs = 0;
  for (const auto& e : fs::recursive_directory_iterator(d))
    if (e.path().filename().string().starts_with("piece-") && e.path().extension() == ".log") ++logs;
  EXPECT_EQ(logs, 2);
}

TEST(TrustFarm, AWorkDirectoryWithALineBreakIsRefusedInOneLine) {
  const fs::path d = dir("evil-work");
  makeClip(d / "clip.mkv");
  fs::create_directories(d / "a\nb");
  const auto r = glintIn(d, "farm post clip.mkv -o ok.mkv --codec ffv1 -e sepia --chunks 2 --dry-run --work-dir " +
                                q("a\nb"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("#SBATCH line cannot hold it"), std::string::npos) << r.output;
}

TEST(TrustFarm, TheFarmMakesTheToolsChecksBeforeSubmitting) {
  const fs::path d = dir("checks");
  makeClip(d / "clip.mkv");
  const std::string clipBytes = readBytes(d / "clip.mkv");
  // An output that is the input: the tool's own refusal (exit 2), before any piece runs.
  for (const char* extra : {" --dry-run", " --scheduler local --wait"}) {
    const auto r = glintIn(d, std::string("farm post clip.mkv -o ./clip.mkv --codec ffv1 -e sepia --chunks 2") + extra);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_TRUE(oneLine(r.output)) << r.output;
    EXPECT_NE(r.output.find("would destroy the input"), std::string::npos) << r.output;
  }
  EXPECT_EQ(readBytes(d / "clip.mkv"), clipBytes);
  bake::writeObj(makeUvSphere(1.0f, 12, 6), d / "in.obj");
  const auto cut = glintIn(d, "farm cut in.obj -o in.obj --light 0,3,0 --shards 2 --dry-run");
  EXPECT_EQ(cut.status, 2) << cut.output;
  EXPECT_NE(cut.output.find("would destroy the input"), std::string::npos) << cut.output;

  // A batch whose AO map is its high mesh: refused by --dry-run, naming the job.
  bake::writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  bake::writeObj(makeUvSphere(1.0f, 48, 24), d / "high.obj");
  std::ofstream(d / "bad.json") << R"({"defaults": {"size": "32x32"}, "bakes": [
    {"low": "low.obj", "high": "high.obj", "output": "n.png"},
    {"low": "low.obj", "high": "high.obj", "output": "m.png", "ao": "high.obj"}]})";
  const auto bad = glintIn(d, "farm bake bad.json --dry-run");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_TRUE(oneLine(bad.output)) << bad.output;
  EXPECT_NE(bad.output.find("job 1"), std::string::npos) << bad.output;

  // Every option of the tool: --samples for every job of the batch, as glint bake --batch takes it.
  std::ofstream(d / "good.json") << R"({"defaults": {"size": "32x32", "padding": 2},
    "bakes": [{"low": "low.obj", "high": "high.obj", "output": "out/a.png", "ao": "out/a_ao.png"}]})";
  fs::create_directories(d / "out");
  const auto dry = glintIn(d, "farm bake good.json --samples 4 --ao-samples 2 --dry-run");
  ASSERT_EQ(dry.status, 0) << dry.output;
  EXPECT_NE(dry.output.find("--samples 4"), std::string::npos) << dry.output;
  const auto farmed = glintIn(d, "farm bake good.json --samples 4 --ao-samples 2 --scheduler local --wait");
  ASSERT_EQ(farmed.status, 0) << farmed.output;
  fs::create_directories(d / "local");
  for (const char* f : {"a.png", "a_ao.png"}) fs::rename(d / "out" / f, d / "local" / f);
  ASSERT_EQ(glintIn(d, "-q bake --batch good.json --samples 4 --ao-samples 2").status, 0);
  for (const char* f : {"a.png", "a_ao.png"}) EXPECT_TRUE(readBytes(d / "out" / f) == readBytes(d / "local" / f)) << f;
}

TEST(TrustFarm, AFileInPlaceOfTheOutputIsNotAlreadyMade) {
  const fs::path d = dir("garbage");
  makeClip(d / "clip.mkv");
  const std::string farm = "farm post clip.mkv -o out.mkv --codec ffv1 -e sepia --chunks 2 --scheduler local --wait";
  ASSERT_EQ(glintIn(d, farm).status, 0);
  const std::string good = readBytes(d / "out.mkv");
  const auto again = glintIn(d, farm);
  EXPECT_NE(again.output.find("already made"), std::string::npos) << again.output;
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::ofstream(d / "out.mkv") << "garbage\n";
  const auto redo = glintIn(d, farm);
  ASSERT_EQ(redo.status, 0) << redo.output;
  EXPECT_EQ(redo.output.find("already made"), std::string::npos) << redo.output;
  EXPECT_TRUE(readBytes(d / "out.mkv") == good);
}

TEST(TrustFarm, CtrlCStopsFollowingAndSaysTheJobsGoOn) {
  const fs::path d = dir("follow");
  makeClip(d / "clip.mkv", 6);
  const fs::path log = d / "farm.log";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (chdir(d.c_str()) != 0) _exit(126);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    execl(GLINT_EXE, GLINT_EXE, "farm", "post", "clip.mkv", "-o", "out.mkv", "--codec", "ffv1", "-e", "kuwahara",
          "--chunks", "2", "--scheduler", "local", "--wait", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Once it follows the jobs, Ctrl-C.
  for (int i = 0; i < 300 && readBytes(log).find("submitted") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(glint::testing::interruptAndWait(pid), 130) << readBytes(log);
  EXPECT_NE(readBytes(log).find("the jobs keep running"), std::string::npos) << readBytes(log);
  // They do: following again finishes the job, with no piece submitted again — or finds it
  // already made, when the jobs finished in between (a fast machine, or one busy elsewhere).
  const auto r = glintIn(d, "farm post clip.mkv -o out.mkv --codec ffv1 -e kuwahara --chunks 2 --scheduler local --wait");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(r.output.find("submitted 0 pieces") != std::string::npos ||
              r.output.find("already made by this very job") != std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(d / "out.mkv"));
}

TEST(TrustFarm, WithoutAClusterConfigurationSlurmsErrorIsExplained) {
  if (runShell("command -v sbatch").status != 0) GTEST_SKIP() << "slurm-client is not installed";
  if (fs::exists("/etc/slurm/slurm.conf")) GTEST_SKIP() << "this machine has a Slurm configuration";
  const fs::path d = dir("no-conf");
  makeClip(d / "clip.mkv");
  const auto r = runShell("cd " + q(d) + " && env -u SLURM_CONF " GLINT_EXE " farm post clip.mkv -o out.mkv --codec ffv1 "
                          "-e sepia --chunks 2");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("point SLURM_CONF at the cluster's slurm.conf"), std::string::npos) << r.output;
}

// ------------------------------------------------------------------------------- outputs

TEST(TrustOutputs, AFullDiskLeavesEveryOutputOfTheRunAsItWas) {
  const fs::path d = dir("full-disk");
  SmallDisk disk(d / "disk", 1 << 20);
  NEED_ROOT_MOUNT(disk);
  const fs::path out = disk.dir();
  // The run again with `files` (path → old bytes) in place and `free` bytes left on the
  // disk: exit 4, one line saying so, every file as it was, no temporary left.
  const auto expectRefused = [&](const std::string& command, const std::map<fs::path, std::string>& files,
                                 std::uintmax_t free) {
    for (const auto& [path, bytes] : files) std::ofstream(path) << bytes;
    disk.leave(free);
    const auto full = runGlint(command);
    EXPECT_EQ(full.status, 4) << full.output;
    EXPECT_NE(full.output.find("no space left on device"), std::string::npos) << full.output;
    for (const auto& [path, bytes] : files) EXPECT_EQ(readBytes(path), bytes) << path;
    EXPECT_EQ(temporaries(out), 0);
    fs::remove(out / "filler");
    return full;
  };

  // cut, two outputs: the second does not fit; the first is not replaced either.
  bake::writeObj(makeTorus(1.0f, 0.35f, 48, 24), d / "room.obj");
  const std::string cut = "-q cut " + q(d / "room.obj") + " --light 0,3,0 -o " + q(out / "c.glb") + " -o " + q(out / "c.ply");
  ASSERT_EQ(runGlint(cut).status, 0);
  const auto glb = fs::file_size(out / "c.glb"), ply = fs::file_size(out / "c.ply");
  EXPECT_TRUE(oneLine(expectRefused(cut, {{out / "c.glb", "old glb"}, {out / "c.ply", "old ply"}}, glb + ply / 2 + 8192).output));

  // bake, a PNG and an EXR map.
  bake::writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  bake::writeObj(makeUvSphere(1.0f, 64, 32), d / "high.obj");
  const std::string bakeCmd = "-q bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " --size 256x256 -o " +
                              q(out / "n.png") + " --ao " + q(out / "ao.exr") + " --ao-samples 2";
  ASSERT_EQ(runGlint(bakeCmd).status, 0);
  const auto png = fs::file_size(out / "n.png"), exr = fs::file_size(out / "ao.exr");
  expectRefused(bakeCmd, {{out / "n.png", "old png"}, {out / "ao.exr", "old exr"}}, std::min(png, exr) + 4096);

  // post, a video and its --json report: the video fits, the report does not.
  makeClip(d / "clip.mkv", 1);
  const std::string post = "-q post " + q(d / "clip.mkv") + " -o " + q(out / "v.mkv") + " --codec ffv1 -e sepia --json " +
                           q(out / "r.json");
  ASSERT_EQ(runGlint(post).status, 0);
  const auto video = fs::file_size(out / "v.mkv");
  expectRefused(post, {{out / "v.mkv", "old video"}, {out / "r.json", "{}"}}, (video + 4095) / 4096 * 4096);

  // A web page into a new folder that does not fit (three.js alone is over 600 KB): no file
  // of it, and no folder either, is left behind (issue 45).
  disk.leave(200 * 1024);
  const auto page = runGlint("-q view " + q(d / "low.obj") + " --export-web " + q(out / "page"));
  EXPECT_EQ(page.status, 4) << page.output;
  EXPECT_TRUE(oneLine(page.output)) << page.output;
  EXPECT_FALSE(fs::exists(out / "page")) << "an empty folder left behind";
  const auto preview = runGlint(bakeCmd + " --preview " + q(out / "preview"));
  EXPECT_EQ(preview.status, 4) << preview.output;
  EXPECT_FALSE(fs::exists(out / "preview")) << "an empty folder left behind";
  EXPECT_EQ(temporaries(out), 0);
  fs::remove(out / "filler");

  // render, a clip that does not fit.
  disk.leave(64 * 1024);
  const auto render = runGlint("render rtt/texture/fbo --frames 0:60 --size 320x240 --codec ffv1 -o " + q(out / "r.mkv"));
  EXPECT_EQ(render.status, 4) << render.output;
  EXPECT_NE(render.output.find("no space left on device"), std::string::npos) << render.output;
  EXPECT_FALSE(fs::exists(out / "r.mkv"));
  EXPECT_EQ(temporaries(out), 0);
}

TEST(TrustOutputs, CtrlCOverAnExistingVideoWritesThePartialBesideIt) {
  const fs::path d = dir("partial");
  const fs::path out = d / "graded.mkv";
  ASSERT_EQ(runGlint("-q post --input lavfi:testsrc2=size=320x240:rate=25:duration=2 --codec ffv1 -o " + q(out)).status, 0);
  const std::string complete = readBytes(out);
  const fs::path log = d / "post.log";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
    const std::string input = "lavfi:testsrc2=size=320x240:rate=25";  // endless
    execl(GLINT_EXE, GLINT_EXE, "post", "--input", input.c_str(), "-o", out.c_str(), "--codec", "ffv1", "-e", "sepia",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_TRUE(glint::testing::waitUntilWriting(d, ".graded.tmp", 100000)) << "glint post never started writing";
  EXPECT_EQ(glint::testing::interruptAndWait(pid), 130);
  EXPECT_TRUE(readBytes(out) == complete) << "the complete video was replaced by a part";
  EXPECT_TRUE(fs::exists(d / "graded.partial.mkv"));
  EXPECT_NE(readBytes(log).find("'" + out.string() + "' was left as it was"), std::string::npos) << readBytes(log);
  EXPECT_NE(readBytes(log).find("graded.partial.mkv"), std::string::npos) << readBytes(log);
  EXPECT_GT(fs::file_size(d / "graded.partial.mkv"), 0u);
}

// -------------------------------------------------------------------------------- colour

TEST(TrustColour, FloatImagesComeBackLinear) {
  const fs::path d = dir("float");
  Image ramp(64, 32, 3, PixelType::F32);
  for (int y = 0; y < ramp.height(); ++y)
    for (int x = 0; x < ramp.width(); ++x)
      for (int c = 0; c < 3; ++c) ramp.set(x, y, c, c == 0 ? 0.2f : c == 1 ? float(x) / 16.0f : float(y) / 31.0f);
  saveImage(ramp, d / "in.exr");
  for (const fs::path& input : {d / "in.exr", fs::path(GLINT_SOURCE_DIR) / "data/env/city.exr"}) {
    if (!fs::exists(input)) continue;
    const fs::path output = d / ("out-" + input.filename().string());
    const auto r = runGlint("-q post " + q(input) + " -o " + q(output) + " -e blur:sigma=0.001");
    ASSERT_EQ(r.status, 0) << r.output;
    const Image a = loadImage(input), b = loadImage(output);
    ASSERT_EQ(b.type(), PixelType::F32);
    ASSERT_EQ(a.width(), b.width());
    double worst = 0.0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x)
        for (int c = 0; c < 3; ++c) {
          const double v = a.at(x, y, c), w = b.at(x, y, c);
          worst = std::max(worst, std::abs(v - w) / std::max(1.0, std::abs(v)));
        }
    // Identity within 1e-4 (relative above 1: an HDR sky of 30 keeps its four digits).
    EXPECT_LT(worst, 1e-4) << input << " (a blur of sigma 0.001 is the identity)";
  }
  // Linear 0.2 stays 0.2 (it came back as 0.484, its sRGB encoding), and an 8-bit input
  // written as EXR holds linear light too.
  EXPECT_NEAR(loadImage(d / "out-in.exr").at(0, 0, 0), 0.2f, 1e-4f);
  Image grey(8, 8, 3, PixelType::U8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) grey.set(x, y, c, 124.0f / 255.0f);
  saveImage(grey, d / "grey.png");
  ASSERT_EQ(runGlint("-q post " + q(d / "grey.png") + " -o " + q(d / "grey.exr") + " -e blur:sigma=0.001").status, 0);
  EXPECT_NEAR(loadImage(d / "grey.exr").at(4, 4, 1), std::pow((124.0 / 255.0 + 0.055) / 1.055, 2.4), 2e-3);
}

TEST(TrustColour, ARotatedClipKeepsItsRotationOrIsTurnedUpright) {
  const fs::path d = dir("rotation");
  // A phone's portrait clip, made the way the platform's FFmpeg makes one: 6.0 and later take
  // -display_rotation (7.1 ignores the rotate tag), 5.1 takes the rotate tag. Both give a
  // display matrix ffprobe reads as rotation=90.
  const bool displayRotation = runShell("ffmpeg -hide_banner -h full 2>/dev/null | grep -q -- -display_rotation").status == 0;
  const auto made = runShell(fmt::format(
      "ffmpeg -nostdin -loglevel error -y -f lavfi -i testsrc2=size=64x48:rate=10:duration=1 -c:v libx264 {} && "
      "ffmpeg -nostdin -loglevel error -y {} -i {} -c copy {} {}",
      q(d / "flat.mp4"), displayRotation ? "-display_rotation:v:0 90" : "", q(d / "flat.mp4"),
      displayRotation ? "" : "-metadata:s:v:0 rotate=90", q(d / "phone.mp4")));
  ASSERT_EQ(made.status, 0) << made.output;
  // Kept: the output's display matrix shows it as the input's does, and the report says so.
  const auto kept = runGlint("post " + q(d / "phone.mp4") + " -o " + q(d / "kept.mp4") + " -e sepia --json " + q(d / "k.json"));
  ASSERT_EQ(kept.status, 0) << kept.output;
  EXPECT_EQ(readJson(d / "k.json")["rotation"], 90);
  EXPECT_EQ(readJson(d / "k.json")["rotation_applied"], false);
  EXPECT_NE(runShell("ffprobe -v error -show_entries stream_side_data_list " + q(d / "kept.mp4")).output.find("rotation=90"),
            std::string::npos);
  // Applied: upright frames, no matrix; the same picture ffmpeg's own autorotation gives.
  const auto up = runGlint("post " + q(d / "phone.mp4") + " -o " + q(d / "up.mp4") + " --apply-rotation --json " +
                           q(d / "u.json"));
  ASSERT_EQ(up.status, 0) << up.output;
  EXPECT_EQ(readJson(d / "u.json")["rotation_applied"], true);
  EXPECT_EQ(readJson(d / "u.json")["width"], 48);
  EXPECT_EQ(runShell("ffprobe -v error -show_entries stream_side_data_list " + q(d / "up.mp4")).output.find("rotation"),
            std::string::npos);
  // The upright still against ffmpeg's own autorotation of the same clip: as far apart as
  // glint's and ffmpeg's colour conversions of the unrotated clip are (the same pixels,
  // each in its place), and far from the frame turned the other way.
  const auto meanDiff = [](const Image& a, const Image& b, bool halfTurn) {
    double diff = 0.0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x)
        for (int c = 0; c < 3; ++c)
          diff += std::abs(a.at(x, y, c) - (halfTurn ? b.at(b.width() - 1 - x, b.height() - 1 - y, c) : b.at(x, y, c)));
    return diff / (a.width() * a.height() * 3);
  };
  const auto still = [&](const char* clip, const char* name) {
    EXPECT_EQ(runGlint("-q post " + q(d / clip) + " -o " + q(d / (std::string(name) + ".png"))).status, 0);
    EXPECT_EQ(runShell("ffmpeg -nostdin -loglevel error -y -i " + q(d / clip) + " -frames:v 1 " +
                       q(d / (std::string(name) + "-ffmpeg.png"))).status, 0);
    return std::make_pair(loadImage(d / (std::string(name) + ".png")), loadImage(d / (std::string(name) + "-ffmpeg.png")));
  };
  const auto [flat, flatRef] = still("flat.mp4", "flat");
  const auto [upright, uprightRef] = still("phone.mp4", "upright");
  ASSERT_EQ(upright.width(), 48);
  ASSERT_EQ(uprightRef.width(), 48);
  const double conversion = meanDiff(flat, flatRef, false);
  EXPECT_NEAR(meanDiff(upright, uprightRef, false), conversion, 1e-3);
  EXPECT_GT(meanDiff(upright, uprightRef, true), 4 * conversion + 0.02);
}

// ------------------------------------------------------------------------------ messages

TEST(TrustMessages, AVariableFrameRateFileIsNotCalledDamaged) {
  const fs::path d = dir("vfr");
  // Frames at 0, 0.1, 0.15, 0.4, ... s: a clean file whose average rate times its duration
  // is not its frame count.
  const auto made = runShell(fmt::format(
      "ffmpeg -nostdin -loglevel error -y -f lavfi -i testsrc2=size=160x120:rate=20:duration=3 "
      "-vf \"select='not(mod(n\\,3))+eq(mod(n\\,7)\\,1)',setpts=N/20/TB+0.2*floor(N/4)/TB\" -fps_mode vfr -c:v ffv1 {}",
      q(d / "vfr.mkv")));
  ASSERT_EQ(made.status, 0) << made.output;
  const auto r = runGlint("post " + q(d / "vfr.mkv") + " -o " + q(d / "out.mkv") + " --codec ffv1 -e sepia");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("truncated or damaged"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
}

TEST(TrustMessages, ABakeBiggerThanTheMachineIsRefusedBeforeItStarts) {
  const fs::path d = dir("big-bake");
  bake::writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  bake::writeObj(makeUvSphere(1.0f, 32, 16), d / "high.obj");
  const std::string args = "bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " --size 2048x2048 -o " + q(d / "n.png");
  const auto refused = runGlint(args, "GLINT_PHYSICAL_MEMORY_MIB=64");
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_TRUE(oneLine(refused.output)) << refused.output;
  EXPECT_NE(refused.output.find("more than this machine's 64 MiB of memory"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(d / "n.png"));
  const auto allowed = runGlint("-q " + args + " --max-memory 8G", "GLINT_PHYSICAL_MEMORY_MIB=64");
  EXPECT_EQ(allowed.status, 0) << allowed.output;
}

TEST(TrustMessages, OutOfMemoryIsItsOwnDocumentedExitStatus) {
  const fs::path d = dir("oom");
  bake::writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  bake::writeObj(makeUvSphere(1.0f, 64, 32), d / "high.obj");
  // An 8192² bake (about 1.3 GB) in a process allowed 1.5 GB of address space: the estimate
  // passes the machine's memory, the allocator then fails.
  const auto r = runShell("ulimit -v 1500000 && " GLINT_EXE " -q bake " + q(d / "low.obj") + " " + q(d / "high.obj") +
                          " --size 8192x8192 -o " + q(d / "n.png"));
  EXPECT_EQ(r.status, 6) << r.output;
  EXPECT_NE(r.output.find("glint: out of memory"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "n.png"));
}

TEST(TrustMessages, BakeGroupsFallBackWithoutHighPartNamesAndCanBeTurnedOff) {
  const fs::path d = dir("groups");
  // A low OBJ whose one part is named suz_low, and a high PLY (PLY has no part names).
  bake::writeObj(makeUvSphere(1.0f, 16, 8), d / "plain.obj");
  std::ofstream(d / "low.obj") << "o suz_low\n" << readBytes(d / "plain.obj");
  const Mesh high = makeUvSphere(1.0f, 48, 24);
  {
    std::ofstream ply(d / "high.ply");
    ply << "ply\nformat ascii 1.0\nelement vertex " << high.vertexCount()
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
        << "element face " << high.triangleCount() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (std::size_t i = 0; i < high.vertexCount(); ++i)
      ply << high.positions[i].x << ' ' << high.positions[i].y << ' ' << high.positions[i].z << ' ' << high.normals[i].x
          << ' ' << high.normals[i].y << ' ' << high.normals[i].z << '\n';
    for (std::size_t t = 0; t < high.triangleCount(); ++t)
      ply << "3 " << high.indices[3 * t] << ' ' << high.indices[3 * t + 1] << ' ' << high.indices[3 * t + 2] << '\n';
  }
  const auto r = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.ply") + " --size 32x32 -o " + q(d / "n.png"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("names no part with '_high'"), std::string::npos) << r.output;
  const auto off = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.ply") + " --size 32x32 -o " + q(d / "m.png") +
                            " --no-groups");
  EXPECT_EQ(off.status, 0) << off.output;
  EXPECT_EQ(off.output.find("warning"), std::string::npos) << off.output;
  EXPECT_TRUE(readBytes(d / "n.png") == readBytes(d / "m.png"));
}

TEST(TrustMessages, BitsAppliesToTheMapsThatHoldIt) {
  const fs::path d = dir("bits");
  bake::writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  bake::writeObj(makeUvSphere(1.0f, 32, 16), d / "high.obj");
  const auto r = runGlint("-q bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " --size 32x32 -o " + q(d / "n.png") +
                          " --ao " + q(d / "ao.exr") + " --ao-samples 2 --bits 16");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(loadImage(d / "n.png").type(), PixelType::U16);
  EXPECT_EQ(loadImage(d / "ao.exr").type(), PixelType::F32);
  // A depth no map has is still a mistake.
  const auto none = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " --size 32x32 -o " + q(d / "t.tga") +
                             " --bits 16");
  EXPECT_EQ(none.status, 2) << none.output;
  EXPECT_TRUE(oneLine(none.output)) << none.output;
}
