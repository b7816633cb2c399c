// The promise itself (docs/reliability.md, "Nothing lost"): every subcommand that writes
// files, run with each of its output paths equal to each of its inputs, and with two of its
// outputs equal, refuses before any work (one line, exit 2) and leaves every input's bytes
// as they were; run into existing outputs with an input that fails, it leaves those files
// as they were too. Before the check existed, post re-encoded its input in place, --json
// replaced the input video, cut and normalmap overwrote their inputs and bake wrote two
// maps to one path.
#include "support/cli.h"

#include "glint/bake/samples.h"
#include "glint/mesh/mesh.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::oneLine;
using glint::testing::readBytes;
using glint::testing::runGlint;

namespace {

/// A command line with {name} for each input file and {0}, {1}, ... for its outputs.
struct Command {
  std::string label;
  std::string args;
  std::vector<std::string> inputs;   ///< the input files' names, as in args
  std::vector<std::string> outputs;  ///< the outputs' default names, for {0}, {1}, ...
};

class Promise : public ::testing::Test {
protected:
  fs::path d;
  std::map<std::string, std::string> original;  // input name → bytes

  // Each test its own inputs: ctest runs the tests as parallel processes.
  void SetUp() override {
    d = glint::testing::freshDir("promise", ::testing::UnitTest::GetInstance()->current_test_info()->name());
    const auto make = [](const std::string& args) {
      const auto r = runGlint("-q " + args);
      ASSERT_EQ(r.status, 0) << args << ": " << r.output;
    };
    make("post --input lavfi:testsrc2=size=64x48 --frames 0:1 -o " + (d / "photo.png").string());
    make("post --input lavfi:testsrc2=size=64x48:rate=24:duration=1 --codec ffv1 -o " + (d / "clip.mkv").string());
    make("post " + (d / "clip.mkv").string() + " --frames 0:12 --codec ffv1 -o " + (d / "part1.mkv").string());
    make("post " + (d / "clip.mkv").string() + " --frames 12: --codec ffv1 -o " + (d / "part2.mkv").string());
    bake::writeObj(makeTorus(1.0f, 0.35f, 16, 8), d / "low.obj");
    bake::writeObj(bake::makeStuddedTorus({.segments = 48, .sides = 24}), d / "high.obj");
    bake::writeObj(makeTorus(1.0f, 0.35f, 16, 8), d / "room.obj");
    make("cut " + (d / "room.obj").string() + " --light 0,3,0 --shard 1/2 -o " + (d / "s1.shard").string());
    make("cut " + (d / "room.obj").string() + " --light 0,3,0 --shard 2/2 -o " + (d / "s2.shard").string());
    for (const char* name : {"photo.png", "clip.mkv", "part1.mkv", "part2.mkv", "low.obj", "high.obj", "room.obj",
                             "s1.shard", "s2.shard"}) {
      original[name] = readBytes(d / name);
      ASSERT_FALSE(original[name].empty()) << name;
    }
  }

  std::vector<Command> commands() const {
    return {
        {"post image", "post {photo.png} -e sepia -o {0} --json {1}", {"photo.png"}, {"out.png", "r.json"}},
        {"post video", "post {clip.mkv} -e sepia --codec ffv1 -o {0} --json {1}", {"clip.mkv"}, {"out.mkv", "r.json"}},
        {"post --concat", "post --concat {part1.mkv} {part2.mkv} -o {0} --json {1}", {"part1.mkv", "part2.mkv"},
         {"whole.mkv", "r.json"}},
        {"cut", "cut {room.obj} --light 0,3,0 -o {0} -o {1} --json {2}", {"room.obj"}, {"cut.glb", "cut.ply", "r.json"}},
        {"cut --shard", "cut {room.obj} --light 0,3,0 --shard 1/2 -o {0} --json {1}", {"room.obj"},
         {"new.shard", "r.json"}},
        {"cut --merge", "cut {room.obj} --light 0,3,0 --merge {s1.shard} {s2.shard} -o {0} --json {1}",
         {"room.obj", "s1.shard", "s2.shard"}, {"merged.glb", "r.json"}},
        {"bake", "bake {low.obj} {high.obj} --size 32x32 -o {0} --ao {1} --height {2} --miss-mask {3} --bent-normal {4} "
                 "--thickness {5} --position {6} --opacity {7} --ao-samples 2 --json {8}",
         {"low.obj", "high.obj"}, {"n.png", "ao.png", "h.png", "miss.png", "bent.png", "thick.png", "pos.png", "alpha.png", "r.json"}},
        {"normalmap", "normalmap {photo.png} -o {0}", {"photo.png"}, {"nm.png"}},
    };
  }

  /// The command line with inputs in place and output k as `outputs[k]`.
  std::string line(const Command& c, const std::vector<std::string>& outputs) const {
    std::string args = c.args;
    for (const std::string& in : c.inputs) {
      for (std::size_t at; (at = args.find("{" + in + "}")) != std::string::npos;)
        args.replace(at, in.size() + 2, (d / in).string());
    }
    for (std::size_t k = 0; k < outputs.size(); ++k) {
      const std::string slot = "{" + std::to_string(k) + "}";
      args.replace(args.find(slot), slot.size(), outputs[k]);
    }
    return args;
  }

  std::vector<std::string> defaults(const Command& c) const {
    std::vector<std::string> out;
    for (const std::string& name : c.outputs) out.push_back((d / "out" / name).string());
    return out;
  }

  void expectInputsUnchanged(const std::string& what) const {
    for (const auto& [name, bytes] : original) EXPECT_TRUE(readBytes(d / name) == bytes) << what << ": " << name << " changed";
  }
};

}  // namespace

TEST_F(Promise, NoOutputIsEverAnInputByAnyNameOrAnotherOutput) {
  fs::create_directories(d / "out");
  fs::create_hard_link(d / "clip.mkv", d / "clip-link.mkv");
  int runs = 0;
  for (const Command& c : commands()) {
    for (std::size_t k = 0; k < c.outputs.size(); ++k) {
      for (const std::string& in : c.inputs) {
        // The input's own name, another spelling of it, and (for the video) a hard link to it.
        std::vector<std::string> spellings{(d / in).string(), (d / "out" / ".." / in).string()};
        for (const std::string& same : spellings) {
          std::vector<std::string> outputs = defaults(c);
          outputs[k] = same;
          const auto r = runGlint(line(c, outputs));
          ++runs;
          EXPECT_EQ(r.status, 2) << c.label << " with output " << k << " = " << same << ": " << r.output;
          EXPECT_TRUE(oneLine(r.output)) << c.label << ": " << r.output;
          EXPECT_NE(r.output.find("would destroy the input"), std::string::npos) << c.label << ": " << r.output;
          expectInputsUnchanged(c.label);
        }
      }
      for (std::size_t j = k + 1; j < c.outputs.size(); ++j) {
        std::vector<std::string> outputs = defaults(c);
        outputs[j] = outputs[k];
        const auto r = runGlint(line(c, outputs));
        ++runs;
        EXPECT_EQ(r.status, 2) << c.label << " with outputs " << k << " and " << j << " equal: " << r.output;
        EXPECT_NE(r.output.find("are the same file"), std::string::npos) << c.label << ": " << r.output;
      }
    }
    EXPECT_TRUE(fs::is_empty(d / "out")) << c.label << " wrote something after refusing";
  }
  // A hard link is the same file under another name.
  const auto link = runGlint("post " + (d / "clip.mkv").string() + " -e sepia --codec ffv1 -o " +
                             (d / "clip-link.mkv").string());
  EXPECT_EQ(link.status, 2) << link.output;
  expectInputsUnchanged("hard link");
  fs::remove(d / "clip-link.mkv");
  EXPECT_GT(runs, 40);
}

TEST_F(Promise, AFailedRunLeavesExistingOutputsAsTheyWere) {
  const fs::path out = d / "existing";
  fs::create_directories(out);
  // Inputs that fail: a corrupt file of each kind, an empty frame range.
  std::ofstream(out / "bad.png") << "not a PNG at all";
  std::ofstream(out / "bad.mkv") << "not a Matroska file";
  std::ofstream(out / "bad.obj") << "v 1 2\nf 1 2 9\n";
  for (const Command& c : commands()) {
    std::vector<std::string> outputs;
    for (const std::string& name : c.outputs) {
      const fs::path p = out / (c.label.substr(0, c.label.find(' ')) + "-" + name);
      std::ofstream(p) << "a good file from an earlier run: " << name;
      outputs.push_back(p.string());
    }
    std::string args = line(c, outputs);
    // The first input replaced by a corrupt one of its kind.
    const std::string first = (d / c.inputs.front()).string();
    const std::string ext = fs::path(first).extension().string();
    const fs::path bad = ext == ".obj" ? out / "bad.obj" : ext == ".png" ? out / "bad.png" : out / "bad.mkv";
    if (ext != ".shard") args.replace(args.find(first), first.size(), bad.string());
    const auto r = runGlint(args);
    EXPECT_NE(r.status, 0) << c.label << ": " << args << "\n" << r.output;
    EXPECT_TRUE(oneLine(r.output)) << c.label << ": " << r.output;
    for (std::size_t k = 0; k < outputs.size(); ++k) {
      EXPECT_EQ(readBytes(outputs[k]), "a good file from an earlier run: " + c.outputs[k]) << c.label << ": " << outputs[k];
    }
  }
  // A video with no frame in range replaces nothing either.
  std::ofstream(out / "keep.mkv") << "keep";
  const auto empty = runGlint("post " + (d / "clip.mkv").string() + " --frames 100: -e sepia --codec ffv1 -o " +
                              (out / "keep.mkv").string());
  EXPECT_EQ(empty.status, 3) << empty.output;
  EXPECT_EQ(readBytes(out / "keep.mkv"), "keep");
  expectInputsUnchanged("failed runs");
}

// Every failure a user met is one line with the documented exit status.
TEST_F(Promise, FailuresAreOneLineWithTheDocumentedExitStatus) {
  struct Case {
    std::string args;
    int status;
    std::string says;
  };
  const std::string photo = (d / "photo.png").string();
  for (const Case& c : std::vector<Case>{
           {"render basics/triangle -o " + (d / "x.xyz").string(), 2, "'.xyz' is not an image format"},
           {"normalmap " + photo + " -o " + (d / "x.xyz").string(), 2, "'.xyz' is not an image format"},
           {"post " + photo + " -e sepia -o " + (d / "x.xyz").string(), 2, "write an image too"},
           {"list zzz", 2, "no scene or variant name contains 'zzz'"},
           {"post " + photo + " -e sepia -o " + (d / "y.png").string() + " --max-memory 1K", 2,
            "more than --max-memory 1K (1 KiB) allows"},
           {"post " + photo + " -e sepia -o " + (d / "y.png").string() + " --threads -3", 2, "'-3' is not 0"},
           {"bake " + (d / "low.obj").string() + " " + (d / "high.obj").string() + " -o " + (d / "y.png").string() +
                " --max-front 1e99", 2, "--max-front must be a distance"},
       }) {
    const auto r = runGlint(c.args);
    EXPECT_EQ(r.status, c.status) << c.args << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << ": " << r.output;
  }
  // The usage line names the command as a user types it, not the binary's path.
  const auto help = runGlint("post --help");
  EXPECT_NE(help.output.find("Usage: glint post"), std::string::npos) << help.output.substr(0, 300);
  EXPECT_EQ(help.output.find(GLINT_EXE), std::string::npos);
}
