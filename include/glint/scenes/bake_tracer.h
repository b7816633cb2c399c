#pragma once
// glint/scenes/bake_tracer.h — rays through a raytrace::Bvh on the GPU: the hierarchy in
// storage buffers, one compute invocation a ray (shaders/bake/trace.comp), closest or any
// hit. The GPU bake's tracer; its arithmetic is raytrace::traverse()'s, so the same ray hits
// the same triangle as on the CPU (tests/bake/gpu_trace_test.cpp).
//
/// ```cpp
/// #include <glint/gl/context.h>
/// const auto context = glint::gl::HeadlessContext::create();
/// const glint::raytrace::Bvh bvh = glint::raytrace::buildBvh(glint::makeTorus());
/// glint::scenes::BakeTracer tracer(bvh);
/// const std::vector<glint::raytrace::Ray> rays = {{.origin = {0, 0, -3}, .direction = {0, 0, 1}}};
/// const std::vector<glint::scenes::BakeHit> hits = tracer.trace(rays);
/// ```
//
// Work goes up and answers come back in batches (one dispatch each) sized to take about
// 30 ms: the first batch is small, and each next one is scaled by how long the last took,
// so a desktop GPU stays responsive (no dispatch near the ~2 s at which drivers reset a
// GPU) and a large one is kept busy. Every call waits for its last batch. Memory: 32 bytes
// a node, 48 a triangle plus 4 for its id (Bvh::bytes()), 36 a triangle for the corner
// normals, and the batch buffers (`batch` items of at most 80 bytes up, 16 down).

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/raytrace/bvh.h"
#include "glint/raytrace/jobs.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace glint::scenes {

/// One ray's result as the GPU writes it.
struct BakeHit {
  float t = 0.0f;
  std::uint32_t triangle = kNoHit;  ///< the mesh's triangle; kNoHit: none
  float u = 0.0f, v = 0.0f;         ///< weights of corners 1 and 2
  static constexpr std::uint32_t kNoHit = 0xFFFFFFFFu;
  bool hit() const { return triangle != kNoHit; }
};
static_assert(sizeof(BakeHit) == 16, "BakeHit is the shader's HitOut");

class BakeTracer {
public:
  /// Uploads the hierarchy and, for curvature(), the mesh's corner normals (corner k of
  /// triangle t at cornerNormals[3t + k]; empty: curvature() is an error). Needs a current
  /// 4.5 context. Error(NoGpu) when the driver refuses the memory.
  explicit BakeTracer(const raytrace::Bvh& bvh, std::span<const vec3> cornerNormals = {},
                     std::size_t batch = std::size_t(1) << 18);
  /// Every ray's closest hit (`anyHit`: any hit, for occlusion), in order.
  std::vector<BakeHit> trace(std::span<const raytrace::Ray> rays, bool anyHit = false);
  /// The same hits as raytrace::Scene gives them (t, triangle, u, v, the geometric normal),
  /// so that code written against Scene::intersectBatch takes them unchanged.
  std::vector<std::optional<raytrace::Hit>> intersect(std::span<const raytrace::Ray> rays);
  /// The same into `hits` (one per ray).
  void intersect(std::span<const raytrace::Ray> rays, std::span<std::optional<raytrace::Hit>> hits);
  /// Each job's hemisphere rays (shaders/bake/hemisphere.comp).
  void hemisphere(std::span<const raytrace::HemisphereJob> jobs, std::span<raytrace::HemisphereSum> sums);
  /// Each job's curvature points (shaders/bake/curvature.comp).
  void curvature(std::span<const raytrace::CurvatureJob> jobs, float epsilon, std::span<raytrace::CurvatureSum> sums);
  std::size_t gpuBytes() const;
  /// Dispatches so far and the longest one (milliseconds, measured on the CPU around each).
  std::size_t dispatches() const { return m_dispatches; }
  double longestDispatchMs() const { return m_longestMs; }

private:
  /// `count` items through `program` in timed batches: `up` items of `upBytes` bytes in, `down`
  /// of `downBytes` out, `raysPerItem` to size the batch.
  void run(gl::Program& program, const void* up, std::size_t upBytes, void* down, std::size_t downBytes,
           std::size_t count, double raysPerItem);

  gl::Program m_trace, m_hemisphere, m_curvature;
  gl::Buffer m_nodes, m_triangles, m_ids, m_turns, m_cornerNormals, m_up, m_down;
  std::size_t m_batch;
  double m_raysPerDispatch = 1 << 14;  ///< what the next dispatch may trace (grows to ~30 ms)
  std::size_t m_dispatches = 0;
  double m_longestMs = 0.0;
  bool m_empty = false;
  bool m_normalsGiven = false;
  std::vector<vec3> m_normals;  ///< per mesh triangle: its unit geometric normal (zero when not in the BVH)
};

}  // namespace glint::scenes
