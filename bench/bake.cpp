// glint bench bake — the normal mapper's speed targets (issue 6, item 10), each against a
// peer measured in the same run:
//   (a) 1024², 1 ray per texel: the whole `glint bake` run vs Blender's Cycles
//       "selected to active" bake of the same OBJ files (bench/peers/blender_bake.py);
//       "peer unavailable" when `blender` is not installed.
//   (b) 2048², 36 samples per texel, 1M-triangle high poly: seconds (target ≤ 20).
//   (c) ray throughput of the bake vs plain Embree rtcIntersect1 on the very same rays,
//       same BVH settings, same threads (target ≥ 70 %).
//   (d) time and memory as the high poly grows 10k → 100k → 1M triangles.
#include "glint/bake/baker.h"
#include "glint/bake/samples.h"
#include "glint/bench/bench.h"
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/raytrace/raytracer.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <sys/resource.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>

namespace glint::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// CPU seconds of this process, all threads: rates per CPU second do not depend on what
/// else the machine is running.
double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

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

constexpr int kWholeRunRepeats = 5, kPeerRepeats = 3, kThroughputRepeats = 3;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// Runs a command line, returns wall seconds, or a negative value when it failed.
double timeCommand(const std::string& command) {
  const auto start = Clock::now();
  const int status = std::system(command.c_str());
  return status == 0 ? since(start) : -1.0;
}

bool blenderAvailable() { return std::system("command -v blender >/dev/null 2>&1") == 0; }

fs::path self() { return fs::read_symlink("/proc/self/exe"); }

/// (a) the whole run, both tools from the same OBJ files.
void versusBlender(Recorder& r, const fs::path& dir) {
  const std::string group = "a: 1024² 1 ray";
  const Mesh low = lowPoly();
  const Mesh high = highPoly(262144);
  bake::writeObj(low, dir / "low.obj");
  bake::writeObj(high, dir / "high.obj");
  const std::string args = fmt::format("{} {} --size 1024x1024 --samples 1 --max-front 0.06 --max-rear 0.06 -q",
                                       shellQuote(dir / "low.obj"), shellQuote(dir / "high.obj"));
  // Medians of several runs: one run of either tool can be slowed by the machine's other load.
  std::vector<double> glintRuns;
  for (int i = 0; i < kWholeRunRepeats; ++i) {
    glintRuns.push_back(timeCommand(fmt::format("{} bake {} -o {}", shellQuote(self()), args, shellQuote(dir / "glint.png"))));
    if (glintRuns.back() < 0) fail(ErrorKind::Internal, "bench bake: `glint bake` failed");
  }
  const double glint = median(glintRuns);
  r.record({.group = group, .name = "glint bake (whole run)", .value = glint, .unit = "s",
            .note = fmt::format("median of {}; {} → {} triangles, OBJ load + bake + PNG", glintRuns.size(),
                                high.triangleCount(), low.triangleCount())});
  if (!blenderAvailable()) {
    r.record({.group = group, .name = "blender cycles", .value = std::nan(""), .unit = "s",
              .note = "peer unavailable: `blender` is not installed (apt install blender)"});
    return;
  }
  const fs::path script = fs::path(GLINT_SOURCE_DIR) / "bench" / "peers" / "blender_bake.py";
  std::vector<double> blenderRuns;
  for (int i = 0; i < kPeerRepeats; ++i) {
    blenderRuns.push_back(timeCommand(fmt::format("blender -b --factory-startup --python {} -- {} {} {} 1024 1 0.06 >/dev/null 2>&1",
                                                  shellQuote(script), shellQuote(dir / "low.obj"),
                                                  shellQuote(dir / "high.obj"), shellQuote(dir / "blender.png"))));
    if (blenderRuns.back() < 0) {
      r.record({.group = group, .name = "blender cycles", .value = std::nan(""), .unit = "s", .note = "peer failed"});
      return;
    }
  }
  const double blender = median(blenderRuns);
  r.record({.group = group, .name = "blender cycles", .value = blender, .unit = "s",
            .note = fmt::format("median of {}; whole run, same files", blenderRuns.size())});
  r.record({.group = group, .name = "speed-up (target ≥ 5)", .value = blender / glint, .unit = "×"});
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
  const double seconds = since(start), cpu = processCpuSeconds() - cpuStart;
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
  bake::bake(low, high, options);  // records the rays
  options.rayLog = nullptr;

  // Plain Embree: the same mesh, the same build settings as the baker's Scene (medium
  // quality, not robust), rtcIntersect1 on the same rays in the same order, spread over the
  // same TBB workers in chunks.
  RTCDevice device = rtcNewDevice("verbose=0");
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_MEDIUM);
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
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const raytrace::Ray& ray = rays[i];
        RTCRayHit rh{};
        rh.ray.org_x = ray.origin.x;
        rh.ray.org_y = ray.origin.y;
        rh.ray.org_z = ray.origin.z;
        rh.ray.dir_x = ray.direction.x;
        rh.ray.dir_y = ray.direction.y;
        rh.ray.dir_z = ray.direction.z;
        rh.ray.tnear = ray.tnear;
        rh.ray.tfar = ray.tfar;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
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
    plainWall.push_back(double(rays.size()) / since(start) / 1e6);
    plainCpu.push_back(double(rays.size()) / (processCpuSeconds() - cpuStart) / 1e6);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  const std::string what = fmt::format("{:.2f} M rays of the bake, {} triangles; medians of {} alternating runs",
                                       double(rays.size()) / 1e6, high.triangleCount(), kThroughputRepeats);
  r.record({.group = group, .name = "plain rtcIntersect1 /cpu-s", .value = median(plainCpu), .unit = "Mrays/s", .note = what});
  r.record({.group = group, .name = "glint bake /cpu-s (≥ 0.7)", .value = median(bakeCpu), .unit = "Mrays/s",
            .ratioTo = "plain rtcIntersect1 /cpu-s", .note = "whole tracing phase, per CPU second (load-independent)"});
  r.record({.group = group, .name = "plain rtcIntersect1 wall", .value = median(plainWall), .unit = "Mrays/s"});
  r.record({.group = group, .name = "glint bake wall", .value = median(bakeWall), .unit = "Mrays/s",
            .ratioTo = "plain rtcIntersect1 wall", .note = "wall clock: depends on the machine's other load"});
}

/// (d) scaling with the high poly.
void scaling(Recorder& r) {
  const Mesh low = lowPoly();
  for (int triangles : {10000, 100000, 1000000}) {
    const Mesh high = highPoly(triangles);
    const bake::BakeOptions options = bakeOptions(1024, 4);
    const auto start = Clock::now();
    const auto result = bake::bake(low, high, options);
    const double seconds = since(start);
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

void registerBakeSuite(Suites& suites) {
  suites.add({.name = "bake",
              .description = "normal mapper: vs Blender Cycles, 2048² 36 spp on 1M triangles, vs plain Embree, scaling",
              .run = [](Recorder& r) {
                const auto level = log::level();
                log::setLevel(log::Level::Error);  // the bakes' own warnings are not the bench's output
                const fs::path dir = fs::temp_directory_path() / fmt::format("glint-bench-bake-{}", getpid());
                fs::create_directories(dir);
                try {
                  scaling(r);
                  {
                    const Mesh low = lowPoly(), high = highPoly(1 << 20);
                    // (the ray log costs 32 B per ray: ~4 M rays each)
                    throughput(r, low, high, 2048, 1);
                    throughput(r, low, high, 1024, 4);
                  }
                  bigBake(r);
                  versusBlender(r, dir);
                } catch (...) {
                  fs::remove_all(dir);
                  log::setLevel(level);
                  throw;
                }
                fs::remove_all(dir);
                log::setLevel(level);
              }});
}

}  // namespace glint::bench
