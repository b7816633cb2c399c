#pragma once
// glint/raytrace/raytracer.h — ray queries against triangle meshes, through Embree 3.
//
// Contents
//   Ray             origin, direction, [tnear, tfar] interval
//   Hit             closest hit: t, mesh and triangle ids, barycentrics, geometric normal
//   SceneOptions    build quality, robust traversal
//   Scene           an immutable acceleration structure built from one or more glint::Mesh
//     intersect / occluded             one ray, on the calling thread
//     intersectBatch / occludedBatch   many rays, in parallel on oneTBB's workers
//     intersectCoherent                a small group of similar rays on the calling thread
//   interpolate     blend per-vertex attributes at a hit (normals, UVs, colours)
//
// Who uses it: the normal-map baker (rays from a low-poly surface to the high
// poly), the shadow oracle in the tests (one shadow ray per visible pixel:
// "is the light occluded?") and the shadow cutter. It never includes GL.
//
// A first example
//
/// ```cpp run
/// const glint::Mesh sphere = glint::makeUvSphere(1.0f, 64, 32);
/// const glint::raytrace::Scene scene(sphere);  // builds the BVH (Embree)
/// const glint::raytrace::Ray ray{.origin = {0, 0, 5}, .direction = {0, 0, -1}};
/// if (const auto hit = scene.intersect(ray)) {
///   const glint::vec3 p = ray.at(hit->t);  // ≈ (0, 0, 1)
///   const glint::vec3 n = glint::raytrace::interpolate(*hit, sphere.normals, sphere.indices);
///   const glint::vec3 toLight = glint::vec3(0, 10, 0) - p;  // a light at (0, 10, 0)
///   // tfar = 1: the segment ends at the light (direction is not unit length)
///   const bool blocked = scene.occluded({.origin = p, .direction = toLight, .tnear = 1e-4f, .tfar = 1.0f});
/// }
/// ```
//
// Semantics, spelled out
//   - Hits are accepted for tnear ≤ t ≤ tfar, both faces (no back-face culling).
//     Embree rays only go forward; to search behind the origin, cast a second ray
//     with the opposite direction (the baker does this for its "negative rays").
//   - `direction` need not be unit length; t is then measured in units of its
//     length (point = origin + t·direction). A zero direction never hits.
//   - Ties (a ray through a shared edge or vertex) are resolved by Embree; the
//     reported triangle is one of the candidates, the same one on every run for
//     the same scene and ray, whatever the thread count.
//   - Triangles with a non-finite vertex and degenerate (zero-area) triangles
//     never hit; they are kept so that triangle ids still match the mesh.
//   - Embree traces within ±kMaxCoordinate (its FLT_LARGE, 1.844e18) and aborts the
//     process beyond it: a finite vertex farther out is Error(Input) when the Scene is
//     built, and a ray whose origin or direction lies beyond it never hits.
//   - Self-intersection is the caller's business: offset the origin or raise
//     tnear (a shadow ray from a surface point needs tnear ≈ 1e-4·scene size).
//
// Threads and cost: building is parallel (Embree uses oneTBB) and takes about
// 0.2–0.5 s per million triangles on two cores at the default quality. Queries are
// const and thread-safe: any number of threads may call intersect()/occluded() on
// one Scene at once. The batched calls spread rays over oneTBB's arena, so
// tbb::global_control limits them too.

#include "glint/core/math.h"
#include "glint/mesh/mesh.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace glint::raytrace {

/// The largest coordinate (and direction component) Embree traces: its FLT_LARGE.
inline constexpr float kMaxCoordinate = 1.844e18f;

/// Error(Input) naming the first finite vertex beyond ±kMaxCoordinate ("<what>: vertex 7
/// at (1e+38, 0, 0) lies beyond ±1.844e+18, the range Embree traces"). Scene checks its
/// meshes with it; a caller whose rays start on another mesh (the baker's low poly) checks that one.
void checkRange(std::span<const vec3> positions, const std::string& what);

/// A ray: the points origin + t·direction for t in [tnear, tfar].
struct Ray {
  vec3 origin{0.0f};
  vec3 direction{0.0f, 0.0f, -1.0f};
  float tnear = 0.0f;                                      ///< smallest accepted t (≥ 0)
  float tfar = std::numeric_limits<float>::infinity();     ///< largest accepted t (≥ tnear)

  vec3 at(float t) const { return origin + t * direction; }
};

/// The closest intersection along a ray.
struct Hit {
  float t = 0.0f;               ///< ray parameter of the hit: point = ray.at(t)
  std::uint32_t mesh = 0;       ///< index of the mesh in the Scene (0 for a one-mesh scene)
  std::uint32_t triangle = 0;   ///< triangle index in that mesh: its corners are indices[3·triangle + 0..2]
  float u = 0.0f;               ///< barycentric weight of corner 1
  float v = 0.0f;               ///< barycentric weight of corner 2 (corner 0 gets 1 − u − v)
  vec3 geometricNormal{0.0f};   ///< unit face normal on the counter-clockwise (front) side; not
                                ///< flipped toward the ray — dot(normal, direction) > 0 means a back face
};

/// How a Scene is built. Zero/default-initialised is a good choice for most uses.
struct SceneOptions {
  enum class Quality {
    Fast,     ///< quickest build, slower queries: scenes rebuilt every frame
    Default,  ///< balanced (Embree's medium quality)
    High      ///< slower build with spatial splits, fastest queries: millions of rays
  };
  Quality quality = Quality::Default;
  /// Robust traversal: no missed hits on edges and vertices shared by triangles, at some
  /// speed cost. Watertight meshes hit by rays through their vertices (grid-aligned rays
  /// on grid meshes, exact poles) want it; random rays rarely need it.
  bool robust = false;
  /// Read the meshes' positions and indices where they are instead of copying them into
  /// the Scene: for a million-triangle mesh loaded without joining vertices, ~48 MB less
  /// to allocate, fault in and copy before the build. The meshes must then outlive the
  /// Scene, unchanged. Embree reads every vertex as 16 bytes, so a mesh whose positions
  /// have no spare capacity after the last vertex is copied all the same (loadMesh leaves
  /// one vertex of slack after the positions it reads from OBJ and PLY files).
  bool shareMeshes = false;
};

/// An acceleration structure over triangle meshes (positions and indices only; other
/// attributes stay in the caller's Mesh, to be looked up with interpolate()).
///
/// The Scene copies what it needs (unless SceneOptions::shareMeshes): the meshes may be
/// destroyed or changed afterwards (rebuild to see the changes). Move-only; owns its
/// Embree device and scene.
class Scene {
public:
  /// Builds from one mesh. Error(Input) when it has no triangles, an index count that is
  /// not a multiple of 3, or an index out of range.
  explicit Scene(const Mesh& mesh, const SceneOptions& options = {});
  /// Builds from several meshes; Hit::mesh is the position in `meshes`. Error(Input)
  /// when the list is empty or any mesh is empty or malformed (the message names it).
  explicit Scene(std::span<const Mesh> meshes, const SceneOptions& options = {});
  ~Scene();
  /// A moved-from Scene may only be destroyed or assigned to.
  Scene(Scene&& other) noexcept;
  Scene& operator=(Scene&& other) noexcept;
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  /// Closest hit in [tnear, tfar], or nothing.
  std::optional<Hit> intersect(const Ray& ray) const;
  /// True when anything lies in [tnear, tfar] (any hit, not the closest: cheaper).
  bool occluded(const Ray& ray) const;

  /// intersect() for every ray, in parallel; hits[i] answers rays[i]. Results do not
  /// depend on the thread count. Error(Usage) when the spans differ in size.
  void intersectBatch(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const;
  std::vector<std::optional<Hit>> intersectBatch(std::span<const Ray> rays) const;
  /// occluded() for every ray, in parallel; blocked[i] is 1 when rays[i] is occluded, else 0.
  void occludedBatch(std::span<const Ray> rays, std::span<std::uint8_t> blocked) const;
  std::vector<std::uint8_t> occludedBatch(std::span<const Ray> rays) const;

  /// intersect() for a group of coherent rays (neighbouring origins, similar directions: the
  /// samples of one texel, the pixels of a tile) on the calling thread, through Embree's
  /// stream interface, which traces them in SIMD packets: faster than one by one for such
  /// groups, the same answers. Error(Usage) when the spans differ in size.
  void intersectCoherent(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const;

  /// Union of the meshes' bounds (all vertices, including unreferenced ones).
  Bounds bounds() const;
  std::size_t meshCount() const;
  /// Triangles over all meshes (degenerate ones included).
  std::size_t triangleCount() const;
  /// Bytes Embree allocated for this scene (BVH and vertex/index copies), as reported by
  /// its memory monitor.
  std::size_t memoryBytes() const;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// Interpolates a per-vertex attribute at a hit on a one-mesh scene's mesh:
/// (1 − u − v)·a[i0] + u·a[i1] + v·a[i2], with i0..i2 the hit triangle's indices.
/// `attribute` must have one element per vertex (not checked in release builds).
template <typename T>
T interpolate(const Hit& hit, std::span<const T> attribute, std::span<const std::uint32_t> indices) {
  const std::size_t base = std::size_t(hit.triangle) * 3;
  return (1.0f - hit.u - hit.v) * attribute[indices[base]] + hit.u * attribute[indices[base + 1]] +
         hit.v * attribute[indices[base + 2]];
}
template <typename T>
T interpolate(const Hit& hit, const std::vector<T>& attribute, const std::vector<std::uint32_t>& indices) {
  return interpolate(hit, std::span<const T>(attribute), std::span<const std::uint32_t>(indices));
}

}  // namespace glint::raytrace
