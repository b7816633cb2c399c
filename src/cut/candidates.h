#pragma once
// Candidate occluders: a bounding-volume hierarchy over the input triangles, queried with
// a convex volume (a receiver's near beam: the tetrahedron between it and the light).
//
// Embree's public API answers rays, point distances and box-box collisions, none of
// which bounds a long thin tetrahedron tightly, so the cutter keeps its own small BVH:
// binned SAH splits along the longest axis, four triangles per leaf, nodes tested against
// the volume's planes (a node is skipped when its box lies wholly outside one plane).
// The query is conservative (planes are relaxed by the caller): it may return
// triangles that do not touch the volume, never miss one that does. The exact cutting
// decides the rest.
#include "glint/core/math.h"

#include <cstdint>
#include <span>
#include <vector>

namespace glint::cut {

using dvec3 = glm::dvec3;
using dvec4 = glm::dvec4;

class TriangleBvh {
public:
  TriangleBvh() = default;
  /// Boxes of the triangles to index; `include[i]` false leaves triangle i out.
  TriangleBvh(std::span<const dvec3> lo, std::span<const dvec3> hi, std::span<const std::uint8_t> include);

  /// Appends to `out`, in ascending order, every included triangle whose box meets the
  /// box [lo, hi] and is not wholly outside any plane (outside: a·x + b·y + c·z + d > 0).
  void query(const dvec3& lo, const dvec3& hi, std::span<const dvec4> planes, std::vector<std::uint32_t>& out) const;

  std::size_t nodeCount() const { return m_nodes.size(); }
  std::size_t memoryBytes() const;

private:
  /// Boxes in float, rounded outwards: half the memory of doubles, so more of the tree
  /// stays in cache; the query stays conservative.
  struct Box {
    vec3 lo, hi;
  };
  struct Node {
    Box box;
    std::uint32_t first = 0;  ///< leaf: first index in m_order; inner: left child (right = left + 1)
    std::uint32_t count = 0;  ///< leaf: triangle count; inner: 0
  };
  void build(std::span<const dvec3> lo, std::span<const dvec3> hi, std::vector<dvec3>& centres);
  std::vector<Node> m_nodes;
  std::vector<std::uint32_t> m_order;  ///< triangles in leaf order
  std::vector<Box> m_boxes;            ///< their boxes, in the same order
};

}  // namespace glint::cut
