// `glint bake --device gpu` (issue 48): every map the CPU bakes, baked on the GPU through
// scenes::bakeGpuBackend() (llvmpipe here, a GPU under scripts/gpu-check), equal to the CPU's
// bake of the same pair: the normal map within 1/255 on ≥ 99.9 % of the covered texels, AO
// within 1/255 in the mean, and every other map within 1/255 (or, for the float maps, 1e-4
// of its range) on ≥ 99.9 %. Equality is what is promised, not closeness: both bakes place the
// same samples, cast the same first rays, settle the same hits and make the same AO,
// thickness and curvature rays from the same seeds; the rest is where a ray grazes an edge
// (the GPU's triangle test is watertight, Embree's is not) and the GPU's last bits of
// arithmetic. The pairs are small (a 128² map in about a second on llvmpipe).
#include "glint/bake/baker.h"
#include "glint/bake/groups.h"
#include "glint/bake/samples.h"
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/gl/debug.h"
#include "glint/mesh/mesh.h"
#include "glint/scenes/bake_gpu.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>

using namespace glint;
namespace fs = std::filesystem;

namespace {

/// How far one map of two bakes differs: over the texels both cover, the share that differ by
/// more than `step` in some channel, and the mean difference.
struct Difference {
  double beyond = 0.0, mean = 0.0, largest = 0.0;
  std::size_t texels = 0;
};

Difference compare(const Image& a, const Image& b, const Image& coverage, double step) {
  Difference d;
  EXPECT_EQ(a.width(), b.width());
  EXPECT_EQ(a.channels(), b.channels());
  std::size_t beyond = 0;
  double sum = 0.0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      if (coverage.at(x, y, 0) < 0.99f) continue;  // the islands: what the bake itself wrote
      ++d.texels;
      bool differs = false;
      for (int c = 0; c < a.channels(); ++c) {
        const double e = std::fabs(double(a.at(x, y, c)) - double(b.at(x, y, c)));
        sum += e;
        d.largest = std::max(d.largest, e);
        differs = differs || e > step;
      }
      beyond += differs ? 1 : 0;
    }
  }
  d.beyond = d.texels ? double(beyond) / double(d.texels) : 0.0;
  d.mean = d.texels ? sum / double(d.texels * std::size_t(a.channels())) : 0.0;
  return d;
}

/// The CPU's and the GPU's bake of one pair with `options`, compared map by map.
void expectEqualBakes(const std::string& what, const auto& bakeWith, bake::BakeOptions options) {
  const auto backend = scenes::bakeGpuBackend();
  options.progress = false;
  options.device = bake::Device::Cpu;
  const bake::BakeResult cpu = bakeWith(options);
  options.device = bake::Device::Gpu;
  options.gpu = backend.get();
  options.gpuDebug = true;
  const std::uint64_t errorsBefore = gl::debugErrorCount();
  const bake::BakeResult gpu = bakeWith(options);
  EXPECT_EQ(gl::debugErrorCount(), errorsBefore) << what << ": the GL debug callback reported errors";
  EXPECT_EQ(cpu.stats.device, "cpu");
  EXPECT_EQ(gpu.stats.device, "gpu") << gpu.stats.deviceReason;
  EXPECT_GT(gpu.stats.gpuDispatches, 0u);
  // The same rays: the counts are exact (the GPU's waves count what the CPU casts).
  EXPECT_EQ(gpu.stats.samples, cpu.stats.samples) << what;
  EXPECT_EQ(gpu.stats.aoRays, cpu.stats.aoRays) << what;
  EXPECT_EQ(gpu.stats.thicknessRays, cpu.stats.thicknessRays) << what;
  EXPECT_EQ(gpu.stats.vertexMeasurements, cpu.stats.vertexMeasurements) << what;
  EXPECT_NEAR(double(gpu.stats.hits), double(cpu.stats.hits), 1e-4 * double(cpu.stats.samples)) << what;
  std::printf("[figure] %s: %llu samples, %llu hits (CPU %llu), %llu AO, %llu thickness, %llu curvature rays (CPU %llu); "
              "%zu dispatches, the longest %.0f ms, %.1f MiB on the GPU\n",
              what.c_str(), (unsigned long long)gpu.stats.samples, (unsigned long long)gpu.stats.hits,
              (unsigned long long)cpu.stats.hits, (unsigned long long)gpu.stats.aoRays,
              (unsigned long long)gpu.stats.thicknessRays, (unsigned long long)gpu.stats.curvatureRays,
              (unsigned long long)cpu.stats.curvatureRays, gpu.stats.gpuDispatches, gpu.stats.gpuLongestDispatchMs,
              double(gpu.stats.gpuBytes) / double(1 << 20));
  const Difference normal = compare(cpu.normal, gpu.normal, cpu.coverage, 1.0 / 255.0 + 1e-6);
  std::printf("[figure] %s: normal: %.4f %% of %zu texels beyond 1/255, largest %.2g\n", what.c_str(), 100.0 * normal.beyond,
              normal.texels, normal.largest);
  EXPECT_GT(normal.texels, 1000u) << what;
  EXPECT_LE(normal.beyond, 0.001) << what << ": the normal map";
  for (const bake::MapInfo& m : bake::mapTable()) {
    if (m.map == bake::Map::Normal || !options.maps.has(m.map)) continue;
    const Image& a = cpu.map(m.map);
    const Image& b = gpu.map(m.map);
    // Float maps in scene units (height, position, curvature): 1e-4 of the CPU map's range.
    double lo = 0.0, hi = 1.0;
    if (m.map == bake::Map::Height || m.map == bake::Map::Position || m.map == bake::Map::Curvature) {
      lo = 1e30;
      hi = -1e30;
      for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
          for (int c = 0; c < a.channels(); ++c) {
            lo = std::min(lo, double(a.at(x, y, c)));
            hi = std::max(hi, double(a.at(x, y, c)));
          }
    }
    const double step = m.map == bake::Map::Height || m.map == bake::Map::Position ? 1e-4 * (hi - lo) : (hi - lo) / 255.0;
    const Difference d = compare(a, b, cpu.coverage, step + 1e-7);
    std::printf("[figure] %s: %s: %.4f %% beyond %.3g, mean %.3g, largest %.3g\n", what.c_str(), m.name, 100.0 * d.beyond,
                step, d.mean, d.largest);
    EXPECT_LE(d.beyond, 0.001) << what << ": " << m.name;
    if (m.map == bake::Map::Ao) {
      EXPECT_LE(d.mean, 1.0 / 255.0) << what << ": AO's mean";
    }
  }
}

/// A stand-in GPU for what llvmpipe cannot show: a driver that reports little free memory,
/// an allocation that fails, a context lost in the middle of a bake.
class FakeBackend final : public bake::GpuBackend {
public:
  enum class Fault { None, UploadFails, LostDuringBake };
  FakeBackend(std::uint64_t freeBytes, Fault fault) : m_free(freeBytes), m_fault(fault) {}
  bool onlySoftwareDevices() override { return false; }
  bake::GpuInfo start(bool) override { return {.renderer = "Fake GPU", .software = false, .freeBytes = m_free}; }
  std::unique_ptr<bake::GpuScene> upload(const Mesh&, const vec3*) override {
    if (m_fault == Fault::UploadFails) fail(ErrorKind::NoGpu, "the GPU has not enough memory for the bake's 300 MiB");
    return std::make_unique<Scene>();
  }

private:
  struct Scene final : bake::GpuScene {
    void closest(std::span<const raytrace::Ray>, std::span<std::optional<raytrace::Hit>>) override {
      fail(ErrorKind::NoGpu, "the GPU was lost during the bake");
    }
    void hemisphere(std::span<const bake::HemisphereJob>, std::span<bake::HemisphereSum>) override {}
    void curvature(std::span<const bake::CurvatureJob>, float, std::span<bake::CurvatureSum>) override {}
    std::uint64_t bytes() const override { return 0; }
    std::size_t dispatches() const override { return 0; }
    double longestDispatchMs() const override { return 0.0; }
  };
  std::uint64_t m_free;
  Fault m_fault;
};

Mesh pushedOut(Mesh m, float by) {
  for (std::size_t i = 0; i < m.positions.size(); ++i) m.positions[i] += by * glm::normalize(m.normals[i]);
  return m;
}

}  // namespace

// The studded torus (closest hit either way, the sweep's path): every map the plain meshes
// have, thickness measured at the vertices of its small triangles (the vertex cache).
TEST(GpuBake, EveryMapOfTheStuddedTorusEqualsTheCpus) {
  log::setLevel(log::Level::Error);
  const Mesh low = makeTorus(1.0f, 0.35f, 48, 12);
  const Mesh high = bake::makeStuddedTorus({.segments = 96, .sides = 48});
  bake::BakeOptions options;
  options.width = options.height = 128;
  options.samples = 4;
  options.aoSamples = 16;
  for (const bake::Map m : {bake::Map::Ao, bake::Map::Height, bake::Map::MissMask, bake::Map::BentNormal,
                            bake::Map::Thickness, bake::Map::Curvature, bake::Map::Position, bake::Map::Opacity})
    options.maps.add(m);
  options.thicknessDistance = {0.3f, false};  // its triangles (edge ≤ 0.07) are small against it: measured at vertices
  expectEqualBakes("studded torus, every map", [&](const bake::BakeOptions& o) { return bake::bake(low, high, o); }, options);
  // The lean path (the normal map alone) and world space.
  bake::BakeOptions lean;
  lean.width = lean.height = 128;
  lean.space = NormalSpace::World;
  expectEqualBakes("studded torus, normal alone", [&](const bake::BakeOptions& o) { return bake::bake(low, high, o); }, lean);
}

// Front first, a cage, and bake groups (each group its own scene on the GPU, uploaded in turn).
TEST(GpuBake, FrontFirstCagesAndGroupsEqualTheCpus) {
  log::setLevel(log::Level::Error);
  const Mesh low = makeUvSphere(0.97f, 24, 12);
  const Mesh sphere = makeUvSphere(1.0f, 96, 48);
  bake::BakeOptions options;
  options.width = options.height = 96;
  options.samples = 4;
  options.maps.add(bake::Map::Ao);
  options.maps.add(bake::Map::Height);
  options.aoSamples = 8;
  options.selection = bake::HitSelection::FrontFirst;
  expectEqualBakes("sphere, front first", [&](const bake::BakeOptions& o) { return bake::bake(low, sphere, o); }, options);
  options.selection = bake::HitSelection::Closest;
  options.cage = pushedOut(low, 0.1f);
  expectEqualBakes("sphere, cage", [&](const bake::BakeOptions& o) { return bake::bake(low, sphere, o); }, options);
  options.cage.reset();

  // Two interpenetrating spheres, a group each (bake_groups_test.cpp's pair).
  const auto part = [](Mesh mesh, vec3 offset, float u0, const std::string& name) {
    for (vec3& p : mesh.positions) p += offset;
    if (u0 >= 0.0f)
      for (vec2& uv : mesh.uvs) uv = vec2(u0 + 0.02f + 0.46f * uv.x, 0.02f + 0.96f * uv.y);
    MeshParts parts;
    parts.mesh = std::move(mesh);
    parts.partNames = {name};
    parts.trianglePart.assign(parts.mesh.triangleCount(), 0);
    return parts;
  };
  const auto combined = [](const MeshParts& a, const MeshParts& b) {
    MeshParts all = a;
    all.mesh.append(b.mesh);
    all.partNames.push_back(b.partNames[0]);
    all.trianglePart.insert(all.trianglePart.end(), b.trianglePart.size(), 1);
    return all;
  };
  const vec3 ca(-0.4f, 0.0f, 0.0f), cb(0.4f, 0.0f, 0.0f);
  const MeshParts lowParts = combined(part(makeUvSphere(0.97f, 24, 12), ca, 0.0f, "a_low"),
                                      part(makeUvSphere(0.97f, 24, 12), cb, 0.5f, "b_low"));
  const MeshParts highParts = combined(part(sphere, ca, -1.0f, "a_high"), part(sphere, cb, -1.0f, "b_high"));
  const bake::GroupMatch match = bake::matchGroups(lowParts, highParts);
  ASSERT_EQ(match.groups.size(), 2u);
  options.maxFront = options.maxRear = {0.3f, false};
  expectEqualBakes("two spheres, bake groups",
                   [&](const bake::BakeOptions& o) { return bake::bake(lowParts, highParts, match, o); }, options);
}

// Which device, and why; the errors a user meets.
TEST(GpuBake, TheDeviceIsChosenAndSaid) {
  log::setLevel(log::Level::Error);
  const Mesh low = makeTorus(1.0f, 0.35f, 24, 8);
  const Mesh high = makeTorus(1.0f, 0.36f, 48, 24);
  bake::BakeOptions options;
  options.width = options.height = 32;
  options.progress = false;
  // No backend: auto is the CPU, gpu an error naming the option.
  EXPECT_EQ(bake::bake(low, high, options).stats.deviceReason, "--device auto: this program has no GPU backend");
  options.device = bake::Device::Gpu;
  try {
    bake::bake(low, high, options);
    ADD_FAILURE() << "--device gpu without a backend baked";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::NoGpu);
    EXPECT_STREQ(e.what(), "--device gpu: this program has no GPU backend");
  }
  // With one: auto takes the CPU on a software renderer and says so; the GPU on hardware.
  const auto backend = scenes::bakeGpuBackend();
  options.gpu = backend.get();
  options.device = bake::Device::Auto;
  const bake::BakeStats autoStats = bake::bake(low, high, options).stats;
  const bake::GpuInfo info = backend->start(false);
  std::printf("[figure] --device auto on %s: %s (%s)\n", info.renderer.c_str(), autoStats.device.c_str(),
              autoStats.deviceReason.c_str());
  if (info.software) {
    EXPECT_EQ(autoStats.device, "cpu");
    EXPECT_NE(autoStats.deviceReason.find("software"), std::string::npos) << autoStats.deviceReason;
  } else {
    EXPECT_EQ(autoStats.device, "gpu") << autoStats.deviceReason;
  }
  // Ctrl-C: a cancelled GPU bake stops between waves with Error(Interrupted).
  const std::atomic<bool> cancel{true};
  options.cancel = &cancel;
  options.device = bake::Device::Gpu;
  try {
    bake::bake(low, high, options);
    ADD_FAILURE() << "a cancelled bake finished";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Interrupted);
  }
}

// GPU memory is checked before anything is uploaded (the driver's free memory, as
// GL_NVX_gpu_memory_info and GL_ATI_meminfo report it): auto then bakes on the CPU and says
// why, gpu stops with one line. A failed allocation or a context lost mid-bake is an error,
// never a map.
TEST(GpuBake, TooLittleGpuMemoryAndALostGpuAreSaid) {
  log::setLevel(log::Level::Error);
  const Mesh low = makeTorus(1.0f, 0.35f, 24, 8);
  const Mesh high = bake::makeStuddedTorus({.segments = 256, .sides = 128});  // 65k triangles: ~33 MiB
  bake::BakeOptions options;
  options.width = options.height = 32;
  options.progress = false;
  FakeBackend small(16u << 20, FakeBackend::Fault::None);
  options.gpu = &small;
  const bake::BakeStats stats = bake::bake(low, high, options).stats;
  EXPECT_EQ(stats.device, "cpu");
  EXPECT_EQ(stats.deviceReason, "--device auto: the high poly's 65536 triangles need about 34 MiB of GPU memory; the "
                                "driver reports 16 MiB free");
  options.device = bake::Device::Gpu;
  const auto expectNoGpu = [&](const std::string& message) {
    try {
      bake::bake(low, high, options);
      ADD_FAILURE() << "baked: " << message;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::NoGpu);
      EXPECT_EQ(std::string(e.what()), message);
    }
  };
  expectNoGpu("--device gpu: the high poly's 65536 triangles need about 34 MiB of GPU memory; the driver reports 16 MiB free");
  FakeBackend refuses(1u << 30, FakeBackend::Fault::UploadFails);
  options.gpu = &refuses;
  expectNoGpu("the GPU has not enough memory for the bake's 300 MiB");
  FakeBackend lost(1u << 30, FakeBackend::Fault::LostDuringBake);
  options.gpu = &lost;
  expectNoGpu("the GPU was lost during the bake");
  options.device = bake::Device::Auto;  // auto chose the GPU: its failure is the bake's, not a silent CPU rerun
  expectNoGpu("the GPU was lost during the bake");
}
