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

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace glint::cut {

/// Convex polygons, appended one after another.
struct ConvexPieces {
  std::vector<std::uint32_t> corners;  ///< vertex ids, counter-clockwise
  std::vector<std::uint8_t> straight;  ///< per corner: 1 when it lies on a straight side
  std::vector<std::uint32_t> end;      ///< per polygon: one past its last corner
  void clear() {
    corners.clear();
    straight.clear();
    end.clear();
  }
};

class RegionTriangulator {
public:
  explicit RegionTriangulator(const exact::Geometry& geometry);
  ~RegionTriangulator();
  RegionTriangulator(const RegionTriangulator&) = delete;
  RegionTriangulator& operator=(const RegionTriangulator&) = delete;

  /// The definition of vertex `id` (a receiver's vertex, or a merged mesh's).
  using Defs = std::function<const exact::VertexDef&(std::uint32_t id)>;

  /// A new plane: points are projected onto axes `axisU`, `axisV`; `corners` (a triangle of
  /// the plane, counter-clockwise about its normal) fix which way round the projection is.
  /// Exact positions are kept by id until the next reset().
  void reset(int axisU, int axisV, const std::array<exact::VertexDef, 3>& corners, Defs defs);

  /// Whether three vertices of the plane lie on one line, exactly.
  bool collinear(std::uint32_t a, std::uint32_t b, std::uint32_t c);

  /// Convex polygons covering the region bounded by the loops (the outline
  /// counter-clockwise, holes clockwise, about the plane's normal), appended to `out`: the
  /// region's constrained triangulation, then triangles joined across their diagonals
  /// while the union stays convex (Hertel and Mehlhorn's greedy pass: at most four times
  /// the fewest convex pieces). A polygon of n corners stands for n − 2 triangles, so the
  /// count is V + 2(L − 1) − 2 for V corners in L loops either way. `loopStart` has one
  /// entry per loop and the end. False (and nothing appended) when the loops do not bound
  /// a region the way they should (points that coincide, edges that cross): the caller
  /// keeps the region's pieces as they were then.
  bool triangulate(std::span<const std::uint32_t> loopVertices, std::span<const std::uint32_t> loopStart,
                   ConvexPieces& out);

private:
  struct Impl;
  std::unique_ptr<Impl> m;
};

}  // namespace glint::cut
