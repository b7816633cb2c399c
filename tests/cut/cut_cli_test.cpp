// `glint cut` as a user runs it (issue 13, items 7 and 8): outputs and the report,
// byte-identical output whatever --threads, shards and merge, Ctrl-C, and bad input:
// one-line errors, the documented exit status, and no file left behind. Issue 21: the
// memory estimate, warnings (grazing, the loader's, none about normals), exact
// coordinates, glTF extras.
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/cut/output.h"
#include "glint/mesh/adjacency.h"
#include "glint/pipedream/machine_room.h"
#include "glint/mesh/mesh.h"

#include "support/cli.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

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
  EXPECT_GT(report["pieces_before_merge"].get<double>(), double(input.triangleCount()));  // shadows were cut in
  EXPECT_GT(report["output_polygons"].get<double>(), 0.0);
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

// glTF indices ("scene", a node's "light") are non-negative integers. A fraction, a negative
// or a number past 2^64 is the file's error, not a C++ cast (undefined past size_t's range:
// fuzz/regressions/cut_files/gltf-light-index-past-size-t).
TEST(CutCli, AGltfIndexThatIsNotAnIntegerIsAnInputError) {
  const auto d = dir("gltf-index");
  const auto gltf = [&](const std::string& scene, const std::string& light) {
    const fs::path file = d / "lights.gltf";
    std::ofstream(file) << R"({"asset":{"version":"2.0"},"extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","name":"key"}]}},)"
                        << R"("scene":)" << scene << R"(,"scenes":[{"nodes":[0]}],)"
                        << R"("nodes":[{"translation":[1,2,3],"extensions":{"KHR_lights_punctual":{"light":)" << light << "}}}]}";
    return file;
  };
  const auto lights = cut::loadGltfLights(gltf("0", "0"));
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_EQ(lights[0].name, "key");
  EXPECT_EQ(lights[0].position, vec3(1.0f, 2.0f, 3.0f));
  for (const auto& [scene, light] : std::vector<std::pair<std::string, std::string>>{
           {"0", "1e300"}, {"0", "-1"}, {"0", "0.5"}, {"0", "\"0\""}, {"1e30", "0"}, {"-2", "0"}, {"0.0", "0"}}) {
    try {
      (void)cut::loadGltfLights(gltf(scene, light));
      ADD_FAILURE() << "scene " << scene << ", light " << light << " was read";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
      EXPECT_NE(std::string(e.what()).find("not an index"), std::string::npos) << e.what();
    }
  }
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

// ------------------------------------------------------------------ issue 21

namespace {

/// The smallest scene a user tries first: an 8 × 8 floor at y = 0 (two triangles) and a
/// unit box floating above it (twelve), as OBJ without normals (as such files often are).
fs::path tinyScene(const fs::path& d) {
  std::ofstream(d / "tiny.obj") << "v -4 0 -4\nv 4 0 -4\nv 4 0 4\nv -4 0 4\n"
                                   "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
                                   "v -0.5 2 -0.5\nv 0.5 2 -0.5\nv 0.5 2 0.5\nv -0.5 2 0.5\n"
                                   "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 9 12 11\nf 9 11 10\nf 5 9 10\n"
                                   "f 5 10 6\nf 6 10 11\nf 6 11 7\nf 7 11 12\nf 7 12 8\nf 8 12 9\nf 8 9 5\n";
  return d / "tiny.obj";
}

/// The JSON report printed by `--json -` after whatever else the run printed.
nlohmann::json reportIn(const std::string& output) {
  const std::size_t start = output.find("\n{");
  return nlohmann::json::parse(start == std::string::npos ? output : output.substr(start + 1));
}

/// Whether a report's `warnings` list holds `warning`.
bool listed(const nlohmann::json& warnings, const std::string& warning) {
  return std::find(warnings.begin(), warnings.end(), warning) != warnings.end();
}

/// The lines the run printed as "warning: ...", without that prefix.
std::vector<std::string> printedWarnings(const std::string& output) {
  std::vector<std::string> out;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("warning: ", 0) == 0) out.push_back(line.substr(9));
  return out;
}

}  // namespace

// The estimate followed measurement: 200 MiB was its floor, so a 14-triangle scene (19 MiB
// measured) was refused under --max-memory 100M.
TEST(CutCli, ATinySceneFitsATinyMemoryLimit) {
  const auto d = dir("tiny-memory");
  const auto r = runGlint("-q cut " + q(tinyScene(d)) + " -o " + q(d / "o.ply") + " --light 0.3,5,0.2 --max-memory 100M --json -");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto report = reportIn(r.output);
  EXPECT_LE(report["memory_estimate_mib"].get<double>(), 100.0) << report.dump();
  if (!glint::testing::kAddressSanitizer) {  // ASan's shadow memory inflates the peak (make sanitize)
    EXPECT_GE(report["memory_estimate_mib"].get<double>(), report["peak_memory_mib"].get<double>()) << report.dump();
  }
}

TEST(CutCli, TheMemoryEstimateCoversTheMeasuredPeak) {
  const auto d = dir("memory");
  const auto in = stage(d, 4);  // 36k triangles
  // Two threads, as measured (the estimate grows with the threads; docs/cut.md, "Memory").
  const auto r = runGlint("-q cut " + q(in) + " -o " + q(d / "o.glb") + " -o " + q(d / "o.ply") + kLights +
                          " --threads 2 --json -");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto report = reportIn(r.output);
  const double estimate = report["memory_estimate_mib"].get<double>(), peak = report["peak_memory_mib"].get<double>();
  std::printf("[ memory   ] %zu triangles, 2 lights: estimate %.0f MiB, peak %.0f MiB\n",
              report["input_triangles"].get<std::size_t>(), estimate, peak);
  if (glint::testing::kAddressSanitizer) GTEST_SKIP() << "under ASan the peak includes its shadow memory and quarantine";
  EXPECT_GE(estimate, peak);
  EXPECT_LE(estimate, 2.5 * peak) << "an upper bound, with a modest margin";
}

// docs/cut.md said grazing triangles were warned about; they were only counted.
TEST(CutCli, GrazingTrianglesAreWarnedAbout) {
  const auto d = dir("grazing");
  // The light lies in the plane of the box's top (y = 2), outside the box: the top's two
  // triangles graze it.
  const auto r = runGlint("cut " + q(tinyScene(d)) + " -o " + q(d / "o.ply") + " --light 3,2,3,lamp --json -");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto report = reportIn(r.output);
  EXPECT_EQ(report["per_light"][0]["grazing_triangles"], 2);
  const auto printed = printedWarnings(r.output);
  std::vector<std::string> grazing;
  for (const auto& w : printed)
    if (w.find("graze") != std::string::npos) grazing.push_back(w);
  ASSERT_EQ(grazing.size(), 1u) << r.output;
  EXPECT_NE(grazing[0].find("2 triangles graze a light (2 for 'lamp')"), std::string::npos) << grazing[0];
  EXPECT_NE(grazing[0].find("the light lies in their plane"), std::string::npos) << grazing[0];
  EXPECT_TRUE(listed(report["warnings"], grazing[0])) << report["warnings"].dump();
  // No grazing, no such warning.
  const auto none = runGlint("cut " + q(tinyScene(d)) + " -o " + q(d / "o.ply") + " --light 3,5,3");
  ASSERT_EQ(none.status, 0) << none.output;
  EXPECT_EQ(none.output.find("graze"), std::string::npos) << none.output;
}

// Every warning a cut prints is in its report: the loader's warning was printed, not listed.
TEST(CutCli, EveryPrintedWarningIsInTheReport) {
  const auto d = dir("warnings");
  // Without normals, with a zero-area triangle, a light on the floor and one grazing the box's top.
  std::ofstream(d / "odd.obj") << "v -4 0 -4\nv 4 0 -4\nv 4 0 4\nv -4 0 4\n"
                                  "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
                                  "v -0.5 2 -0.5\nv 0.5 2 -0.5\nv 0.5 2 0.5\nv -0.5 2 0.5\n"
                                  "v 1 0.5 1\nv 2 0.5 1\nv 3 0.5 1\n"
                                  "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 9 12 11\nf 9 11 10\nf 5 9 10\n"
                                  "f 5 10 6\nf 6 10 11\nf 6 11 7\nf 7 11 12\nf 7 12 8\nf 8 12 9\nf 8 9 5\nf 13 14 15\n";
  for (const std::string format : {"obj", "ply"}) {
    const fs::path in = d / ("odd." + format);
    if (format == "ply") {  // the same scene as ASCII PLY, read by the PLY fast path
      const Mesh m = loadMesh(d / "odd.obj", {.generateNormals = false});
      std::ofstream ply(in);
      ply << "ply\nformat ascii 1.0\nelement vertex " << m.positions.size() << "\nproperty float x\nproperty float y\n"
          << "property float z\nelement face " << m.triangleCount() << "\nproperty list uchar int vertex_indices\nend_header\n";
      for (const vec3& p : m.positions) ply << p.x << ' ' << p.y << ' ' << p.z << '\n';
      for (std::size_t i = 0; i < m.indices.size(); i += 3)
        ply << "3 " << m.indices[i] << ' ' << m.indices[i + 1] << ' ' << m.indices[i + 2] << '\n';
    }
    const auto r = runGlint("cut " + q(in) + " -o " + q(d / "o.glb") + " --light 2,0,-3,onfloor --light 3,2,3,grazer --json -");
    ASSERT_EQ(r.status, 0) << r.output;
    const auto report = reportIn(r.output);
    const auto printed = printedWarnings(r.output);
    EXPECT_GE(printed.size(), 3u) << r.output;  // the zero-area triangle, the light on the floor, grazing
    EXPECT_EQ(report["warnings"].size(), printed.size()) << r.output;
    for (std::string w : printed) {
      if (w.rfind("cut: ", 0) == 0) w = w.substr(5);  // the library's log prefix
      EXPECT_TRUE(listed(report["warnings"], w))
          << format << ": '" << w << "' printed but not in the report " << report["warnings"].dump();
    }
  }
}

// The route the loader's warnings take into the report: log::WarningCapture sees what it prints.
TEST(CutCli, TheLoadersWarningsAreCaptured) {
  const auto d = dir("capture");
  log::WarningCapture capture;
  const Mesh m = loadMesh(tinyScene(d));  // normals generated, and the warning printed
  EXPECT_TRUE(m.hasNormals());
  const auto warnings = capture.take();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("have no normals"), std::string::npos) << warnings[0];
  EXPECT_TRUE(capture.take().empty());
}

// The cutter needs positions only: it neither generates normals nor warns that there are none.
TEST(CutCli, NoWarningAboutNormalsACutDoesNotNeed) {
  const auto d = dir("loader-quiet");
  const auto obj = tinyScene(d);
  // An OBJ (fast path), the same as OFF (Assimp) and PLY.
  {
    const Mesh m = loadMesh(obj, {.generateNormals = false});
    EXPECT_FALSE(m.hasNormals());
    std::ofstream off(d / "tiny.off");
    off << "OFF\n" << m.positions.size() << ' ' << m.triangleCount() << " 0\n";
    for (const vec3& p : m.positions) off << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (std::size_t i = 0; i < m.indices.size(); i += 3)
      off << "3 " << m.indices[i] << ' ' << m.indices[i + 1] << ' ' << m.indices[i + 2] << '\n';
    std::ofstream ply(d / "tiny.ply");
    ply << "ply\nformat ascii 1.0\nelement vertex " << m.positions.size() << "\nproperty float x\nproperty float y\n"
        << "property float z\nelement face " << m.triangleCount() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const vec3& p : m.positions) ply << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (std::size_t i = 0; i < m.indices.size(); i += 3)
      ply << "3 " << m.indices[i] << ' ' << m.indices[i + 1] << ' ' << m.indices[i + 2] << '\n';
  }
  for (const fs::path& in : {obj, d / "tiny.off", d / "tiny.ply"}) {
    const auto r = runGlint("cut " + q(in) + " -o " + q(d / "o.ply") + " --light 0.3,5,0.2 --json -");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("normals"), std::string::npos) << in << ": " << r.output;
    EXPECT_EQ(r.output.find("warning: "), std::string::npos) << in << ": " << r.output;
    EXPECT_EQ(reportIn(r.output)["warnings"], nlohmann::json::array()) << in;
    EXPECT_EQ(reportIn(r.output)["input_triangles"], 14) << in;
    // Other users of the loader still get their normals, and the warning.
    log::WarningCapture capture;
    EXPECT_TRUE(loadMesh(in).hasNormals()) << in;
    EXPECT_FALSE(loadMesh(in, {.generateNormals = false}).hasNormals()) << in;
    EXPECT_EQ(capture.take().size(), 1u) << in;
  }
}

// A floor at y = 0 came out at y = −1.1e-16 (`glint mesh-info` showed it in the bounds).
TEST(CutCli, AFloorAtZeroStaysAtZero) {
  const auto d = dir("exact");
  const auto r = runGlint("-q cut " + q(tinyScene(d)) + " -o " + q(d / "o.ply") + " -o " + q(d / "o.glb") + " --light 0.3,5,0.2");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* out : {"o.ply", "o.glb"}) {
    const Mesh m = loadMesh(d / out, {.generateNormals = false});
    const Bounds b = m.bounds();
    EXPECT_EQ(b.min.y, 0.0f) << out;
    EXPECT_FALSE(std::signbit(b.min.y)) << out;
    EXPECT_EQ(b.max.y, 2.0f) << out;
    EXPECT_EQ(b.min.x, -4.0f) << out;
    EXPECT_EQ(b.max.z, 4.0f) << out;
    for (const vec3& p : m.positions) {
      // Every vertex is on the floor (y = 0) or on the box, whose faces are axis-aligned.
      const bool onFloor = p.y == 0.0f;
      const bool onBox = (p.x == -0.5f || p.x == 0.5f || p.y == 1.0f || p.y == 2.0f || p.z == -0.5f || p.z == 0.5f) &&
                         std::abs(p.x) <= 0.5f && std::abs(p.z) <= 0.5f && p.y >= 1.0f && p.y <= 2.0f;
      EXPECT_TRUE(onFloor || onBox) << out << ": (" << p.x << ", " << p.y << ", " << p.z << ")";
    }
  }
  const auto info = runGlint("mesh-info " + q(d / "o.ply"));
  EXPECT_NE(info.output.find("bounds:             (-4, 0, -4) .. (4, 2, 4)"), std::string::npos) << info.output;
}

// glTF extras: light_mask was written as a float (1.0) and lit_by as null instead of [].
TEST(CutCli, GltfExtrasAreAnIntegerMaskAndAListOfLights) {
  const auto d = dir("extras");
  const auto in = tinyScene(d);
  // 32 lights (all high above: the floor's far parts are lit by all, bit 31 included), and
  // the floor under the box shadowed for all of them (mask 0).
  std::string lights;
  for (int l = 0; l < 32; ++l) lights += fmt::format(" --light {},{},{},l{}", 0.01 * l, 30 + l, 0.02 * l, l);
  const auto r = runGlint("-q cut " + q(in) + " -o " + q(d / "o.glb") + " -o " + q(d / "o.gltf") + lights);
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* out : {"o.glb", "o.gltf"}) {
    const std::string file = bytes(d / out);
    std::string_view text = file;
    if (std::string(out) == "o.glb") {
      std::uint32_t header[5];
      ASSERT_GE(file.size(), sizeof header);
      std::memcpy(header, file.data(), sizeof header);
      EXPECT_EQ(header[0], 0x46546C67u);
      EXPECT_EQ(header[2], file.size()) << "the GLB's length";
      EXPECT_EQ(header[3] % 4, 0u);
      text = text.substr(20, header[3]);
    }
    const auto gltf = nlohmann::json::parse(text);
    const auto& primitives = gltf["meshes"][0]["primitives"];
    ASSERT_GE(primitives.size(), 2u) << out;
    bool none = false, all = false;
    for (const auto& p : primitives) {
      const auto& extras = p["extras"];
      ASSERT_TRUE(extras["light_mask"].is_number_unsigned()) << out << ": " << extras.dump();
      ASSERT_TRUE(extras["lit_by"].is_array()) << out << ": " << extras.dump();
      const std::uint32_t mask = extras["light_mask"].get<std::uint32_t>();
      EXPECT_EQ(extras["lit_by"].size(), std::size_t(std::popcount(mask))) << out << ": " << extras.dump();
      none = none || (mask == 0 && extras["lit_by"] == nlohmann::json::array());
      all = all || (mask == 0xFFFFFFFFu && extras["lit_by"][31] == "l31");
    }
    EXPECT_TRUE(none) << out << ": no primitive with mask 0 and lit_by []";
    EXPECT_TRUE(all) << out << ": no primitive lit by all 32 lights";
    // Still a glTF file Assimp reads, with every triangle.
    EXPECT_GT(loadMesh(d / out, {.generateNormals = false}).triangleCount(), 14u) << out;
  }
}
