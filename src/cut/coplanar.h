#pragma once
// The optimization step across input triangles (merge.cpp, step 3b): pieces of coplanar
// neighbours with the same light mask are merged, and the vertices that then lie inside a
// region or on a straight outline between two regions are dropped.
//
// A *patch* is a set of input triangles of one connected surface joined across manifold
// edges where both triangles lie in one plane (decided exactly), face the same way and
// wind consistently (and, when the caller gives merge groups, share a group). Within a
// patch, every vertex on the patch's outline that another patch uses stays, so the mesh
// stays watertight; a vertex inside the patch, or on an open edge of the surface, is
// dropped where no region outline turns or meets another there, and each region that lost a vertex is triangulated
// again from its outlines (regions.h). A region of V corners in L loops then needs
// V + 2(L − 1) − 2 triangles: a floor of a thousand grid cells in one light is a handful
// of triangles around its shadows.
#include "exact.h"
#include "pieces.h"

#include <cstdint>
#include <span>
#include <vector>

namespace glint::cut {

struct CoplanarInput {
  const Prepared& prep;
  std::span<const std::uint32_t> polygonFirst;  ///< per triangle, and the end: its polygons in `polygons`
  std::span<const exact::VertexDef> defs;       ///< every vertex id's name
  std::span<const std::uint32_t> groups;        ///< per triangle, or empty: merge only within a group
  std::span<const std::uint8_t> shared = {};    ///< per vertex id: used by two patches (mergeCoplanar fills it)
};

/// Which patch each triangle belongs to: the lowest triangle of its patch (itself when
/// alone).
std::vector<std::uint32_t> coplanarPatches(const CoplanarInput& in);

/// `polygons` (corners are vertex ids, polygons in triangle order) with each patch's pieces
/// merged; the merged pieces' source is the patch's lowest triangle, and they come in its
/// place. `merged` counts the patches that changed; a patch that did not change becomes its
/// triangles again in `patch` (each its own).
CutMesh mergeCoplanar(CoplanarInput in, std::vector<std::uint32_t>& patch, const CutMesh& polygons,
                      std::uint64_t& merged);

}  // namespace glint::cut
