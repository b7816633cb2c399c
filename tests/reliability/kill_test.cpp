// kill -9 at random points: a tool killed outright leaves no partial file at its output
// path (only a clearly named temporary, which the next run removes), and never touches
// its inputs. Each tool runs once to completion (the reference), then is killed a dozen
// times at delays spread over that run's duration, then runs once more.
#include "support/cli.h"

#include "glint/bake/samples.h"
#include "glint/pipedream/machine_room.h"
#include "glint/mesh/mesh.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::readBytes;

namespace {

/// Every regular file under `dir`, by relative path, with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = readBytes(e.path());
  }
  return files;
}

/// A temporary as core/file.h names it: ".<stem>.tmp<pid>-<n><ext>".
bool isTemporary(const fs::path& p) {
  const std::string name = p.filename().string();
  return name.size() > 1 && name[0] == '.' && name.find(".tmp") != std::string::npos;
}

/// Starts `glint args` (output discarded) and returns its process id.
pid_t spawnGlint(const std::string& args) {
  const std::string command = "exec " GLINT_EXE " " + args;
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

/// Runs `glint args` to completion; its wall time.
double runToEnd(const std::string& args) {
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = spawnGlint(args);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "glint " << args;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Job {
  std::string args;             ///< the command line, writing into `out`
  fs::path out;                 ///< the output directory
  std::vector<fs::path> inputs; ///< must stay byte-identical
  /// Files whose bytes may differ between complete runs (timings in a report).
  std::vector<std::string> variable;
};

/// The kill rounds for one job; the seed is printed so a failure can be replayed.
void killRepeatedly(const Job& job, int rounds, unsigned seed) {
  std::map<fs::path, std::string> inputs;
  for (const fs::path& p : job.inputs) inputs[p] = readBytes(p);
  // The shorter of two complete runs: a first run slowed by a busy machine (another test's
  // browser beside it) would draw most delays past the end of the runs that follow.
  double seconds = runToEnd(job.args);
  seconds = std::min(seconds, runToEnd(job.args));
  const auto reference = snapshot(job.out);
  ASSERT_FALSE(reference.empty());
  std::mt19937 random(seed);
  int killedBeforeEnd = 0;
  for (int round = 0; round < rounds; ++round) {
    // A run that finished before its kill was shorter than that delay: later delays are
    // drawn below it (the reference runs, on a busy machine, can be slower than these).
    const double delay = std::uniform_real_distribution<double>(0.0, 1.1 * seconds)(random);
    const pid_t pid = spawnGlint(job.args);
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    ::kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    killedBeforeEnd += WIFSIGNALED(status) ? 1 : 0;  // else it had finished
    if (!WIFSIGNALED(status)) seconds = std::min(seconds, delay);
    // What is there is complete: a reference file, byte for byte, or a temporary.
    for (const auto& [name, bytes] : snapshot(job.out)) {
      if (isTemporary(name)) continue;
      const auto ref = reference.find(name);
      ASSERT_NE(ref, reference.end()) << "round " << round << " (" << delay << " s): unexpected file " << name;
      const bool variable = std::find(job.variable.begin(), job.variable.end(), name) != job.variable.end();
      if (!variable) {
        EXPECT_EQ(bytes.size(), ref->second.size()) << "round " << round << " (" << delay << " s): " << name;
        EXPECT_TRUE(bytes == ref->second) << "round " << round << " (" << delay << " s): partial or different " << name;
      } else {
        // Whole even when its bytes vary: a page ends with its closing tag, JSON with '}'.
        const std::size_t last = bytes.find_last_not_of(" \n");
        ASSERT_NE(last, std::string::npos) << name << " is empty";
        EXPECT_TRUE(name.ends_with(".html") ? bytes.ends_with("</html>\n") || bytes.ends_with("</html>") : bytes[last] == '}')
            << "round " << round << ": partial " << name;
      }
    }
  }
  EXPECT_GT(killedBeforeEnd, rounds / 3) << "the delays should catch most runs while they work (seed " << seed << ")";
  // The next complete run removes what the killed ones left.
  runToEnd(job.args);
  for (const auto& [name, bytes] : snapshot(job.out)) {
    EXPECT_FALSE(isTemporary(name)) << "a killed run's temporary survived the next run: " << name;
  }
  for (const auto& [path, bytes] : inputs) EXPECT_TRUE(readBytes(path) == bytes) << "input changed: " << path;
  std::printf("[figure] %s: %d kills over %.2f s runs, %d before the end (seed %u)\n", job.args.c_str(), rounds,
              seconds, killedBeforeEnd, seed);
}

constexpr int kRounds = 12;
constexpr unsigned kSeed = 20261123;

constexpr auto q = glint::testing::shellQuote;  // a path as one shell word

}  // namespace

TEST(KillNine, BakeLeavesNoPartialMap) {
  const fs::path d = glint::testing::freshDir("kill", "bake");
  fs::create_directories(d / "out");
  bake::writeObj(makeTorus(1.0f, 0.35f, 24, 12), d / "low.obj");
  bake::writeObj(bake::makeStuddedTorus({.segments = 256, .sides = 128}), d / "high.obj");
  killRepeatedly({.args = "bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " --size 512x512 --max-front 0.06 --max-rear 0.06 -q -o " +
                          q(d / "out" / "map.png"),
                  .out = d / "out",
                  .inputs = {d / "low.obj", d / "high.obj"}},
                 kRounds, kSeed);
}

TEST(KillNine, CutLeavesNoPartialMeshes) {
  const fs::path d = glint::testing::freshDir("kill", "cut");
  fs::create_directories(d / "out");
  const MachineRoomOptions room{.modules = 4};
  bake::writeObj(makeMachineRoom(room), d / "room.obj");
  const auto lights = machineRoomLights(room);
  const auto light = [](vec3 p) { return fmt::format("{},{},{}", p.x, p.y, p.z); };
  killRepeatedly({.args = "cut " + q(d / "room.obj") + " --light " + light(lights[0]) + " --light " + light(lights[1]) +
                          " -q -o " + q(d / "out" / "room.glb") + " -o " + q(d / "out" / "room.ply"),
                  .out = d / "out",
                  .inputs = {d / "room.obj"}},
                 kRounds, kSeed + 1);
}

TEST(KillNine, GalleryLeavesOnlyWholeFiles) {
  const fs::path d = glint::testing::freshDir("kill", "gallery");
  // Frame times are measured (--repeats): the page and its JSON differ run to run; they
  // must still be whole files. The pictures are deterministic, byte for byte.
  killRepeatedly({.args = "gallery --filter basics/ --size 160x120 --repeats 1 -o " + q(d / "out"),
                  .out = d / "out",
                  .variable = {"index.html", "gallery.json"}},
                 kRounds, kSeed + 2);
}

TEST(KillNine, PostLeavesNoPartialImageOrVideo) {
  const fs::path d = glint::testing::freshDir("kill", "post");
  fs::create_directories(d / "out");
  // The inputs, made by glint post itself from FFmpeg's test pattern.
  const auto made = glint::testing::runGlint("post --input lavfi:testsrc2=size=320x240:rate=25:duration=2 --codec ffv1 -q -o " +
                                             q(d / "clip.mkv"));
  ASSERT_EQ(made.status, 0) << made.output;
  const auto still = glint::testing::runGlint("post --input lavfi:testsrc2=size=640x480 --frames 0:1 -q -o " + q(d / "photo.png"));
  ASSERT_EQ(still.status, 0) << still.output;
  killRepeatedly({.args = "post " + q(d / "photo.png") + " -e kuwahara -e edges -q -o " + q(d / "out" / "photo.png"),
                  .out = d / "out",
                  .inputs = {d / "photo.png"}},
                 kRounds, kSeed + 3);
  fs::remove_all(d / "out");
  fs::create_directories(d / "out");
  killRepeatedly({.args = "post " + q(d / "clip.mkv") + " -e sepia --codec ffv1 -q -o " + q(d / "out" / "clip.mkv"),
                  .out = d / "out",
                  .inputs = {d / "clip.mkv"}},
                 kRounds, kSeed + 4);
}
