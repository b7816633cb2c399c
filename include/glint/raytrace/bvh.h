#pragma once
// glint/raytrace/bvh.h — a bounding volume hierarchy as flat arrays a GPU walks: built on the
// CPU by Embree's BVH builder (rtcBuildBVH, glint's own node layout), traversed by the GPU
// bake's compute shader (shaders/bake/trace.comp) and, for tests, by traverse() here: the
// same arithmetic on the CPU, no GL.
//
// Layout (std430, 32 bytes a node, 48 bytes a triangle):
//   BvhNode   lower.xyz, then `first`; upper.xyz, then `count`. An inner node (count 0) has
//             its two children at nodes[first] and nodes[first + 1]; a leaf has triangles
//             [first, first + count) of `triangles`. The root is nodes[0].
//   BvhTriangle  the three corners (vec4 each, w unused but the mesh's triangle id in a.w as
//             float bits), in leaf order: `ids` maps them back to the mesh's triangles.
// Children are adjacent so an inner node needs one index; the traversal tests both boxes
// and descends into the nearer first (closest hit) or either (any hit).
//
// The triangle test is watertight (Woop, Benthin and Wald 2013): a ray through a shared
// edge or vertex hits one of the triangles that meet there, never slips between them.
//
/// ```cpp run
/// const glint::Mesh torus = glint::makeTorus(1.0f, 0.35f, 64, 32);
/// const glint::raytrace::Bvh bvh = glint::raytrace::buildBvh(torus);
/// const auto hit = glint::raytrace::traverse(bvh, {.origin = {0, 0, -3}, .direction = {0, 0, 1}});
/// // hit->t ≈ 3 − 1.35: the torus's outer side along the axis
/// ```

#include "glint/core/math.h"
#include "glint/mesh/mesh.h"
#include "glint/raytrace/raytracer.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace glint::raytrace {

struct BvhNode {
  vec3 lower{0.0f};
  std::uint32_t first = 0;  ///< inner: the first child's index; leaf: the first triangle's
  vec3 upper{0.0f};
  std::uint32_t count = 0;  ///< 0: inner; else the leaf's triangle count
};
static_assert(sizeof(BvhNode) == 32, "BvhNode is std430's two vec4s");

struct BvhTriangle {
  vec4 a{0.0f}, b{0.0f}, c{0.0f};  ///< corners; w unused
};
static_assert(sizeof(BvhTriangle) == 48, "BvhTriangle is std430's three vec4s");

struct Bvh {
  std::vector<BvhNode> nodes;
  std::vector<BvhTriangle> triangles;  ///< in leaf order
  std::vector<std::uint32_t> ids;      ///< per triangle: its index in the mesh
  int depth = 0;                       ///< the longest root-to-leaf path (the traversal's stack bound)

  std::size_t bytes() const {
    return nodes.size() * sizeof(BvhNode) + triangles.size() * sizeof(BvhTriangle) + ids.size() * sizeof(std::uint32_t);
  }
};

struct BvhOptions {
  int maxLeafSize = 4;  ///< triangles a leaf holds at most
};

/// The hierarchy of `mesh`'s triangles (degenerate and non-finite ones left out: they never
/// hit, as in Scene). Error(Input) for a mesh beyond Embree's range (as Scene).
Bvh buildBvh(const Mesh& mesh, const BvhOptions& options = {});

/// The closest hit on [tnear, tfar] (Hit's fields as Scene gives them: t, triangle id in the
/// mesh, barycentrics u and v of corners 1 and 2; the normal is the triangle's geometric
/// one), through the GPU's arithmetic. `anyHit`: stop at the first hit found.
std::optional<Hit> traverse(const Bvh& bvh, const Ray& ray, bool anyHit = false);

}  // namespace glint::raytrace
