// glint bench bake — the normal mapper's speed targets (issue 6, item 10), each against a
// peer measured in the same run:
//   (a) 1024², 1 ray per texel: the whole `glint bake` run vs Blender's Cycles
//       "selected to active" bake of the same OBJ files (bench/peers/blender_bake.py);
//       "peer unavailable" when `blender` is not installed.
//   (b) 2048², 36 samples per texel, 1M-triangle high poly: seconds (target ≤ 20).
//   (c) ray throughput of the bake vs plain Embree rtcIntersect1 on the very same rays,
//       same BVH settings, same threads (target ≥ 70 %).
//   (d) time and memory as the high poly grows 10k → 100k → 1M triangles.
//   (e) mesh loading: MB/s for ~28 MB OBJ, PLY (binary) and glTF (GLB) files, glint's fast
//       paths against Assimp (the peer) in the same run, alternating.
//   (f) 2048², every map in one command (normal, AO, bent normal, curvature, thickness,
//       position) vs Blender baking the passes it has (normal, AO, position) one after
//       another on the same OBJ files (target ≥ 10×; issue 23).
//   (g) the Blender add-on's whole bake inside Blender (meshes out, glint's bake through the
//       Python module, images in, material wired) vs Blender's Cycles bake of the same maps
//       in the same session, runs alternating (bench/peers/blender_addon_bench.py): the normal
//       map at 2048² (target ≥ 10×), normal + AO with 16 rays, and the add-on's own share
//       (target < 5 % of the bake; issue 36); on a hardware GPU once with the add-on's Device
//       on CPU and once on GPU (normal + AO against Cycles: target ≥ 50×; issue 48).
//   (h) the Python module's own cost on a small bake: glint.bake()'s wall time against the
//       job's (target < 5 %; bench/peers/python_overhead.py).
#include "glint/bake/baker.h"
#include "glint/bake/samples.h"
#include "glint/bench/bench.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/raytrace/raytracer.h"
#include "glint/scenes/bake_gpu.h"

#include "embree.h"  // src/raytrace: Embree 3 or 4, the same seam as glint::raytrace
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include <unistd.h>

namespace glint::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double peakRssMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

/// Ray distances for these meshes: the studs stand 0.03 above the torus, whose 1,152-triangle
/// version lies up to 0.012 inside it; 0.06 leaves room (the same value drives Blender).
const bake::Distance kDistance{0.06f, false};

/// A square bake with the bench's ray distances, no progress bar.
bake::BakeOptions bakeOptions(int size, int samples) {
  bake::BakeOptions options;
  options.width = options.height = size;
  options.samples = samples;
  options.progress = false;
  options.maxFront = options.maxRear = kDistance;
  return options;
}

/// The low poly every case uses: a 1,152-triangle torus.
Mesh lowPoly() { return makeTorus(1.0f, 0.35f, 48, 12); }

/// A studded torus with about `triangles` triangles (2 · segments · sides, sides = segments / 2).
Mesh highPoly(int triangles) {
  const int segments = int(std::lround(std::sqrt(double(triangles))));
  return bake::makeStuddedTorus({.segments = segments, .sides = segments / 2});
}

std::string shellQuote(const fs::path& p) {
  std::string out = "'";
  for (char c : p.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

constexpr int kWholeRunRepeats = 5, kPeerRepeats = 3, kThroughputRepeats = 3, kLoadRepeats = 3;

/// Runs a command line, returns wall seconds, or a negative value when it failed.
double timeCommand(const std::string& command) {
  const auto start = Clock::now();
  const int status = std::system(command.c_str());
  return status == 0 ? secondsSince(start) : -1.0;
}

bool blenderAvailable() { return std::system("command -v blender >/dev/null 2>&1") == 0; }

fs::path self() { return fs::read_symlink("/proc/self/exe"); }

/// The "seconds" object of a `glint bake --json` report (null when the file is missing or
/// not JSON: the phases then read as NaN).
nlohmann::json reportSeconds(const fs::path& path) {
  std::ifstream in(path);
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  return report.is_object() && report.contains("seconds") ? report["seconds"] : nlohmann::json();
}

/// One phase of such an object, or NaN.
double phaseSeconds(const nlohmann::json& seconds, const char* phase) {
  return seconds.is_object() && seconds.contains(phase) && seconds[phase].is_number() ? seconds[phase].get<double>()
                                                                                       : std::nan("");
}

/// (a) the whole run, both tools from the same OBJ files, runs alternating.
void versusBlender(Recorder& r, const fs::path& dir) {
  const std::string group = "a: 1024² 1 ray";
  const Mesh low = lowPoly();
  const Mesh high = highPoly(262144);
  bake::writeObj(low, dir / "low.obj");
  bake::writeObj(high, dir / "high.obj");
  const std::string args = fmt::format("{} {} --size 1024x1024 --samples 1 --max-front 0.06 --max-rear 0.06 -q",
                                       shellQuote(dir / "low.obj"), shellQuote(dir / "high.obj"));
  const bool blender = blenderAvailable();
  const fs::path script = fs::path(GLINT_SOURCE_DIR) / "bench" / "peers" / "blender_bake.py";
  // Medians of alternating runs: one run of either tool can be slowed by the machine's other load.
  std::vector<double> glintRuns, blenderRuns, load, bake, write;
  bool blenderFailed = false;
  for (int i = 0; i < kWholeRunRepeats; ++i) {
    glintRuns.push_back(timeCommand(fmt::format("{} bake {} -o {} --json {}", shellQuote(self()), args,
                                                shellQuote(dir / "glint.png"), shellQuote(dir / "glint.json"))));
    if (glintRuns.back() < 0) fail(ErrorKind::Internal, "bench bake: `glint bake` failed");
    const nlohmann::json seconds = reportSeconds(dir / "glint.json");
    load.push_back(phaseSeconds(seconds, "load"));
    bake.push_back(phaseSeconds(seconds, "prepare") + phaseSeconds(seconds, "trace") + phaseSeconds(seconds, "dilate"));
    write.push_back(phaseSeconds(seconds, "write"));
    if (blender && !blenderFailed && i < kPeerRepeats) {
      blenderRuns.push_back(timeCommand(fmt::format("blender -b --factory-startup --python-exit-code 1 --python {} -- {} {} {} 1024 1 0.06 >/dev/null 2>&1",
                                                    shellQuote(script), shellQuote(dir / "low.obj"),
                                                    shellQuote(dir / "high.obj"), shellQuote(dir / "blender.png"))));
      blenderFailed = blenderRuns.back() < 0;
    }
  }
  const double glint = median(glintRuns);
  r.record({.group = group, .name = "glint bake (whole run)", .value = glint, .unit = "s",
            .note = fmt::format("median of {}; {} → {} triangles, OBJ load + bake + PNG", glintRuns.size(),
                                high.triangleCount(), low.triangleCount())});
  const double loadS = median(load), bakeS = median(bake), writeS = median(write);
  r.record({.group = group, .name = "  load (both meshes)", .value = loadS, .unit = "s",
            .note = fmt::format("{:.1f} MB of OBJ; medians of the runs' --json phases", double(fs::file_size(dir / "high.obj") + fs::file_size(dir / "low.obj")) / 1e6)});
  r.record({.group = group, .name = "  bake (prepare + trace + dilate)", .value = bakeS, .unit = "s",
            .note = "all of bake::bake(): checks, tangents, BVH, rays, dilation, images"});
  r.record({.group = group, .name = "  write (PNG)", .value = writeS, .unit = "s"});
  r.record({.group = group, .name = "  load + write vs bake (target < 1)", .value = (loadS + writeS) / bakeS, .unit = "×"});
  if (!blender) {
    r.record({.group = group, .name = "blender cycles", .value = std::nan(""), .unit = "s",
              .note = "peer unavailable: `blender` is not installed (apt install blender)"});
    return;
  }
  if (blenderFailed) {
    r.record({.group = group, .name = "blender cycles", .value = std::nan(""), .unit = "s", .note = "peer failed"});
    return;
  }
  const double peer = median(blenderRuns);
  r.record({.group = group, .name = "blender cycles", .value = peer, .unit = "s",
            .note = fmt::format("median of {}, alternating with glint's; whole run, same files", blenderRuns.size())});
  r.record({.group = group, .name = "speed-up (target ≥ 10)", .value = peer / glint, .unit = "×"});
}

/// (f) every map glint bakes from one command against the three passes Blender bakes, one
/// after another, at 2048²: the same OBJ files, 1 sample per texel for the normal-like
/// passes, 16 AO rays per texel (Blender: 16 Cycles samples of one AO ray each), AO
/// distance 0.1, runs alternating.
void everyMapVersusBlender(Recorder& r, const fs::path& dir) {
  const std::string group = "f: 2048² every map";
  const Mesh low = lowPoly();
  const Mesh high = highPoly(262144);
  if (!fs::exists(dir / "low.obj")) bake::writeObj(low, dir / "low.obj");
  if (!fs::exists(dir / "high.obj")) bake::writeObj(high, dir / "high.obj");
  // Curvature joins the list where this glint has it (the bench does not hard-code the map set).
  const bool curvature = std::system(fmt::format("{} bake --help 2>/dev/null | grep -q -- --curvature ",
                                                 shellQuote(self())).c_str()) == 0;
  const auto out = [&](const char* name) { return shellQuote(dir / fmt::format("all.{}.png", name)); };
  std::string maps = fmt::format("-o {} --ao {} --bent-normal {} --thickness {} --position {}", out("normal"), out("ao"),
                                 out("bent"), out("thickness"), out("position"));
  if (curvature) maps += " --curvature " + out("curvature");
  const std::string command = fmt::format(
      "{} bake {} {} {} --size 2048x2048 --samples 1 --max-front 0.06 --max-rear 0.06 --ao-samples 16 "
      "--ao-distance 0.1 --thickness-distance 0.1 -q",
      shellQuote(self()), shellQuote(dir / "low.obj"), shellQuote(dir / "high.obj"), maps);
  const bool blender = blenderAvailable();
  const fs::path script = fs::path(GLINT_SOURCE_DIR) / "bench" / "peers" / "blender_bake.py";
  std::vector<double> glintRuns, blenderRuns;
  bool blenderFailed = false;
  for (int i = 0; i < kPeerRepeats; ++i) {
    glintRuns.push_back(timeCommand(command));
    if (glintRuns.back() < 0) fail(ErrorKind::Internal, "bench bake: `glint bake` with every map failed");
    if (blender && !blenderFailed) {
      blenderRuns.push_back(timeCommand(fmt::format(
          "blender -b --factory-startup --python-exit-code 1 --python {} -- {} {} {} 2048 1 0.06 normal,ao,position 16 0.1 >/dev/null 2>&1",
          shellQuote(script), shellQuote(dir / "low.obj"), shellQuote(dir / "high.obj"), shellQuote(dir / "blender-all.png"))));
      blenderFailed = blenderRuns.back() < 0;
    }
  }
  const double glint = median(glintRuns);
  r.record({.group = group, .name = "glint bake, 1 command", .value = glint, .unit = "s",
            .note = fmt::format("median of {}; normal, AO, bent normal, {}thickness, position; {} → {} triangles",
                                glintRuns.size(), curvature ? "curvature, " : "", high.triangleCount(), low.triangleCount())});
  if (!blender || blenderFailed) {
    r.record({.group = group, .name = "blender cycles, 3 passes", .value = std::nan(""), .unit = "s",
              .note = blender ? "peer failed" : "peer unavailable: `blender` is not installed (apt install blender)"});
    return;
  }
  const double peer = median(blenderRuns);
  r.record({.group = group, .name = "blender cycles, 3 passes", .value = peer, .unit = "s",
            .note = fmt::format("median of {}, alternating; normal, AO, position one after another", blenderRuns.size())});
  r.record({.group = group, .name = "speed-up (target ≥ 10)", .value = peer / glint, .unit = "×",
            .note = fmt::format("glint bakes {} maps, Blender 3", curvature ? 6 : 5)});
}

/// The lines of a command's standard output that start with "RESULT ", parsed; empty when
/// the command failed.
std::vector<nlohmann::json> resultLines(const std::string& command) {
  std::vector<nlohmann::json> out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  std::string line;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) {
    line += buffer;
    if (line.empty() || line.back() != '\n') continue;
    if (line.starts_with("RESULT ")) out.push_back(nlohmann::json::parse(line.substr(7), nullptr, false));
    line.clear();
  }
  if (pclose(pipe) != 0) out.clear();
  return out;
}

/// Where the build keeps the Python module and the add-on's zip; empty when not built.
fs::path buildPath(const char* path) {
  std::error_code ec;
  return fs::exists(path, ec) ? fs::path(path) : fs::path();
}

/// (g) the add-on in Blender against Cycles in Blender, the same OBJ files as (a) and (f).
void addonVersusBlender(Recorder& r, const fs::path& dir) {
  const std::string group = "g: Blender add-on, 2048²";
  const fs::path zip = buildPath(GLINT_ADDON_ZIP_PATH), extension = buildPath(GLINT_ADDON_EXTENSION_ZIP_PATH),
                 module = buildPath(GLINT_PYTHON_DIR);
  const auto unavailable = [&](const std::string& why) {
    r.record({.group = group, .name = "add-on vs cycles", .value = std::nan(""), .unit = "×", .note = why});
  };
  if (!blenderAvailable()) return unavailable("peer unavailable: `blender` is not installed (apt install blender)");
  if (zip.empty() || extension.empty() || module.empty())
    return unavailable("the add-on or the Python module was not built (GLINT_BUILD_PYTHON)");
  if (!fs::exists(dir / "low.obj")) bake::writeObj(lowPoly(), dir / "low.obj");
  if (!fs::exists(dir / "high.obj")) bake::writeObj(highPoly(262144), dir / "high.obj");
  // On a hardware GPU the add-on bakes with its Device on CPU and on GPU (issue 48), each
  // against Cycles; elsewhere with its default (auto: the CPU).
  bool hardware = false;
  try {
    hardware = !scenes::bakeGpuBackend()->start(false).software;
  } catch (const Error&) {
    hardware = false;
  }
  const std::vector<std::string> tools = hardware ? std::vector<std::string>{"addon-cpu", "addon-gpu"}
                                                  : std::vector<std::string>{"addon"};
  const auto results = resultLines(fmt::format(
      "BLENDER_USER_SCRIPTS={} BLENDER_USER_EXTENSIONS={} blender -b --factory-startup --python-exit-code 1 --python {} -- "
      "{} {} {} {} {} 2048 {} {} 2>/dev/null",
      shellQuote(dir / "blender-scripts"), shellQuote(dir / "blender-extensions"),
      shellQuote(fs::path(GLINT_SOURCE_DIR) / "bench" / "peers" / "blender_addon_bench.py"), shellQuote(zip),
      shellQuote(extension), shellQuote(module), shellQuote(dir / "low.obj"), shellQuote(dir / "high.obj"), kPeerRepeats,
      hardware ? "cpu,gpu" : "auto"));
  if (results.size() != 2 * kPeerRepeats * (tools.size() + 1)) return unavailable("peer failed (blender_addon_bench.py)");
  for (const char* name : {"normal", "normal+ao"}) {
    std::vector<double> cycles;
    for (const nlohmann::json& j : results)
      if (j.value("case", "") == name && j.value("tool", "") == "cycles") cycles.push_back(j.value("seconds", std::nan("")));
    const bool normalOnly = std::string(name) == "normal";
    const std::string label = normalOnly ? "normal map" : "normal + AO (16 rays)";
    const double c = median(cycles);
    r.record({.group = group, .name = "blender cycles, " + label, .value = c, .unit = "s",
              .note = fmt::format("median of {}, alternating, same session and objects", cycles.size())});
    for (const std::string& tool : tools) {
      std::vector<double> addon, outside, inside, exported, imported;
      for (const nlohmann::json& j : results) {
        if (j.value("case", "") != name || j.value("tool", "") != tool) continue;
        addon.push_back(j.value("seconds", std::nan("")));
        const nlohmann::json& p = j["phases"];
        inside.push_back(p.value("bake", std::nan("")));
        outside.push_back(p.value("export", 0.0) + p.value("import", 0.0) + p.value("wire", 0.0));
        exported.push_back(p.value("export", 0.0));
        imported.push_back(p.value("import", 0.0));
      }
      const std::string who = tool == "addon" ? "add-on" : tool == "addon-cpu" ? "add-on (CPU)" : "add-on (GPU)";
      const double a = median(addon);
      r.record({.group = group, .name = who + ", " + label, .value = a, .unit = "s",
                .note = fmt::format("median of {}; the operator whole: meshes out, glint.bake, images in, wiring",
                                    addon.size())});
      const bool gpu = tool == "addon-gpu";
      const char* target = gpu ? (normalOnly ? "" : " (target ≥ 50)") : (normalOnly ? " (target ≥ 10)" : "");
      r.record({.group = group, .name = "  " + who + " speed-up" + target,
                .value = c / a, .unit = "×",
                .note = normalOnly ? "" : gpu ? "the GPU's rays (issue 48)" : "AO: 16 CPU rays per texel bound both"});
      r.record({.group = group, .name = "  " + who + "'s own share (target < 5 %)",
                .value = 100.0 * median(outside) / median(inside), .unit = "%",
                .note = fmt::format("{:.3f} s (meshes out {:.3f} s, images in {:.3f} s, wiring) of the bake's {:.2f} s",
                                    median(outside), median(exported), median(imported), median(inside))});
    }
  }
}

/// (h) the Python module's cost: glint.bake()'s wall time less the job's own, on a small bake.
void pythonOverhead(Recorder& r, const fs::path& dir) {
  const std::string group = "h: Python module";
  const fs::path module = buildPath(GLINT_PYTHON_DIR);
  if (module.empty()) {
    r.record({.group = group, .name = "module overhead", .value = std::nan(""), .unit = "%",
              .note = "the Python module was not built (GLINT_BUILD_PYTHON)"});
    return;
  }
  bake::writeObj(lowPoly(), dir / "small_low.obj");
  bake::writeObj(highPoly(16384), dir / "small_high.obj");
  const auto results = resultLines(fmt::format(
      "PYTHONPATH={} {} {} {} {} 256 {} 2>/dev/null", shellQuote(module), shellQuote(GLINT_PYTHON_EXECUTABLE),
      shellQuote(fs::path(GLINT_SOURCE_DIR) / "bench" / "peers" / "python_overhead.py"), shellQuote(dir / "small_low.obj"),
      shellQuote(dir / "small_high.obj"), kWholeRunRepeats));
  if (results.size() != 1) {
    r.record({.group = group, .name = "module overhead", .value = std::nan(""), .unit = "%", .note = "python_overhead.py failed"});
    return;
  }
  const std::vector<double> walls = results[0]["wall"].get<std::vector<double>>();
  const std::vector<double> jobs = results[0]["job"].get<std::vector<double>>();
  std::vector<double> overheads;
  for (std::size_t i = 0; i < walls.size() && i < jobs.size(); ++i) overheads.push_back(walls[i] - jobs[i]);
  const double job = median(jobs), overhead = median(overheads);
  r.record({.group = group, .name = "glint.bake, 256², 16k triangles", .value = median(walls), .unit = "s",
            .note = fmt::format("median of {}; the job itself {:.3f} s", walls.size(), job)});
  r.record({.group = group, .name = "  module overhead (target < 5 %)", .value = 100.0 * overhead / job, .unit = "%",
            .note = fmt::format("{:.1f} ms: options in, the worker thread, arrays out", 1000.0 * overhead)});
}

/// A binary little-endian PLY with positions, normals and uvs.
void writePly(const Mesh& mesh, const fs::path& path) {
  std::string out = fmt::format("ply\nformat binary_little_endian 1.0\nelement vertex {}\n"
                                "property float x\nproperty float y\nproperty float z\n"
                                "property float nx\nproperty float ny\nproperty float nz\n"
                                "property float s\nproperty float t\n"
                                "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
                                mesh.vertexCount(), mesh.triangleCount());
  const auto put = [&](const void* data, std::size_t n) { out.append(static_cast<const char*>(data), n); };
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    put(&mesh.positions[i], 12);
    put(&mesh.normals[i], 12);
    put(&mesh.uvs[i], 8);
  }
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    out.push_back(3);
    put(&mesh.indices[3 * t], 12);
  }
  writeTextAtomically(path, out);
}

/// A GLB (binary glTF 2.0): one mesh, positions, normals, uvs and 32-bit indices.
void writeGlb(const Mesh& mesh, const fs::path& path) {
  const std::size_t n = mesh.vertexCount(), positions = n * 12, normals = n * 12, uvs = n * 8,
                    indices = mesh.indices.size() * 4;
  const Bounds b = mesh.bounds();
  std::string json = fmt::format(
      R"({{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],)"
      R"("meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3}}]}}],)"
      R"("buffers":[{{"byteLength":{}}}],"bufferViews":[)"
      R"({{"buffer":0,"byteOffset":0,"byteLength":{}}},{{"buffer":0,"byteOffset":{},"byteLength":{}}},)"
      R"({{"buffer":0,"byteOffset":{},"byteLength":{}}},{{"buffer":0,"byteOffset":{},"byteLength":{}}}],"accessors":[)"
      R"({{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3","min":[{},{},{}],"max":[{},{},{}]}},)"
      R"({{"bufferView":1,"componentType":5126,"count":{},"type":"VEC3"}},)"
      R"({{"bufferView":2,"componentType":5126,"count":{},"type":"VEC2"}},)"
      R"({{"bufferView":3,"componentType":5125,"count":{},"type":"SCALAR"}}]}})",
      positions + normals + uvs + indices, positions, positions, normals, positions + normals, uvs,
      positions + normals + uvs, indices, n, b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z, n, n,
      mesh.indices.size());
  while (json.size() % 4) json += ' ';
  const std::uint32_t binSize = std::uint32_t(positions + normals + uvs + indices);
  const std::uint32_t header[3] = {0x46546C67u, 2u, std::uint32_t(12 + 8 + json.size() + 8 + binSize)};
  const std::uint32_t jsonChunk[2] = {std::uint32_t(json.size()), 0x4E4F534Au};
  const std::uint32_t binChunk[2] = {binSize, 0x004E4942u};
  std::string out;
  const auto put = [&](const void* data, std::size_t size) { out.append(static_cast<const char*>(data), size); };
  put(header, 12);
  put(jsonChunk, 8);
  out += json;
  put(binChunk, 8);
  put(mesh.positions.data(), positions);
  put(mesh.normals.data(), normals);
  put(mesh.uvs.data(), uvs);
  put(mesh.indices.data(), indices);
  writeTextAtomically(path, out);
}

/// (e) load speed per format: the fast path and Assimp on the same file, alternating.
void loading(Recorder& r, const fs::path& dir) {
  const Mesh obj = highPoly(262144);  // 28 MB of OBJ text
  const Mesh big = highPoly(1 << 20);  // 29 MB as binary PLY, 28 MB as GLB
  bake::writeObj(obj, dir / "load.obj");
  writePly(big, dir / "load.ply");
  writeGlb(big, dir / "load.glb");
  struct Case {
    std::string file;
    bool join;
    bool fast;  // has a fast path
  };
  for (const Case& c : {Case{"load.obj", true, true}, Case{"load.obj", false, true}, Case{"load.ply", true, true},
                        Case{"load.glb", true, false}}) {
    const fs::path path = dir / c.file;
    const double mb = double(fs::file_size(path)) / 1e6;
    const std::string group = fmt::format("e: load {} {:.0f} MB{}", path.extension().string().substr(1), mb,
                                          c.join ? "" : ", not joined");
    std::vector<double> fastRuns, assimpRuns;
    std::size_t triangles = 0;
    for (int i = 0; i < kLoadRepeats; ++i) {
      for (MeshParser parser : {MeshParser::Auto, MeshParser::Assimp}) {
        if (parser == MeshParser::Auto && !c.fast) continue;
        const auto start = Clock::now();
        const Mesh m = loadMesh(path, {.joinVertices = c.join, .parser = parser});
        (parser == MeshParser::Assimp ? assimpRuns : fastRuns).push_back(secondsSince(start));
        triangles = m.triangleCount();
      }
    }
    const std::string note = fmt::format("{} triangles; median of {}, alternating", triangles, kLoadRepeats);
    r.record({.group = group, .name = "Assimp", .value = mb / median(assimpRuns), .unit = "MB/s", .note = note});
    if (c.fast) {
      r.record({.group = group, .name = path.extension() == ".obj" ? "glint (from_chars lane + tinyobjloader, parallel)" : "glint (Draco PLY reader)",
                .value = mb / median(fastRuns), .unit = "MB/s", .ratioTo = "Assimp", .note = note});
    }
  }
}

/// (b) the big bake, in process.
void bigBake(Recorder& r) {
  const std::string group = "b: 2048² 36 spp";
  const Mesh low = lowPoly();
  const Mesh high = highPoly(1 << 20);
  const bake::BakeOptions options = bakeOptions(2048, 36);
  const auto start = Clock::now();
  const double cpuStart = processCpuSeconds();
  const auto result = bake::bake(low, high, options);
  const double seconds = secondsSince(start), cpu = processCpuSeconds() - cpuStart;
  const auto& s = result.stats;
  r.record({.group = group, .name = "bake (target ≤ 20)", .value = seconds, .unit = "s",
            .note = fmt::format("{} triangles; prepare {:.2f} s, trace {:.2f} s, dilate {:.2f} s", high.triangleCount(),
                                s.prepareSeconds, s.traceSeconds, s.dilateSeconds)});
  r.record({.group = group, .name = "CPU time / 2 cores", .value = cpu / 2.0, .unit = "s",
            .note = fmt::format("{:.1f} CPU s: the wall time on two otherwise idle cores", cpu)});
  r.record({.group = group, .name = "rays", .value = double(s.rays) / 1e6, .unit = "M",
            .note = fmt::format("{:.1f} M samples, hit ratio {:.4f}", double(s.samples) / 1e6, s.hitRatio())});
  r.record({.group = group, .name = "throughput", .value = double(s.rays) / s.traceSeconds / 1e6, .unit = "Mrays/s"});
}

/// (c) the bake's rays, replayed through plain Embree.
void throughput(Recorder& r, const Mesh& low, const Mesh& high, int size, int samples) {
  const std::string group = fmt::format("c: {}² {} spp", size, samples);
  bake::BakeOptions options = bakeOptions(size, samples);
  std::vector<raytrace::Ray> rays;
  options.rayLog = &rays;
  const bool lowQuality = bake::bake(low, high, options).stats.lowQualityBvh;  // records the rays
  options.rayLog = nullptr;

  // Plain Embree: the same mesh, the same build settings as the baker's Scene (the quality
  // it chose for this many rays per triangle, not robust), rtcIntersect1 on the same rays in
  // the same order, spread over the same TBB workers in chunks.
  const RTCBuildQuality quality = lowQuality ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM;
  RTCDevice device = rtcNewDevice("verbose=0");
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, quality);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, quality);
  std::memcpy(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(vec3), high.vertexCount()),
              high.positions.data(), high.vertexCount() * sizeof(vec3));
  std::memcpy(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, high.triangleCount()),
              high.indices.data(), high.indices.size() * 4);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  const auto plainRun = [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        RTCRayHit rh;
        raytrace::embree::fill(rays[i], rh);  // the Scene's own conversion (src/raytrace/embree.h)
        raytrace::embree::intersect(scene, rh);
      }
    });
  };

  // Alternating runs, medians of each: both see the same machine state over time.
  std::vector<double> bakeCpu, bakeWall, plainCpu, plainWall;
  for (int i = 0; i < kThroughputRepeats; ++i) {
    // Throughput of the bake itself: every ray over the whole tracing phase (rasterizing the
    // UV layout, interpolating, shading and writing texels included).
    const auto result = bake::bake(low, high, options);
    bakeWall.push_back(double(result.stats.rays) / result.stats.traceSeconds / 1e6);
    bakeCpu.push_back(double(result.stats.rays) / result.stats.traceCpuSeconds / 1e6);
    const auto start = Clock::now();
    const double cpuStart = processCpuSeconds();
    plainRun();
    plainWall.push_back(double(rays.size()) / secondsSince(start) / 1e6);
    plainCpu.push_back(double(rays.size()) / (processCpuSeconds() - cpuStart) / 1e6);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  const std::string what = fmt::format("{:.2f} M rays of the bake, {} triangles, {} quality BVH; medians of {} alternating runs",
                                       double(rays.size()) / 1e6, high.triangleCount(), lowQuality ? "low" : "medium",
                                       kThroughputRepeats);
  r.record({.group = group, .name = "plain rtcIntersect1 /cpu-s", .value = median(plainCpu), .unit = "Mrays/s", .note = what});
  r.record({.group = group, .name = "glint bake /cpu-s (≥ 0.7)", .value = median(bakeCpu), .unit = "Mrays/s",
            .ratioTo = "plain rtcIntersect1 /cpu-s", .note = "whole tracing phase, per CPU second (load-independent)"});
  r.record({.group = group, .name = "plain rtcIntersect1 wall", .value = median(plainWall), .unit = "Mrays/s"});
  r.record({.group = group, .name = "glint bake wall", .value = median(bakeWall), .unit = "Mrays/s",
            .ratioTo = "plain rtcIntersect1 wall", .note = "wall clock: depends on the machine's other load"});
}

/// (i) the GPU bake (issue 48) against glint's own CPU path, in the same run: rays per
/// second (the trace phase's rays over its wall time: sample placement, shading and storing
/// included) for the normal map and for AO with 16 and 256 rays; the whole command (normal +
/// AO with 16 rays) against the CPU path and Blender's Cycles; 256-ray AO at 4096². On a
/// software renderer (llvmpipe) the sizes shrink so the rows exist in minutes, and the rows a
/// GPU's targets are about say they were not run.
void gpuVersusCpu(Recorder& r, const fs::path& dir) {
  const std::string group = "i: GPU vs CPU, studded torus";
  const auto backend = scenes::bakeGpuBackend();
  bake::GpuInfo info;
  try {
    info = backend->start(false);
  } catch (const Error& e) {
    r.record({.group = group, .name = "GPU", .value = std::nan(""), .unit = "Mrays/s",
              .note = fmt::format("no GPU: {}", e.what())});
    return;
  }
  // GLINT_BENCH_QUICK (scripts/gpu-check's own test): the smallest sizes, one run each.
  const bool software = info.software, fast = quick();
  const Mesh low = lowPoly();
  const Mesh high = highPoly(fast ? 16384 : 262144);
  const std::string where = fmt::format("{}{}", info.renderer, software ? " (software: smaller sizes)" : "");
  const int shrink = fast ? 8 : 1;
  struct Case {
    const char* name;
    int size, aoSamples;
  };
  const Case cases[] = {{"normal map", (software ? 1024 : 2048) / shrink, 0},
                        {"AO 16 rays", (software ? 512 : 2048) / shrink, 16},
                        {"AO 256 rays", (software ? 128 : 2048) / shrink, 256}};
  for (const Case& c : cases) {
    bake::BakeOptions options = bakeOptions(c.size, 1);
    if (c.aoSamples) {
      options.maps.add(bake::Map::Ao);
      options.aoSamples = c.aoSamples;
    }
    const auto rate = [&](const bake::BakeStats& s) {
      return double(c.aoSamples ? s.aoRays : s.rays) / s.traceSeconds / 1e6;
    };
    std::vector<double> cpu, gpu;
    // Alternating; 256-ray AO once each on a GPU (a billion rays: most of the CPU path's minute).
    const int repeats = fast || (c.aoSamples == 256 && !software) ? 1 : kThroughputRepeats;
    for (int i = 0; i < repeats; ++i) {
      options.device = bake::Device::Cpu;
      options.gpu = nullptr;
      cpu.push_back(rate(bake::bake(low, high, options).stats));
      options.device = bake::Device::Gpu;
      options.gpu = backend.get();
      gpu.push_back(rate(bake::bake(low, high, options).stats));
    }
    const std::string cpuName = fmt::format("{} {}², CPU", c.name, c.size);
    r.record({.group = group, .name = cpuName, .value = median(cpu), .unit = "Mrays/s",
              .note = fmt::format("Embree, {} threads; medians of {} alternating runs", tbb::this_task_arena::max_concurrency(), cpu.size())});
    r.record({.group = group, .name = fmt::format("{} {}², GPU", c.name, c.size), .value = median(gpu), .unit = "Mrays/s",
              .ratioTo = cpuName,
              .note = c.aoSamples ? fmt::format("{}; target ≥ 1000 Mrays/s on an H100/H200", where) : where});
  }

  if (fast) {
    for (const char* name : {"normal + AO 16, command, GPU", "AO 256 rays 4096², GPU (target < 10 s)"})
      r.record({.group = group, .name = name, .value = std::nan(""), .unit = "s",
                .note = "GLINT_BENCH_QUICK: the whole runs take minutes"});
    return;
  }
  // The whole command, normal + AO (16 rays): GPU, CPU and Cycles, alternating.
  const int size = software ? 1024 : 2048;
  if (!fs::exists(dir / "low.obj")) bake::writeObj(low, dir / "low.obj");
  if (!fs::exists(dir / "high.obj")) bake::writeObj(high, dir / "high.obj");
  const auto command = [&](const char* device) {
    return fmt::format("{} bake {} {} -o {} --ao {} --size {}x{} --samples 1 --max-front 0.06 --max-rear 0.06 "
                       "--ao-samples 16 --ao-distance 0.1 --device {} -q", shellQuote(self()), shellQuote(dir / "low.obj"),
                       shellQuote(dir / "high.obj"), shellQuote(dir / "gpu-n.png"), shellQuote(dir / "gpu-ao.png"), size,
                       size, device);
  };
  const bool blender = blenderAvailable();
  const fs::path script = fs::path(GLINT_SOURCE_DIR) / "bench" / "peers" / "blender_bake.py";
  std::vector<double> gpuRuns, cpuRuns, cyclesRuns;
  for (int i = 0; i < kPeerRepeats; ++i) {
    gpuRuns.push_back(timeCommand(command("gpu")));
    cpuRuns.push_back(timeCommand(command("cpu")));
    if (gpuRuns.back() < 0 || cpuRuns.back() < 0) fail(ErrorKind::Internal, "bench bake: `glint bake --device` failed");
    if (blender) {
      cyclesRuns.push_back(timeCommand(fmt::format(
          "blender -b --factory-startup --python-exit-code 1 --python {} -- {} {} {} {} 1 0.06 normal,ao 16 0.1 >/dev/null 2>&1",
          shellQuote(script), shellQuote(dir / "low.obj"), shellQuote(dir / "high.obj"), shellQuote(dir / "cycles-n.png"),
          size)));
    }
  }
  const std::string whole = fmt::format("normal + AO 16, {}², command", size);
  r.record({.group = group, .name = whole + ", CPU", .value = median(cpuRuns), .unit = "s",
            .note = fmt::format("whole runs, medians of {} alternating", cpuRuns.size())});
  r.record({.group = group, .name = whole + ", GPU", .value = median(gpuRuns), .unit = "s",
            .note = "speed-up over the CPU path: target ≥ 25× on an H100/H200's machine"});
  r.record({.group = group, .name = "  CPU / GPU", .value = median(cpuRuns) / median(gpuRuns), .unit = "×"});
  const bool cycles = blender && !cyclesRuns.empty() && *std::min_element(cyclesRuns.begin(), cyclesRuns.end()) >= 0;
  r.record({.group = group, .name = whole + ", Blender Cycles", .value = cycles ? median(cyclesRuns) : std::nan(""),
            .unit = "s", .note = cycles ? "the same files, normal then AO (16 samples)" : "peer unavailable or failed"});
  r.record({.group = group, .name = "  Cycles / GPU (target ≥ 50)", .value = cycles ? median(cyclesRuns) / median(gpuRuns) : std::nan(""),
            .unit = "×"});

  // 256-ray AO at 4096²: 4.3 G rays, the GPU's alone (the CPU path would take tens of minutes).
  if (software) {
    r.record({.group = group, .name = "AO 256 rays 4096², GPU (target < 10 s)", .value = std::nan(""), .unit = "s",
              .note = "not run on a software renderer (4.3 G rays)"});
    return;
  }
  bake::BakeOptions options = bakeOptions(4096, 1);
  options.maps.add(bake::Map::Ao);
  options.aoSamples = 256;
  options.device = bake::Device::Gpu;
  options.gpu = backend.get();
  const auto start = Clock::now();
  const bake::BakeStats s = bake::bake(low, high, options).stats;
  r.record({.group = group, .name = "AO 256 rays 4096², GPU (target < 10 s)", .value = secondsSince(start), .unit = "s",
            .note = fmt::format("{:.2f} G AO rays, {:.0f} Mrays/s over the trace; {} dispatches, the longest {:.0f} ms",
                                double(s.aoRays) / 1e9, double(s.aoRays) / s.traceSeconds / 1e6, s.gpuDispatches,
                                s.gpuLongestDispatchMs)});
}

/// (d) scaling with the high poly.
void scaling(Recorder& r) {
  const Mesh low = lowPoly();
  for (int triangles : {10000, 100000, 1000000}) {
    const Mesh high = highPoly(triangles);
    const bake::BakeOptions options = bakeOptions(1024, 4);
    const auto start = Clock::now();
    const auto result = bake::bake(low, high, options);
    const double seconds = secondsSince(start);
    const std::string group = fmt::format("d: {}k triangles", (high.triangleCount() + 500) / 1000);
    r.record({.group = group, .name = "bake 1024² 4 spp", .value = seconds, .unit = "s",
              .note = fmt::format("prepare (BVH) {:.2f} s, trace {:.2f} s", result.stats.prepareSeconds,
                                  result.stats.traceSeconds)});
    r.record({.group = group, .name = "BVH memory", .value = double(result.stats.bvhBytes) / (1 << 20), .unit = "MiB"});
    r.record({.group = group, .name = "mesh memory", .value = double(high.vertexCount() * 32 + high.indices.size() * 4) / (1 << 20),
              .unit = "MiB", .note = "positions, normals, UVs, indices"});
    r.record({.group = group, .name = "process peak RSS", .value = peakRssMiB(), .unit = "MiB",
              .note = "high-water mark of the whole bench so far"});
  }
}

}  // namespace

/// The "bake" suite (bench/bench.cpp lists it).
void runBakeSuite(Recorder& r) {
  const auto level = log::level();
  log::setLevel(log::Level::Error);  // the bakes' own warnings are not the bench's output
  const fs::path dir = fs::temp_directory_path() / fmt::format("glint-bench-bake-{}", getpid());
  fs::create_directories(dir);
  // GLINT_BENCH_BAKE_PARTS=g,h runs only those parts (the letters above); unset: every part.
  const char* only = std::getenv("GLINT_BENCH_BAKE_PARTS");
  const auto part = [only](char letter) { return !only || std::strchr(only, letter) != nullptr; };
  try {
    if (part('e')) loading(r, dir);
    if (part('d')) scaling(r);
    if (part('c')) {
      const Mesh low = lowPoly(), high = highPoly(1 << 20);
      // (the ray log costs 32 B per ray: ~4 M rays each)
      throughput(r, low, high, 2048, 1);
      throughput(r, low, high, 1024, 4);
    }
    if (part('b')) bigBake(r);
    if (part('a')) versusBlender(r, dir);
    if (part('f')) everyMapVersusBlender(r, dir);
    if (part('g')) addonVersusBlender(r, dir);
    if (part('h')) pythonOverhead(r, dir);
    if (part('i')) gpuVersusCpu(r, dir);
  } catch (...) {
    fs::remove_all(dir);
    log::setLevel(level);
    throw;
  }
  fs::remove_all(dir);
  log::setLevel(level);
}

}  // namespace glint::bench
