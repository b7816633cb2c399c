// `glint bake` as a user runs it: outputs and formats, the JSON report, --quiet,
// determinism across --threads, Ctrl-C, and every kind of bad input (issue 6, item 11):
// one-line errors, the documented exit status, and no file left behind.
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include <glm/gtc/matrix_transform.hpp>

#include "support/cli.h"
#include "support/obj.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <array>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;

namespace {
using Run = glint::testing::CliRun;
using glint::testing::fileCount;
using glint::testing::oneLine;
using glint::testing::runGlint;
using glint::testing::runShell;
using glint::testing::writeObj;
using glint::testing::writeObjLines;


fs::path dir(const char* name) { return glint::testing::freshDir("bake-cli", name); }

/// A low/high sphere pair in `d`: low.obj, high.obj.
void writeSpheres(const fs::path& d) {
  writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  writeObj(makeUvSphere(1.0f, 64, 32), d / "high.obj");
}

constexpr auto q = glint::testing::shellQuote;  // a path as one shell word

/// Writes named parts as one OBJ: `o name`, `usemtl material` (from parts.mtl) per part.
void writeObjParts(const std::vector<std::tuple<std::string, std::string, Mesh>>& parts, const fs::path& path) {
  std::ofstream out(path);
  out << "mtllib parts.mtl\n";
  std::size_t base = 0;
  for (const auto& [name, material, m] : parts) {
    out << "o " << name << "\nusemtl " << material << '\n';
    writeObjLines(out, m, base);
    base += m.positions.size();
  }
  std::ofstream(path.parent_path() / "parts.mtl") << "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n";
}

Mesh placed(Mesh m, vec3 offset, float u0) {
  for (vec3& p : m.positions) p += offset;
  for (vec2& uv : m.uvs) uv = vec2(u0 + 0.02f + 0.46f * uv.x, 0.02f + 0.96f * uv.y);
  return m;
}

}  // namespace

TEST(BakeCli, WritesTheMapAndTheReportAndNothingElse) {
  const auto d = dir("ok");
  writeSpheres(d);
  fs::create_directories(d / "out");
  const auto out = d / "out";
  const auto r = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(out / "n.png") +
                          " --size 96x64 --samples 4 --ao " + q(out / "ao.png") + " --height " + q(out / "h.exr") +
                          " --miss-mask " + q(out / "miss.png") + " --json " + q(out / "report.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const Image n = loadImage(out / "n.png");
  EXPECT_EQ(n.width(), 96);
  EXPECT_EQ(n.height(), 64);
  EXPECT_EQ(n.type(), PixelType::U8);
  EXPECT_EQ(loadImage(out / "h.exr").type(), PixelType::F32);
  EXPECT_EQ(fileCount(out), 5u);  // no temporaries
  std::ifstream in(out / "report.json");
  const auto report = nlohmann::json::parse(in);  // throws (fails the test) on malformed JSON
  EXPECT_EQ(report["tool"], "bake");
  EXPECT_EQ(report["texels"], 6144);
  EXPECT_EQ(report["samples_per_texel"], 4);
  EXPECT_EQ(report["hit_ratio"], 1.0);
  EXPECT_EQ(report["misses"], 0);
  EXPECT_GT(report["rays"].get<double>(), 0.0);
  EXPECT_GE(report["threads"].get<int>(), 1);
  for (const char* phase : {"load", "prepare", "trace", "dilate", "write"}) {
    EXPECT_GE(report["seconds"][phase].get<double>(), 0.0) << phase;
    EXPECT_LE(report["seconds"][phase].get<double>(), report["seconds"]["total"].get<double>()) << phase;
  }
  EXPECT_GT(report["peak_memory_mib"].get<double>(), 1.0);
  EXPECT_TRUE(report["warnings"].is_array());
}

TEST(BakeCli, FormatsAndDepths) {
  const auto d = dir("formats");
  writeSpheres(d);
  const std::string meshes = q(d / "low.obj") + " " + q(d / "high.obj") + " --size 32x32 -q";
  struct Case {
    const char* file;
    const char* extra;
    PixelType type;
  };
  for (const Case& c : {Case{"a.png", "", PixelType::U8}, Case{"b.png", "--bits 16", PixelType::U16},
                        Case{"c.tga", "", PixelType::U8}, Case{"d.tif", "", PixelType::U16},
                        Case{"e.exr", "", PixelType::F32}}) {
    const auto r = runGlint("bake " + meshes + " -o " + q(d / c.file) + " " + c.extra);
    ASSERT_EQ(r.status, 0) << c.file << ": " << r.output;
    EXPECT_EQ(r.output, "") << "--quiet prints nothing on success";
    EXPECT_EQ(loadImage(d / c.file).type(), c.type) << c.file;
  }
  // Same bake, any format: the 16-bit and float maps agree with the 8-bit one within its step.
  const Image a = loadImage(d / "a.png"), b = loadImage(d / "b.png"), e = loadImage(d / "e.exr");
  EXPECT_LE(compareImages(a, b).maxAbs, 0.5 / 255 + 1e-6);
  EXPECT_LE(compareImages(a, e).maxAbs, 0.5 / 255 + 1e-6);
  // --directx flips green and nothing else.
  ASSERT_EQ(runGlint("bake " + meshes + " -o " + q(d / "dx.exr") + " --directx").status, 0);
  const Image dx = loadImage(d / "dx.exr");
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      EXPECT_FLOAT_EQ(dx.at(x, y, 0), e.at(x, y, 0));
      EXPECT_NEAR(dx.at(x, y, 1), 1.0f - e.at(x, y, 1), 1e-6f);
    }
  const auto bad = runGlint("bake " + meshes + " -o " + q(d / "f.tga") + " --bits 16");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_TRUE(oneLine(bad.output)) << bad.output;
}

TEST(BakeCli, SameBytesWhateverTheThreadCount) {
  const auto d = dir("threads");
  writeSpheres(d);
  const std::string meshes = q(d / "low.obj") + " " + q(d / "high.obj") + " --size 64x64 --samples 4 -q";
  ASSERT_EQ(runGlint("bake " + meshes + " -o " + q(d / "one.png") + " --threads 1").status, 0);
  ASSERT_EQ(runGlint("bake " + meshes + " -o " + q(d / "two.png") + " --threads 2").status, 0);
  std::ifstream a(d / "one.png", std::ios::binary), b(d / "two.png", std::ios::binary);
  const std::string bytesA((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  const std::string bytesB((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(bytesA.empty());
  EXPECT_TRUE(bytesA == bytesB);
}

TEST(BakeCli, HelpExplainsOptionsAndArtistNotes) {
  const auto r = runGlint("bake --help");
  EXPECT_EQ(r.status, 0);
  for (const char* text : {"--samples", "--max-rear", "--padding", "--height-detail", "--directx", "Shared normals",
                           "UV spacing", "MikkTSpace"}) {
    EXPECT_NE(r.output.find(text), std::string::npos) << text;
  }
}

TEST(BakeCli, BadInputIsOneLineAndLeavesNothing) {
  const auto d = dir("bad");
  writeSpheres(d);
  Mesh noUv = makeUvSphere(1.0f, 16, 8);
  noUv.uvs.clear();
  writeObj(noUv, d / "nouv.obj");
  { std::ofstream(d / "empty.obj") << "# nothing\nv 0 0 0\n"; }
  { std::ofstream(d / "corrupt.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n"; }
  Mesh nan = makeUvSphere(1.0f, 16, 8);
  nan.positions[5] = vec3(std::nanf(""));
  writeObj(nan, d / "nan.obj");
  const fs::path out = d / "out";
  fs::create_directories(out);
  const std::string low = q(d / "low.obj"), high = q(d / "high.obj"), o = " -o " + q(out / "n.png") + " --size 16x16";
  struct Case {
    std::string args;
    int status;
    const char* message;
  };
  const std::vector<Case> cases{
      {q(d / "nouv.obj") + " " + high + o, 3, "no UVs"},
      {q(d / "missing.obj") + " " + high + o, 3, "no such file"},
      {low + " " + q(d / "empty.obj") + o, 3, "empty.obj"},
      {low + " " + q(d / "corrupt.ply") + o, 3, "corrupt.ply"},
      {low + " " + q(d / "nan.obj") + o, 3, "not finite"},
      {low + " " + high + " -o " + q(d / "no-such-dir" / "n.png"), 4, "no-such-dir"},
      {low + " " + high + o + " --samples 5", 2, "square"},
      {low + " " + high + " -o " + q(out / "n.bmp"), 2, "unknown map format"},
      {low + " " + high + o + " --max-front far", 2, "--max-front"},
      {low + " " + high + o + " --height-detail " + q(d / "missing.png"), 3, "missing.png"},
  };
  for (const Case& c : cases) {
    const auto r = runGlint("bake " + c.args);
    EXPECT_EQ(r.status, c.status) << c.args << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
    EXPECT_EQ(fileCount(out), 0u) << c.args;
  }
}

TEST(BakeCli, WarningsStillBake) {
  const auto d = dir("warn");
  Mesh noNormals = makeUvSphere(1.0f, 16, 8);
  noNormals.normals.clear();
  writeObj(noNormals, d / "nonormals.obj");
  Mesh mirrored = makeUvSphere(1.0f, 16, 8);
  for (vec2& uv : mirrored.uvs) uv.x = uv.x < 0.5f ? uv.x : 1.0f - uv.x;
  writeObj(mirrored, d / "mirrored.obj");
  Mesh degenerate = makeUvSphere(1.0f, 16, 8);
  degenerate.indices.insert(degenerate.indices.end(), {3, 3, 4});
  writeObj(degenerate, d / "degenerate.obj");
  writeObj(makeUvSphere(1.0f, 64, 32), d / "high.obj");
  for (const auto& [file, warning] : std::vector<std::pair<const char*, const char*>>{
           {"nonormals.obj", "no normals"}, {"mirrored.obj", "mirrored UVs"}, {"degenerate.obj", "zero UV area"}}) {
    const auto r = runGlint("-q bake " + q(d / file) + " " + q(d / "high.obj") + " -o " + q(d / (std::string(file) + ".png")) +
                            " --size 32x32");
    EXPECT_EQ(r.status, 0) << file << ": " << r.output;
    EXPECT_NE(r.output.find(warning), std::string::npos) << file << ": " << r.output;
    EXPECT_TRUE(fs::exists(d / (std::string(file) + ".png"))) << file;
  }
}

TEST(BakeCli, ProgressBarOnATerminalSilenceWithQuiet) {
  // The shared tool plumbing (core/tool.h): a progress bar when stderr is a terminal (a
  // pseudo-terminal from util-linux's `script` here), nothing at all with -q.
  const auto d = dir("progress");
  writeSpheres(d);
  const std::string bake = std::string(GLINT_EXE) + " bake " + q(d / "low.obj") + " " + q(d / "high.obj") +
                           " --size 128x128 -o ";
  const auto onTerminal = [&](const std::string& args) {
    return runShell("script -qec " + q(bake + args) + " /dev/null");
  };
  const auto loud = onTerminal(q(d / "loud.png"));
  ASSERT_EQ(loud.status, 0) << loud.output;
  EXPECT_NE(loud.output.find("bake ["), std::string::npos) << loud.output;
  EXPECT_NE(loud.output.find("texels baked"), std::string::npos) << loud.output;
  const auto quiet = onTerminal(q(d / "quiet.png") + " -q");
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_EQ(quiet.output, "");
  // Not a terminal (a pipe, as in CI logs): no bar, just the summary line.
  const auto piped = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " --size 128x128 -o " +
                              q(d / "piped.png"));
  ASSERT_EQ(piped.status, 0) << piped.output;
  EXPECT_EQ(piped.output.find("bake ["), std::string::npos) << piped.output;
}

TEST(BakeCli, CtrlCOrSigtermLeavesNoPartialFile) {
  const auto d = dir("interrupt");
  writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  writeObj(makeUvSphere(1.0f, 128, 64), d / "high.obj");
  const fs::path out = d / "out";
  fs::create_directories(out);
  const std::string lowPath = (d / "low.obj").string(), highPath = (d / "high.obj").string(),
                    outPath = (out / "n.png").string();
  // Ctrl-C (SIGINT) and a scheduler cancelling the job (SIGTERM) are handled alike.
  for (const int signal : {SIGINT, SIGTERM}) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      execl(GLINT_EXE, GLINT_EXE, "-q", "bake", lowPath.c_str(), highPath.c_str(), "-o", outPath.c_str(), "--size",
            "2048x2048", "--samples", "64", static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1000));  // loading done, tracing
    kill(pid, signal);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "signal " << signal;
    EXPECT_EQ(WEXITSTATUS(status), 130) << "signal " << signal;
    EXPECT_EQ(fileCount(out), 0u) << "signal " << signal;
  }
}

// An inside-out high poly (winding and normals flipped, as an exporter with a mirrored
// transform makes it) used to bake a map pointing 100% inward without a word; now the
// bake warns, and the report counts the inward hits. A right-way-out one says nothing.
TEST(BakeCli, AnInsideOutHighPolyIsWarnedAbout) {
  const auto d = dir("inside-out");
  writeSpheres(d);
  Mesh flipped = makeUvSphere(1.0f, 64, 32);
  for (std::size_t i = 0; i < flipped.indices.size(); i += 3) std::swap(flipped.indices[i + 1], flipped.indices[i + 2]);
  for (vec3& n : flipped.normals) n = -n;
  writeObj(flipped, d / "flipped.obj");
  const auto bad = runGlint("-q bake " + q(d / "low.obj") + " " + q(d / "flipped.obj") + " -o " + q(d / "bad.png") +
                            " --size 32x32 --json " + q(d / "bad.json"));
  ASSERT_EQ(bad.status, 0) << bad.output;
  EXPECT_NE(bad.output.find("the high poly looks inside out"), std::string::npos) << bad.output;
  std::ifstream badReport(d / "bad.json");
  const auto report = nlohmann::json::parse(badReport);
  EXPECT_EQ(report["inward_hits"], report["hits"]);
  EXPECT_EQ(report["warnings"].size(), 1u) << report["warnings"];
  // normalmap --check agrees: the map points inward.
  const auto check = runGlint("normalmap --check " + q(d / "bad.png"));
  EXPECT_EQ(check.status, 3) << check.output;

  const auto good = runGlint("-q bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "good.png") +
                             " --size 32x32 --json " + q(d / "good.json"));
  ASSERT_EQ(good.status, 0) << good.output;
  EXPECT_EQ(good.output.find("inside out"), std::string::npos) << good.output;
  std::ifstream goodReport(d / "good.json");
  EXPECT_EQ(nlohmann::json::parse(goodReport)["inward_hits"], 0);
}

// ------------------------------------------------------------------ --batch (issue 22)

namespace {

/// Three small jobs in `d` sharing defaults, with overrides: job 1 another low poly, size
/// and --directx; job 2 more samples and an AO map. Paths in the file are relative to it.
constexpr const char* kBatch = R"({
  "defaults": {"size": "32x32", "samples": 1, "padding": 2, "max-front": "5%"},
  "bakes": [
    {"low": "low.obj", "high": "high.obj", "output": "a.png"},
    {"low": "low2.obj", "high": "high.obj", "output": "b.png", "size": "48x24", "directx": true, "front-first": false},
    {"low": "low.obj", "high": "high.obj", "output": "c.png", "samples": 4, "ao": "c_ao.png", "ao-samples": 4}
  ]
})";

void writeBatch(const fs::path& d, const std::string& json = kBatch) {
  writeSpheres(d);
  writeObj(makeUvSphere(1.0f, 12, 6), d / "low2.obj");
  std::ofstream(d / "jobs.json") << json;
}

/// The same three bakes as plain `glint bake` commands, writing into `out`.
void bakeOneByOne(const fs::path& d, const fs::path& out) {
  fs::create_directories(out);
  const std::string common = " --padding 2 --max-front 5% -q";
  for (const std::string& args :
       {q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(out / "a.png") + " --size 32x32 --samples 1" + common,
        q(d / "low2.obj") + " " + q(d / "high.obj") + " -o " + q(out / "b.png") + " --size 48x24 --samples 1 --directx" + common,
        q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(out / "c.png") + " --size 32x32 --samples 4 --ao " +
            q(out / "c_ao.png") + " --ao-samples 4" + common}) {
    const auto r = runGlint("bake " + args);
    ASSERT_EQ(r.status, 0) << args << ": " << r.output;
  }
}

std::string bytes(const fs::path& p) { return glint::testing::readBytes(p); }

}  // namespace

TEST(BakeCli, BatchGivesTheBytesOfSeparateBakes) {
  const auto d = dir("batch");
  writeBatch(d);
  bakeOneByOne(d, d / "separate");
  const auto r = runGlint("bake --batch " + q(d / "jobs.json") + " --json " + q(d / "report.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* file : {"a.png", "b.png", "c.png", "c_ao.png"}) {
    EXPECT_FALSE(bytes(d / file).empty()) << file;
    EXPECT_TRUE(bytes(d / file) == bytes(d / "separate" / file)) << file;
  }
  EXPECT_EQ(loadImage(d / "b.png").width(), 48);  // the job's size, not the default
  // Progress names the job, and a summary lists every job.
  EXPECT_NE(r.output.find("bake 2/3: job 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 jobs in"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 ok, 0 failed"), std::string::npos) << r.output;
  std::ifstream in(d / "report.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["tool"], "bake");
  ASSERT_EQ(report["jobs"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(report["jobs"][i]["job"], i);
    EXPECT_EQ(report["jobs"][i]["status"], "ok");
    EXPECT_GT(report["jobs"][i]["seconds"]["total"].get<double>(), 0.0);
  }
  EXPECT_EQ(report["jobs"][1]["output"], (d / "b.png").string());
  EXPECT_EQ(report["jobs"][2]["samples_per_texel"], 4);
  EXPECT_EQ(report["failed"], 0);
  // Every job bakes high.obj: read once (the bytes above are those of separate bakes), and
  // jobs 0 and 1 want the same BVH quality (few rays per triangle): built once.
  EXPECT_EQ(report["jobs"][0]["high_mesh_reused"], false);
  EXPECT_EQ(report["jobs"][1]["high_mesh_reused"], true);
  EXPECT_EQ(report["jobs"][2]["high_mesh_reused"], true);
  EXPECT_EQ(report["jobs"][1].value("bvh_reused", false), true);
  EXPECT_NE(r.output.find("high mesh reused from an earlier job"), std::string::npos) << r.output;
}

TEST(BakeCli, BatchJobRunsOnlyThatJob) {
  const auto d = dir("batch-job");
  writeBatch(d);
  bakeOneByOne(d, d / "separate");
  const auto r = runGlint("bake --batch " + q(d / "jobs.json") + " --job 1 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "") << "-q: nothing on success";
  EXPECT_TRUE(bytes(d / "b.png") == bytes(d / "separate" / "b.png"));
  for (const char* file : {"a.png", "c.png", "c_ao.png"}) EXPECT_FALSE(fs::exists(d / file)) << file;
}

TEST(BakeCli, BatchListPrintsTheEquivalentCommands) {
  const auto d = dir("batch-list");
  writeBatch(d);
  const auto list = runGlint("bake --batch " + q(d / "jobs.json") + " --list --threads 2");
  ASSERT_EQ(list.status, 0) << list.output;
  std::vector<std::string> lines;
  std::istringstream in(list.output);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u) << list.output;
  EXPECT_NE(lines[1].find("--size 48x24"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("--directx"), std::string::npos) << lines[1];
  EXPECT_EQ(lines[1].find("--front-first"), std::string::npos) << "false: the flag is left out: " << lines[1];
  EXPECT_NE(lines[1].find("--threads 2"), std::string::npos) << "command-line options apply to every job: " << lines[1];
  EXPECT_EQ(fileCount(d), 4u) << "--list runs nothing";
  // Run as commands, the lines give the batch's files.
  std::map<std::string, std::string> listed;
  for (const std::string& line : lines) {
    ASSERT_EQ(line.rfind("glint bake ", 0), 0u) << line;
    const auto r = runShell(std::string(GLINT_EXE) + line.substr(5) + " -q");
    ASSERT_EQ(r.status, 0) << line << ": " << r.output;
  }
  for (const char* file : {"a.png", "b.png", "c.png", "c_ao.png"}) {
    listed[file] = bytes(d / file);
    EXPECT_FALSE(listed[file].empty()) << file;
    fs::remove(d / file);
  }
  ASSERT_EQ(runGlint("bake --batch " + q(d / "jobs.json") + " -q").status, 0);
  for (const auto& [file, contents] : listed) EXPECT_TRUE(bytes(d / file) == contents) << file;
}

TEST(BakeCli, BatchErrorsNameTheJobAndBakeNothing) {
  const auto d = dir("batch-errors");
  writeBatch(d);
  const std::string jobA = R"({"low": "low.obj", "high": "high.obj", "output": "a.png"})";
  const std::string jobB = R"({"low": "low2.obj", "high": "high.obj", "output": "b.png"})";
  const auto file = [&](const std::string& job2) {
    return R"({"defaults": {"size": "32x32", "samples": 1}, "bakes": [)" + jobA + ", " + jobB + ", " + job2 + "]}";
  };
  struct Case {
    std::string json, args;
    int status;
    std::vector<const char*> messages;
  };
  const std::vector<Case> cases{
      {file(R"({"low": "low.obj", "high": "high.obj", "output": "c.png", "colour": "red"})"), "", 2,
       {"job 2 (low.obj)", "unknown key 'colour'"}},
      {file(R"({"low": "low.obj", "high": "high.obj", "output": "c.png", "size": "big"})"), "", 2,
       {"jobs.json job 2 (low.obj): size must be WIDTHxHEIGHT", "'big'"}},
      {file(R"({"low": "low.obj", "high": "high.obj", "output": "c.png", "samples": 5})"), "", 2, {"job 2", "square"}},
      {file(R"({"low": "low.obj", "high": "high.obj", "output": "c.png", "directx": "yes"})"), "", 2,
       {"job 2", "'directx' is a flag"}},
      {file(R"({"low": "low.obj", "high": "high.obj", "output": "a.png"})"), "", 2,
       {"job 0 -o", "job 2 -o", "same file"}},
      {file(R"({"low": "low.obj", "high": "high.obj", "output": "c.png", "ao": "low2.obj"})"), "", 2,
       {"job 2 --ao", "job 1's low poly", "destroy the input"}},
      {file(R"({"low": "low.obj", "output": "c.png"})"), "", 2, {"job 2 (low.obj)", "high is required"}},
      {file(R"({"low": "low.obj", "high": "high.obj", "output": "c.png"})"), " --job 5", 2, {"--job 5", "has 3 jobs"}},
      {file(R"({"low": "low.obj", "high": "high.obj", "output": "c.png"})"), " " + q(d / "low.obj") + " " + q(d / "high.obj"), 2,
       {"--batch", "LOW HIGH"}},
      {R"({"defaults": {"size": "32x32",}, "bakes": []})", "", 2, {"not valid JSON", "line 1, column 31"}},
      {R"({"defaults": {"size": "32x32"}, "bakes": []})", "", 2, {"no jobs"}},
      {R"({"defaults": {"sise": "32x32"}, "bakes": [)" + jobA + "]}", "", 2, {"defaults", "unknown key 'sise'"}},
      {R"({"bake": [)" + jobA + "]}", "", 2, {"unknown key 'bake'"}},
  };
  for (const Case& c : cases) {
    std::ofstream(d / "jobs.json") << c.json;
    const auto r = runGlint("bake --batch " + q(d / "jobs.json") + c.args);
    EXPECT_EQ(r.status, c.status) << c.json << c.args << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << c.json << ": " << r.output;
    for (const char* message : c.messages) EXPECT_NE(r.output.find(message), std::string::npos) << message << ": " << r.output;
    EXPECT_EQ(fileCount(d), 4u) << "nothing baked: " << c.json;
  }
  const auto missing = runGlint("bake --batch " + q(d / "missing.json"));
  EXPECT_EQ(missing.status, 3) << missing.output;
  EXPECT_TRUE(oneLine(missing.output)) << missing.output;
  EXPECT_NE(missing.output.find("missing.json"), std::string::npos) << missing.output;
}

TEST(BakeCli, BatchAFailedJobDoesNotStopTheOthers) {
  const auto d = dir("batch-failed");
  writeBatch(d, R"({"defaults": {"size": "32x32", "samples": 1}, "bakes": [
    {"low": "low.obj", "high": "high.obj", "output": "a.png"},
    {"low": "gone.obj", "high": "high.obj", "output": "b.png"},
    {"low": "low2.obj", "high": "high.obj", "output": "c.png"}]})");
  const auto r = runGlint("bake --batch " + q(d / "jobs.json") + " -q --json " + q(d / "report.json"));
  EXPECT_EQ(r.status, 3) << "the failed job's status: " << r.output;
  EXPECT_NE(r.output.find("job 1 (gone.obj)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 3 jobs failed (job 1)"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(d / "a.png"));
  EXPECT_FALSE(fs::exists(d / "b.png"));
  EXPECT_TRUE(fs::exists(d / "c.png"));
  std::ifstream in(d / "report.json");
  const auto report = nlohmann::json::parse(in);
  ASSERT_EQ(report["jobs"].size(), 3u);
  EXPECT_EQ(report["jobs"][0]["status"], "ok");
  EXPECT_EQ(report["jobs"][1]["status"], "failed");
  EXPECT_EQ(report["jobs"][1]["exit_status"], 3);
  EXPECT_NE(report["jobs"][1]["error"].get<std::string>().find("gone.obj"), std::string::npos);
  EXPECT_EQ(report["jobs"][2]["status"], "ok");
  EXPECT_EQ(report["failed"], 1);
}

// ------------------------------------------------------------------ more maps (issue 23)

TEST(BakeCli, EveryMapInOneCommandAndInABatchJob) {
  const auto d = dir("maps");
  writeSpheres(d);
  const auto out = d / "out";
  fs::create_directories(out);
  const auto r = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(out / "n.png") +
                          " --size 64x32 --samples 4 --ao-samples 4 --bent-normal " + q(out / "bent.png") +
                          " --thickness " + q(out / "thick.tif") + " --thickness-distance 1.5 --position " +
                          q(out / "pos.exr") + " --opacity " + q(out / "alpha.png") + " --curvature " + q(out / "curv.png") +
                          " --curvature-radius 0.2 --json " + q(out / "report.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(loadImage(out / "bent.png").channels(), 3);
  EXPECT_EQ(loadImage(out / "bent.png").type(), PixelType::U8);
  EXPECT_EQ(loadImage(out / "thick.tif").type(), PixelType::U16);
  const Image position = loadImage(out / "pos.exr");
  EXPECT_EQ(position.type(), PixelType::F32);  // raw coordinates: on the unit sphere (within its facets)
  EXPECT_NEAR(glm::length(vec3(position.at(32, 16, 0), position.at(32, 16, 1), position.at(32, 16, 2))), 1.0f, 0.01f);
  EXPECT_EQ(loadImage(out / "alpha.png").at(32, 16, 0), 1.0f);
  // A unit sphere at radius 0.2: 0.5 + 0.5 · 0.2 / 1 = 0.6 (153 / 255), to a step.
  EXPECT_NEAR(loadImage(out / "curv.png").at(32, 16, 0), 0.6f, 1.5f / 255.0f);
  EXPECT_EQ(fileCount(out), 7u);
  std::ifstream in(out / "report.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["maps"]["normal"], (out / "n.png").string());
  EXPECT_EQ(report["maps"]["bent_normal"], (out / "bent.png").string());
  EXPECT_EQ(report["maps"]["thickness"], (out / "thick.tif").string());
  EXPECT_EQ(report["maps"]["position"], (out / "pos.exr").string());
  EXPECT_EQ(report["maps"]["opacity"], (out / "alpha.png").string());
  EXPECT_EQ(report["maps"]["curvature"], (out / "curv.png").string());
  EXPECT_FLOAT_EQ(report["curvature_radius"].get<float>(), 0.2f);
  EXPECT_GT(report["curvature_rays"].get<double>(), 0.0);
  EXPECT_FALSE(report["maps"].contains("ao"));
  EXPECT_GT(report["ao_rays"].get<double>(), 0.0);  // bent normals cast the AO rays without --ao
  EXPECT_EQ(report["thickness_rays"], report["ao_rays"]);
  EXPECT_FLOAT_EQ(report["thickness_distance"].get<float>(), 1.5f);
  EXPECT_EQ(report["position_min"].size(), 3u);
  EXPECT_LT(report["position_min"][0].get<double>(), -0.99);
  EXPECT_GT(report["position_max"][1].get<double>(), 0.99);

  // The same maps from a batch job: the generic option mapping knows "bent-normal" and
  // "curvature-radius".
  std::ofstream(d / "jobs.json") << R"({"bakes": [{"low": "low.obj", "high": "high.obj", "output": "b_n.png",
    "size": "64x32", "samples": 4, "ao-samples": 4, "bent-normal": "b_bent.png", "curvature": "b_curv.png",
    "curvature-radius": "0.2"}]})";
  const auto b = runGlint("bake --batch " + q(d / "jobs.json") + " -q");
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_TRUE(bytes(d / "b_bent.png") == bytes(out / "bent.png"));
  EXPECT_TRUE(bytes(d / "b_curv.png") == bytes(out / "curv.png"));
  EXPECT_TRUE(bytes(d / "b_n.png") == bytes(out / "n.png"));

  // Their options are checked before any work: a zero thickness distance, two maps to one file.
  const std::string meshes = q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "x.png") + " --size 16x16";
  auto bad = runGlint("bake " + meshes + " --thickness " + q(d / "t.png") + " --thickness-distance 0");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--thickness-distance"), std::string::npos) << bad.output;
  bad = runGlint("bake " + meshes + " --curvature " + q(d / "c.png") + " --curvature-radius 0");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--curvature-radius"), std::string::npos) << bad.output;
  bad = runGlint("bake " + meshes + " --position " + q(d / "same.png") + " --opacity " + q(d / "same.png"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_FALSE(fs::exists(d / "x.png"));
  const auto help = runGlint("bake --help");
  for (const char* text : {"--bent-normal", "--thickness", "--thickness-distance", "--curvature", "--curvature-radius",
                           "--position", "--opacity", "Maps"})
    EXPECT_NE(help.output.find(text), std::string::npos) << text;
}

// UDIM (issue 23): a low poly whose UVs span two tiles bakes one image per tile, named by
// <UDIM>; each tile's image is byte for byte the bake of the same triangles with their UVs
// in the unit square (relative distances are the whole low poly's: given absolute here).
TEST(BakeCli, UdimTilesAreTheBakesOfTheirTrianglesInTheUnitSquare) {
  const auto d = dir("udim");
  Mesh lowA = makeUvSphere(1.0f, 16, 8), highA = makeUvSphere(1.0f, 64, 32);
  Mesh lowB = lowA, highB = makeUvSphere(1.0f, 8, 4);  // faceted: tile 1002 differs from 1001
  const mat4 apart = glm::translate(mat4(1.0f), vec3(3.0f, 0.0f, 0.0f));
  lowB.transform(apart);
  highB.transform(apart);
  writeObj(lowA, d / "a_low.obj");
  writeObj(lowB, d / "b_low.obj");  // its UVs in [0, 1], as tile 1002 holds them
  Mesh low = lowA, shifted = lowB, high = highA;
  for (vec2& uv : shifted.uvs) uv.x += 1.0f;  // tile 1002
  low.append(shifted);
  high.append(highB);
  writeObj(low, d / "low.obj");
  writeObj(high, d / "high.obj");
  const std::string options = " --size 32x32 --samples 4 --max-front 0.2 --max-rear 0.2 --padding 2 -q";
  const auto r = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n.<UDIM>.png") +
                          " --ao " + q(d / "ao.<UDIM>.png") + " --ao-distance 0.5 --json " + q(d / "r.json") + options);
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* part : {"a", "b"}) {
    const std::string tile = part == std::string("a") ? "1001" : "1002";
    const auto ref = runGlint("bake " + q(d / (std::string(part) + "_low.obj")) + " " + q(d / "high.obj") + " -o " +
                              q(d / (std::string("ref_") + part + ".png")) + " --ao " +
                              q(d / (std::string("refao_") + part + ".png")) + " --ao-distance 0.5" + options);
    ASSERT_EQ(ref.status, 0) << ref.output;
    EXPECT_FALSE(bytes(d / ("n." + tile + ".png")).empty()) << tile;
    EXPECT_TRUE(bytes(d / ("n." + tile + ".png")) == bytes(d / (std::string("ref_") + part + ".png"))) << tile;
    EXPECT_TRUE(bytes(d / ("ao." + tile + ".png")) == bytes(d / (std::string("refao_") + part + ".png"))) << tile;
  }
  EXPECT_FALSE(fs::exists(d / "n.1011.png"));
  EXPECT_FALSE(bytes(d / "n.1001.png") == bytes(d / "n.1002.png")) << "the tiles hold different parts";
  std::ifstream in(d / "r.json");
  const auto report = nlohmann::json::parse(in);
  ASSERT_EQ(report["udim_tiles"].size(), 2u);
  EXPECT_EQ(report["udim_tiles"][1]["tile"], 1002);
  EXPECT_EQ(report["udim_tiles"][1]["low_triangles_in_tile"], lowB.triangleCount());

  // UVs beyond the unit square need <UDIM> in every output's name.
  const auto unnamed = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "x.png") + options);
  EXPECT_EQ(unnamed.status, 2) << unnamed.output;
  EXPECT_TRUE(oneLine(unnamed.output)) << unnamed.output;
  EXPECT_NE(unnamed.output.find("<UDIM>"), std::string::npos) << unnamed.output;
  EXPECT_FALSE(fs::exists(d / "x.png"));
}

// UDIM tiles with a cage, and with bake groups: each tile is still the bake of its own
// triangles in the unit square, byte for byte: through the cage's vertices of those
// triangles, and with the groups of those triangles' parts (rays of a tile's part hit only
// its own group's high poly, though the other group's sphere cuts through it).
TEST(BakeCli, UdimTilesWithACageAndWithBakeGroups) {
  const auto d = dir("udim-cage-groups");
  const std::string options = " --size 32x32 --samples 4 --padding 2 -q";
  const auto cageOf = [](Mesh m) {
    for (std::size_t i = 0; i < m.positions.size(); ++i) m.positions[i] += 0.1f * m.normals[i];
    return m;
  };
  // The cage: the UDIM test's two spheres, tile 1002's moved 3 along x.
  Mesh lowA = makeUvSphere(1.0f, 16, 8), lowB = lowA;
  lowB.transform(glm::translate(mat4(1.0f), vec3(3.0f, 0.0f, 0.0f)));
  Mesh high = makeUvSphere(1.0f, 64, 32), highB = makeUvSphere(1.0f, 8, 4);
  highB.transform(glm::translate(mat4(1.0f), vec3(3.0f, 0.0f, 0.0f)));
  high.append(highB);
  writeObj(high, d / "high.obj");
  writeObj(lowA, d / "a_low.obj");
  writeObj(cageOf(lowA), d / "a_cage.obj");
  writeObj(lowB, d / "b_low.obj");
  writeObj(cageOf(lowB), d / "b_cage.obj");
  Mesh low = lowA, shifted = lowB;
  for (vec2& uv : shifted.uvs) uv.x += 1.0f;
  low.append(shifted);
  writeObj(low, d / "low.obj");
  writeObj(cageOf(low), d / "cage.obj");
  const auto r = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " --cage " + q(d / "cage.obj") + " -o " +
                          q(d / "n.<UDIM>.png") + options);
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* part : {"a", "b"}) {
    const std::string tile = part == std::string("a") ? "1001" : "1002", p(part);
    const auto ref = runGlint("bake " + q(d / (p + "_low.obj")) + " " + q(d / "high.obj") + " --cage " +
                              q(d / (p + "_cage.obj")) + " -o " + q(d / ("ref_" + p + ".png")) + options);
    ASSERT_EQ(ref.status, 0) << ref.output;
    EXPECT_FALSE(bytes(d / ("n." + tile + ".png")).empty()) << tile;
    EXPECT_TRUE(bytes(d / ("n." + tile + ".png")) == bytes(d / ("ref_" + p + ".png"))) << "cage, tile " << tile;
  }

  // Groups: two interpenetrating spheres, a's island in tile 1001 and b's in tile 1002.
  // (The sphere's own UVs, k/16 and k/8: written exactly to the OBJ, before and after the
  // tile's +1, as in the UDIM test above.)
  const auto onGrid = [](Mesh m, vec3 offset) {
    for (vec3& p : m.positions) p += offset;
    return m;
  };
  const vec3 a(-0.4f, 0, 0), b(0.4f, 0, 0);
  const Mesh lowPartA = onGrid(makeUvSphere(0.97f, 16, 8), a), lowPartB = onGrid(makeUvSphere(0.97f, 16, 8), b);
  Mesh lowPartB1002 = lowPartB;
  for (vec2& uv : lowPartB1002.uvs) uv.x += 1.0f;
  writeObjParts({{"a_low", "red", lowPartA}, {"b_low", "blue", lowPartB1002}}, d / "glow.obj");
  writeObjParts({{"a_low", "red", lowPartA}}, d / "glow_a.obj");
  writeObjParts({{"b_low", "blue", lowPartB}}, d / "glow_b.obj");
  writeObjParts({{"a_high", "red", placed(makeUvSphere(1.0f, 48, 24), a, 0.0f)},
                 {"b_high", "blue", placed(makeUvSphere(1.0f, 48, 24), b, 0.0f)}}, d / "ghigh.obj");
  const std::string groupOptions = " --max-front 0.3 --max-rear 0.3" + options;
  const auto g = runGlint("bake " + q(d / "glow.obj") + " " + q(d / "ghigh.obj") + " -o " + q(d / "g.<UDIM>.png") +
                          " --json " + q(d / "g.json") + groupOptions);
  ASSERT_EQ(g.status, 0) << g.output;
  for (const char* part : {"a", "b"}) {
    const std::string tile = part == std::string("a") ? "1001" : "1002", p(part);
    const auto ref = runGlint("bake " + q(d / ("glow_" + p + ".obj")) + " " + q(d / "ghigh.obj") + " -o " +
                              q(d / ("gref_" + p + ".png")) + groupOptions);
    ASSERT_EQ(ref.status, 0) << ref.output;
    EXPECT_FALSE(bytes(d / ("g." + tile + ".png")).empty()) << tile;
    EXPECT_TRUE(bytes(d / ("g." + tile + ".png")) == bytes(d / ("gref_" + p + ".png"))) << "groups, tile " << tile;
  }
  std::ifstream in(d / "g.json");
  const auto report = nlohmann::json::parse(in);
  ASSERT_EQ(report["udim_tiles"].size(), 2u);
}

// Bake groups from files: two interpenetrating spheres named a_low/b_low and a_high/b_high,
// in one command with a material ID map; the report lists the groups, the material map
// holds exactly the two materials' colours on the islands.
TEST(BakeCli, BakeGroupsByNameAndMaterialIdFromFiles) {
  const auto d = dir("groups");
  const vec3 a(-0.4f, 0, 0), b(0.4f, 0, 0);
  writeObjParts({{"a_low", "red", placed(makeUvSphere(0.97f, 16, 8), a, 0.0f)},
                 {"b_low", "blue", placed(makeUvSphere(0.97f, 16, 8), b, 0.5f)}}, d / "low.obj");
  writeObjParts({{"a_high", "red", placed(makeUvSphere(1.0f, 48, 24), a, 0.0f)},
                 {"b_high_1", "blue", placed(makeUvSphere(1.0f, 48, 24), b, 0.5f)},
                 {"stray_high", "blue", placed(makeCube(0.2f), vec3(5, 0, 0), 0.0f)}}, d / "high.obj");
  const auto r = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n.png") +
                          " --material-id " + q(d / "m.png") + " --size 64x64 --max-front 0.3 --max-rear 0.3 --json " +
                          q(d / "r.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("stray_high"), std::string::npos) << r.output;  // unmatched, by name
  std::ifstream in(d / "r.json");
  const auto report = nlohmann::json::parse(in);
  ASSERT_EQ(report["groups"].size(), 2u) << report.dump(2);
  EXPECT_EQ(report["groups"][0]["name"], "a");
  EXPECT_EQ(report["groups"][1]["high_parts"][0], "b_high_1");
  EXPECT_EQ(report["unmatched_high"][0], "stray_high");
  EXPECT_EQ(report["maps"]["material_id"], (d / "m.png").string());
  const Image m = loadImage(d / "m.png");
  std::set<std::array<int, 3>> colours;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      colours.insert({int(std::lround(m.at(x, y, 0) * 255)), int(std::lround(m.at(x, y, 1) * 255)),
                      int(std::lround(m.at(x, y, 2) * 255))});
  colours.erase({0, 0, 0});
  EXPECT_EQ(colours.size(), 2u);  // red's and blue's colours, nothing blended
  // Vertex colours the high poly lacks: a one-line input error, nothing written.
  const auto bad = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n2.png") +
                            " --vertex-color " + q(d / "c.png"));
  EXPECT_EQ(bad.status, 3) << bad.output;
  EXPECT_NE(bad.output.find("no vertex colours"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(d / "n2.png"));
}
