#pragma once
// glint/bake/gpu_backend.h — the interface between the baker (GL-free) and a GPU that traces
// its rays: what `glint bake --device gpu` asks of one. glint's implementation is
// scenes/bake_gpu.h's bakeGpuBackend() (scenes/bake_tracer.h's compute shaders on a headless
// context); a program without one bakes on the CPU.
//
// The baker keeps every decision on the CPU: where the samples are, which ray each casts,
// which hit counts, how a texel is shaded. The GPU answers batches of questions:
//   closest()     the closest hit of each ray (the bake's first ray per sample),
//   hemisphere()  the rays of one sample's AO / bent normal (any hit: which escape) or
//                 thickness (closest hit: how far), generated on the GPU from the same
//                 stratified set the CPU uses, so 16–1,024 rays per sample never cross the bus,
//   curvature()   one sample's 8 points dropped onto the high poly (up to 3 crossings each).
// The answers are sums per sample; the baker turns them into texels exactly as on the CPU.
//
/// ```cpp
/// #include <glint/bake/baker.h>
/// glint::bake::BakeOptions options;
/// options.device = glint::bake::Device::Auto;  // the GPU when it is hardware and the bake fits
/// // options.gpu = backend.get(), with `const auto backend = glint::scenes::bakeGpuBackend();`
/// // (scenes/bake_gpu.h); without one, Auto bakes on the CPU.
/// // glint::bake::bake(low, high, options).stats.device: "gpu" or "cpu"; .deviceReason says why
/// ```

#include "glint/core/math.h"
#include "glint/mesh/mesh.h"
#include "glint/raytrace/jobs.h"
#include "glint/raytrace/raytracer.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace glint::bake {

/// Where a bake's rays are traced (`--device`).
enum class Device {
  Auto,  ///< the GPU when its renderer is hardware and the bake fits its memory; else the CPU
  Cpu,   ///< Embree on every core
  Gpu    ///< the GPU or an error (Error(NoGpu)): also a software renderer, which tests use
};

using raytrace::CurvatureJob;
using raytrace::CurvatureSum;
using raytrace::HemisphereJob;
using raytrace::HemisphereSum;

/// A high poly on the GPU (GpuBackend::upload): its BVH, triangles and corner normals.
class GpuScene {
public:
  virtual ~GpuScene() = default;
  /// Each ray's closest hit, as raytrace::Scene::intersect gives it (t, the mesh's triangle,
  /// u, v, the unit geometric normal); nullopt: none.
  virtual void closest(std::span<const raytrace::Ray> rays, std::span<std::optional<raytrace::Hit>> hits) = 0;
  virtual void hemisphere(std::span<const HemisphereJob> jobs, std::span<HemisphereSum> sums) = 0;
  /// `epsilon`: how far past a skipped surface the next crossing starts.
  virtual void curvature(std::span<const CurvatureJob> jobs, float epsilon, std::span<CurvatureSum> sums) = 0;
  virtual std::uint64_t bytes() const = 0;  ///< GPU memory it holds
  virtual std::size_t dispatches() const = 0;  ///< compute dispatches so far
  virtual double longestDispatchMs() const = 0;  ///< the longest of them
};

/// The device a backend started (GpuBackend::start).
struct GpuInfo {
  std::string renderer;                    ///< GL_RENDERER
  bool software = false;                   ///< llvmpipe, softpipe, SwiftShader
  std::optional<std::uint64_t> freeBytes;  ///< free memory as the driver reports it (NVX / ATI); nullopt: not reported
};

class GpuBackend {
public:
  virtual ~GpuBackend() = default;
  /// Whether every device EGL lists is a software rasterizer (known without a context).
  virtual bool onlySoftwareDevices() = 0;
  /// Makes the headless context the bake runs in (once; kept until the backend is destroyed)
  /// on the calling thread, which must be the thread that bakes. Error(NoGpu) without GL 4.5.
  virtual GpuInfo start(bool debug) = 0;
  /// Uploads `mesh`'s triangles (the scene's) and its corner normals (corner k of triangle t
  /// at cornerNormals[3t + k]). Error(NoGpu) when the driver refuses the memory.
  virtual std::unique_ptr<GpuScene> upload(const Mesh& mesh, const vec3* cornerNormals) = 0;
};

/// The GPU memory a high poly of `triangles` triangles needs at most (BVH, triangles, corner
/// normals, and the batches' buffers), for the check before upload.
std::uint64_t estimateGpuBytes(std::size_t triangles);

}  // namespace glint::bake
