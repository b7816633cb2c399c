// `glint cut` as a user runs it (issue 13, items 7 and 8): outputs and the report,
// byte-identical output whatever --threads, shards and merge, Ctrl-C, and bad input:
// one-line errors, the documented exit status, and no file left behind.
#include "glint/cut/output.h"
#include "glint/mesh/adjacency.h"
#include "glint/mesh/machine_room.h"
#include "glint/mesh/mesh.h"

#include "support/cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::fileCount;
using glint::testing::oneLine;
using glint::testing::runGlint;

namespace {

fs::path dir(const char* name) { return glint::testing::freshDir("cut-cli", name); }
constexpr auto q = glint::testing::shellQuote;  // a path as one shell word

/// OBJ with normals (so loading it warns about nothing).
void writeObj(const Mesh& m, const fs::path& path) {
  std::ofstream out(path);
  out.precision(9);
  for (const vec3& p : m.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const vec3& n : m.normals) out << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    out << 'f';
    for (std::size_t k = 0; k < 3; ++k) out << ' ' << m.indices[i + k] + 1 << "//" << m.indices[i + k] + 1;
    out << '\n';
  }
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A small stage (one module) as OBJ in d / "stage.obj".
fs::path stage(const fs::path& d, int modules = 1) {
  writeObj(makeMachineRoom({.modules = modules}), d / "stage.obj");
  return d / "stage.obj";
}

constexpr const char* kLights = " --light -1.1,10.9,2.2,key --light 2.4,7.1,0.6,fill";

}  // namespace

TEST(CutCli, WritesTheOutputsAndTheReportAndNothingElse) {
  const auto d = dir("ok");
  const auto in = stage(d);
  fs::create_directories(d / "out");
  const auto r = runGlint("cut " + q(in) + " -o " + q(d / "out/cut.glb") + " -o " + q(d / "out/cut.ply") + kLights +
                          " --json " + q(d / "out/report.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(fileCount(d / "out"), 3u);  // no temporaries
  std::ifstream json(d / "out/report.json");
  const auto report = nlohmann::json::parse(json);
  EXPECT_EQ(report["tool"], "cut");
  const Mesh input = loadMesh(in);
  EXPECT_EQ(report["input_triangles"], input.triangleCount());
  EXPECT_GT(report["output_polygons"].get<double>(), double(input.triangleCount()));
  ASSERT_EQ(report["per_light"].size(), 2u);
  EXPECT_EQ(report["per_light"][0]["name"], "key");
  EXPECT_GT(report["per_light"][0]["shadowed_polygons"].get<double>(), 0.0);
  EXPECT_GT(report["per_light"][1]["lit_area"].get<double>(), 0.0);
  // Both files load as meshes; the PLY keeps its masks per face, every pipe stays closed.
  const Mesh ply = loadMesh(d / "out/cut.ply");
  const Mesh glb = loadMesh(d / "out/cut.glb");
  EXPECT_EQ(cut::loadPlyMasks(d / "out/cut.ply").size(), report["output_polygons"].get<std::size_t>());
  EXPECT_EQ(glb.triangleCount(), report["output_triangles"].get<std::size_t>());
  // Assimp triangulates the PLY's polygons itself (dropping what it finds degenerate).
  EXPECT_LE(ply.triangleCount(), report["output_triangles"].get<std::size_t>());
  EXPECT_GE(ply.triangleCount(), report["output_polygons"].get<std::size_t>());
  const auto lights = cut::loadGltfLights(d / "out/cut.glb");
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_EQ(lights[0].name, "key");
  EXPECT_NEAR(lights[1].position.x, 2.4f, 1e-6f);
}

TEST(CutCli, OutputIsTheSameBytesWhateverTheThreads) {
  const auto d = dir("threads");
  const auto in = stage(d);
  for (const char* t : {"1", "2"}) {
    const auto r = runGlint("-q cut " + q(in) + " -o " + q(d / (std::string("t") + t + ".glb")) + " -o " +
                            q(d / (std::string("t") + t + ".ply")) + kLights + " --threads " + t);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  EXPECT_EQ(bytes(d / "t1.glb"), bytes(d / "t2.glb"));
  EXPECT_EQ(bytes(d / "t1.ply"), bytes(d / "t2.ply"));
  EXPECT_GT(bytes(d / "t1.ply").size(), 100000u);
}

TEST(CutCli, ShardsMergeToTheSameFile) {
  const auto d = dir("shards");
  const auto in = stage(d);
  ASSERT_EQ(runGlint("-q cut " + q(in) + " -o " + q(d / "whole.ply") + kLights).status, 0);
  std::string parts;
  for (int i = 1; i <= 3; ++i) {
    const auto part = d / ("part" + std::to_string(i) + ".shard");
    const auto r = runGlint("-q cut " + q(in) + kLights + " --shard " + std::to_string(i) + "/3 -o " + q(part));
    ASSERT_EQ(r.status, 0) << r.output;
    parts += " " + q(part);
  }
  const auto r = runGlint("-q cut " + q(in) + " --merge" + parts + " -o " + q(d / "merged.ply"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(bytes(d / "whole.ply"), bytes(d / "merged.ply"));
  // One shard short: an error, and no output.
  const auto missing = runGlint("-q cut " + q(in) + " --merge " + q(d / "part1.shard") + " " + q(d / "part3.shard") +
                                " -o " + q(d / "bad.ply"));
  EXPECT_EQ(missing.status, 3) << missing.output;
  EXPECT_TRUE(oneLine(missing.output)) << missing.output;
  EXPECT_NE(missing.output.find("shard 2/3 is missing"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(d / "bad.ply"));
  // Lights other than the shards': a usage error, and no output.
  const auto moved = runGlint("-q cut " + q(in) + " --light -1.1,10.9,2.3 --light 2.4,7.1,0.6 --merge" + parts + " -o " +
                              q(d / "bad.ply"));
  EXPECT_EQ(moved.status, 2) << moved.output;
  EXPECT_TRUE(oneLine(moved.output)) << moved.output;
  EXPECT_NE(moved.output.find("--light differs"), std::string::npos) << moved.output;
  EXPECT_FALSE(fs::exists(d / "bad.ply"));
}

TEST(CutCli, LightsComeFromTheGltfScene) {
  const auto d = dir("gltf-lights");
  Mesh scene = makeCube(1.0f);
  scene.transform(glm::translate(mat4(1.0f), vec3(0.0f, 1.5f, 0.0f)));
  scene.append(makeGrid(8, 8, 6.0f));
  writeObj(scene, d / "scene.obj");
  const auto in = d / "scene.obj";
  ASSERT_EQ(runGlint("-q cut " + q(in) + " -o " + q(d / "lit.glb") + kLights).status, 0);
  // The written glTF carries its lights: cutting it again needs no --light.
  const auto r = runGlint("cut " + q(d / "lit.glb") + " -o " + q(d / "again.ply") + " --json -");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"name\": \"fill\""), std::string::npos) << r.output;
}

TEST(CutCli, BadInputIsAOneLineErrorAndLeavesNothing) {
  const auto d = dir("bad");
  const auto in = stage(d);
  std::ofstream(d / "empty.obj") << "# nothing\n";
  std::ofstream(d / "nan.obj") << "v 0 0 0\nv 1 0 0\nv 0 1e999 1\nvn 0 1 0\nf 1//1 2//1 3//1\n";
  std::ofstream(d / "garbage.ply") << "ply\nthis is not a mesh\n";
  struct Case {
    std::string args;
    int status;
    std::string says;
  };
  const std::vector<Case> cases = {
      {q(d / "missing.obj") + " -o " + q(d / "o.ply") + kLights, 3, "missing.obj"},
      {q(d / "empty.obj") + " -o " + q(d / "o.ply") + kLights, 3, "empty.obj"},
      {q(d / "nan.obj") + " -o " + q(d / "o.ply") + kLights, 3, ""},
      {q(d / "garbage.ply") + " -o " + q(d / "o.ply") + kLights, 3, "garbage.ply"},
      {q(in) + " -o " + q(d / "nodir/o.ply") + kLights, 4, "nodir"},
      {q(in) + " -o " + q(d / "o.obj") + kLights, 2, ".glb, .gltf or .ply"},
      {q(in) + " -o " + q(d / "o.ply"), 2, "no lights"},
      {q(in) + " -o " + q(d / "o.ply") + " --light 1,2", 2, "--light"},
      {q(in) + " -o " + q(d / "o.ply") + " --light 1,2,inf", 2, "--light"},
      {q(in) + " -o " + q(d / "o.ply") + kLights + " --shard 3/2", 2, "--shard"},
      // Strict: no blanks or signs around the numbers (sscanf took " 1/2"), nothing after them.
      {q(in) + " -o " + q(d / "o.ply") + kLights + " --shard ' 1/2'", 2, "--shard must be i/n"},
      {q(in) + " -o " + q(d / "o.ply") + kLights + " --shard 1/2x", 2, "--shard must be i/n"},
      {q(in) + " -o " + q(d / "o.ply") + kLights + " --shard +1/2", 2, "--shard must be i/n"},
      {q(in) + " -o " + q(d / "o.ply") + " --merge " + q(d / "garbage.ply"), 3, "not a glint cut shard"},
  };
  for (const Case& c : cases) {
    const auto r = runGlint("-q cut " + c.args);
    EXPECT_EQ(r.status, c.status) << c.args << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(d / "o.ply"));
  EXPECT_EQ(fileCount(d), 4u);  // the inputs only
}

TEST(CutCli, ALightOnASurfaceIsAWarning) {
  const auto d = dir("light-on-floor");
  const auto in = stage(d);
  const auto r = runGlint("-q cut " + q(in) + " -o " + q(d / "o.ply") + " --light 0.37,0,0.41,onfloor");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("'onfloor' lies on a surface"), std::string::npos) << r.output;
}

TEST(CutCli, CtrlCLeavesNoPartialFile) {
  const auto d = dir("interrupt");
  const auto in = stage(d, 16);
  const fs::path out = d / "out";
  fs::create_directories(out);
  const std::string inPath = in.string(), glb = (out / "cut.glb").string(), json = (out / "r.json").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // Four lights: the cut takes several seconds even on a quiet machine, so the signal
    // below always arrives while it is loading or cutting.
    execl(GLINT_EXE, GLINT_EXE, "-q", "cut", inPath.c_str(), "-o", glb.c_str(), "--light", "-1,20,2", "--light",
          "6,18,-3", "--light", "-8,15,5", "--light", "3,22,9", "--json", json.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));  // loaded, cutting
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_EQ(fileCount(out), 0u);
}
