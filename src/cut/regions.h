#pragma once
// The optimization step's second half: a receiver's light-mask regions triangulated again
// with only the vertices where their outlines turn or meet (receiver.cpp decides which).
//
// Merging convex faces leaves the lines of every beam that cut A: a lit region around a
// pipe's shadow is a ring of convex pieces whose corners are where beam planes crossed.
// A region bounded by V corners in L loops needs V + 2(L − 1) − 2 triangles and no other
// vertex, whatever the cuts were. The points are the vertices' exact rational coordinates
// projected onto A's two projection axes, and CGAL's constrained Delaunay triangulation
// over the exact kernel decides every orientation, so the result is as exact as the cut.
#include "exact.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace glint::cut {

class RegionTriangulator {
public:
  explicit RegionTriangulator(const exact::Geometry& geometry);
  ~RegionTriangulator();
  RegionTriangulator(const RegionTriangulator&) = delete;
  RegionTriangulator& operator=(const RegionTriangulator&) = delete;

  /// A new receiver: its points are projected onto axes `axisU`, `axisV`; `corners` (A's
  /// corners, counter-clockwise about A's normal) fix which way round the projection is.
  void reset(int axisU, int axisV, const std::array<exact::VertexDef, 3>& corners);

  /// Triangles covering the region bounded by the loops (the outline counter-clockwise,
  /// holes clockwise, about A's normal), appended to `triangles` as vertex ids, three each,
  /// counter-clockwise. `loopStart` has one entry per loop and the end; ids index `vertices`,
  /// whose exact positions are kept by id until reset(). False (and nothing appended) when
  /// the loops do not bound a region the way they should (points that coincide, edges that
  /// cross): the caller keeps the region's convex faces then.
  bool triangulate(std::span<const exact::VertexRec> vertices, std::span<const std::uint32_t> loopVertices,
                   std::span<const std::uint32_t> loopStart, std::vector<std::uint32_t>& triangles);

private:
  struct Impl;
  std::unique_ptr<Impl> m;
};

}  // namespace glint::cut
