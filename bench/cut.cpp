// glint bench cut — the shadow cutter's speed targets (issue 13, item 6):
//   (a) the ~550k-triangle Pipe Dream stand-in (pipedream/machine_room.h) with its two lights:
//       seconds, target ≤ 60 (ATI's brute force: about 20 minutes), median of the runs;
//   (b) time and peak memory as the stage grows 10k → 100k → 1M triangles, with the
//       exponent of time ∝ triangles^k fitted over them;
//   (c) throughput in clipped pairs per second, per CPU second, and how the exact
//       predicates were decided.
// The machine is shared: every row notes the load average it ran under, and rates are
// also given per CPU second of this process, which other processes do not change.
// GLINT_BENCH_CUT_SIZES=10000,100000 replaces the growth sizes; GLINT_BENCH_CUT_RUNS=N
// the runs of (a) (default 3); GLINT_BENCH_CUT_MODULES=N its stage size (default 63).
#include "glint/bench/bench.h"
#include "glint/core/log.h"
#include "glint/cut/cutter.h"
#include "glint/pipedream/machine_room.h"

#include <fmt/format.h>
#include <malloc.h>
#include <sys/resource.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace glint::bench {
namespace {

using Clock = std::chrono::steady_clock;

/// Peak resident memory since the last resetPeak() (Linux: VmHWM, reset through
/// /proc/self/clear_refs), so each run reports its own peak, not the process's so far.
/// Free heap pages go back to the system first (malloc_trim), so the new peak starts from
/// what the process really holds.
void resetPeak() {
  malloc_trim(0);
  std::ofstream("/proc/self/clear_refs") << "5";
}
double peakRssMiB() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

struct Run {
  double seconds = 0.0, cpuSeconds = 0.0, load = 0.0, peakMiB = 0.0;
  cut::CutResult result;
};

Run runCut(const Mesh& stage, const std::vector<cut::Light>& lights) {
  cut::CutOptions options;
  options.lights = lights;
  Run run;
  resetPeak();
  const double cpu = processCpuSeconds();
  const auto start = Clock::now();
  run.result = cut::cut(stage, options);
  run.seconds = secondsSince(start);
  run.cpuSeconds = processCpuSeconds() - cpu;
  run.load = loadAverage();
  run.peakMiB = peakRssMiB();  // the scene, the cut and its result
  return run;
}

std::vector<cut::Light> stageLights(const MachineRoomOptions& options) {
  const auto l = machineRoomLights(options);
  return {{.position = l[0], .name = "key"}, {.position = l[1], .name = "fill"}};
}

std::vector<std::size_t> growthSizes() {
  std::vector<std::size_t> sizes{10000, 100000, 1000000};
  if (const char* env = std::getenv("GLINT_BENCH_CUT_SIZES")) {
    sizes.clear();
    std::stringstream in(env);
    std::string item;
    while (std::getline(in, item, ',')) sizes.push_back(std::stoull(item));
  }
  return sizes;
}

void runSuite(Recorder& r) {
  const int threads = int(tbb::info::default_concurrency());
  // (b) growth first, smallest to largest, so each run's peak memory is its own.
  std::vector<double> logN, logT, logCpu;
  for (std::size_t target : growthSizes()) {
    const MachineRoomOptions options{.modules = machineRoomModulesFor(target)};
    const Mesh stage = makeMachineRoom(options);
    const Run run = runCut(stage, stageLights(options));
    const std::string group = "growth";
    const std::string name = fmt::format("{}k tris", stage.triangleCount() / 1000);
    r.record({.group = group, .name = name, .value = run.seconds, .unit = "s",
              .note = fmt::format("{:.1f} CPU s, {:.0f} pairs/CPU s, {} polygons out ({:.2f}×), {} triangles ({:.2f}×), peak {:.0f} MiB, load {:.2f}",
                                  run.cpuSeconds, double(run.result.stats.clippedPairs) / run.cpuSeconds,
                                  run.result.stats.outputPolygons,
                                  double(run.result.stats.outputPolygons) / double(stage.triangleCount()),
                                  run.result.stats.outputTriangles,
                                  double(run.result.stats.outputTriangles) / double(stage.triangleCount()), run.peakMiB,
                                  run.load)});
    logN.push_back(std::log(double(stage.triangleCount())));
    logT.push_back(std::log(run.seconds));
    logCpu.push_back(std::log(run.cpuSeconds));
  }
  // Least squares of log time against log size, for wall and CPU seconds.
  const auto fit = [&](const std::vector<double>& logY) {
    const double n = double(logN.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < logN.size(); ++i) {
      sx += logN[i];
      sy += logY[i];
      sxx += logN[i] * logN[i];
      sxy += logN[i] * logY[i];
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
  };
  if (logN.size() >= 2) {
    r.record({.group = "growth", .name = "exponent k (time ∝ n^k)", .value = fit(logT), .unit = "",
              .note = "wall seconds, least squares over the sizes above"});
    r.record({.group = "growth", .name = "exponent k, CPU seconds", .value = fit(logCpu), .unit = "",
              .note = "what the machine's load does not change"});
  }
  // (a) the Pipe Dream size.
  {
    MachineRoomOptions options{.modules = 63};
    if (const char* env = std::getenv("GLINT_BENCH_CUT_MODULES")) options.modules = std::max(1, std::atoi(env));
    const Mesh stage = makeMachineRoom(options);
    const auto lights = stageLights(options);
    const std::string group = fmt::format("{}k tris, 2 lights", stage.triangleCount() / 1000);
    int runs = 3;
    if (const char* env = std::getenv("GLINT_BENCH_CUT_RUNS")) runs = std::max(1, std::atoi(env));
    std::vector<Run> all;
    for (int i = 0; i < runs; ++i) {
      all.push_back(runCut(stage, lights));
      log::info("bench cut: {} triangles in {:.2f} s (load {:.2f})", stage.triangleCount(), all.back().seconds, all.back().load);
    }
    std::sort(all.begin(), all.end(), [](const Run& a, const Run& b) { return a.seconds < b.seconds; });
    const Run& median = all[all.size() / 2];
    const cut::CutStats& s = median.result.stats;
    r.record({.group = group, .name = "target (ATI: ~1200 s)", .value = 60.0, .unit = "s"});
    r.record({.group = group, .name = "cut (median)", .value = median.seconds, .unit = "s", .ratioTo = "target (ATI: ~1200 s)",
              .note = fmt::format("{} runs, {} threads, load {:.2f}; min {:.2f} max {:.2f}", runs, threads, median.load,
                                  all.front().seconds, all.back().seconds)});
    r.record({.group = group, .name = "cut (median), CPU", .value = median.cpuSeconds, .unit = "s",
              .note = "all threads: what the run costs whatever else the machine runs"});
    r.record({.group = group, .name = "prepare", .value = s.prepareSeconds, .unit = "s"});
    r.record({.group = group, .name = "cut receivers", .value = s.cutSeconds, .unit = "s"});
    r.record({.group = group, .name = "assemble", .value = s.assembleSeconds, .unit = "s"});
    r.record({.group = group, .name = "input triangles", .value = double(s.inputTriangles), .unit = ""});
    r.record({.group = group, .name = "output polygons", .value = double(s.outputPolygons), .unit = "", .ratioTo = "input triangles"});
    r.record({.group = group, .name = "output triangles", .value = double(s.outputTriangles), .unit = "", .ratioTo = "input triangles"});
    r.record({.group = group, .name = "polygons out per input triangle", .value = double(s.outputPolygons) / double(s.inputTriangles),
              .unit = "", .note = "convex pieces, after merging"});
    r.record({.group = group, .name = "triangles out per input triangle", .value = double(s.outputTriangles) / double(s.inputTriangles),
              .unit = "", .note = "target ≤ 1.5 (issue 24; 4.13 before the merge across triangles)"});
    r.record({.group = group, .name = "patches merged", .value = double(s.mergedPatches), .unit = "",
              .note = "sets of coplanar neighbours whose pieces merged across triangles"});
    r.record({.group = group, .name = "pieces before merge", .value = double(s.facesBeforeMerge), .unit = "", .ratioTo = "input triangles"});
    r.record({.group = group, .name = "candidates (near-beam query)", .value = double(s.candidates), .unit = "", .ratioTo = "input triangles"});
    r.record({.group = group, .name = "occluders (far beam meets A)", .value = double(s.occluders), .unit = "", .ratioTo = "input triangles"});
    r.record({.group = group, .name = "clipped pairs", .value = double(s.clippedPairs), .unit = "", .ratioTo = "input triangles"});
    r.record({.group = group, .name = "cuts (pairs that shadowed)", .value = double(s.cuts), .unit = "", .ratioTo = "input triangles"});
    r.record({.group = group, .name = "clipped pairs/s", .value = double(s.clippedPairs) / median.seconds, .unit = "pairs/s"});
    r.record({.group = group, .name = "clipped pairs/CPU s", .value = double(s.clippedPairs) / median.cpuSeconds, .unit = "pairs/s"});
    const double predicates = double(s.symbolicPredicates + s.filteredPredicates + s.exactPredicates);
    r.record({.group = group, .name = "predicates by name", .value = 100.0 * double(s.symbolicPredicates) / predicates, .unit = "%"});
    r.record({.group = group, .name = "predicates by interval", .value = 100.0 * double(s.filteredPredicates) / predicates, .unit = "%"});
    r.record({.group = group, .name = "predicates exact (GMP)", .value = 100.0 * double(s.exactPredicates) / predicates, .unit = "%",
              .note = fmt::format("{} of {:.0f}", s.exactPredicates, predicates)});
    for (const cut::LightStats& l : s.lights)
      r.record({.group = group, .name = "shadowed area " + l.name, .value = 100.0 * l.shadowedArea / (l.litArea + l.shadowedArea), .unit = "%"});
    r.record({.group = group, .name = "peak memory", .value = median.peakMiB, .unit = "MiB",
              .note = "resident, during the run (scene, cut, result)"});
  }
}

}  // namespace

/// The "cut" suite (bench/bench.cpp lists it).
void runCutSuite(Recorder& r) { runSuite(r); }

}  // namespace glint::bench
