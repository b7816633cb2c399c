#pragma once
// The cutter's exact geometry: points, planes and implicit vertices, and the one
// predicate everything is decided by — on which side of a plane a vertex lies.
//
// Nothing here ever computes a coordinate that a later decision depends on. Points are
// the input's (welded positions and the lights, as doubles: exact copies of the input
// numbers). A plane is named by three of those points. A vertex made by a split is named
// by the planes or lines that meet there:
//
//   Point(p)               an input point
//   LinePlane(u, v, Q)     where the line through points u and v meets plane Q
//   ThreePlanes(P, Q, R)   where three planes meet
//
// so every predicate is a polynomial in the input numbers, and its sign is decided
// exactly: first in interval arithmetic (CGAL::Interval_nt, rounding upwards), which
// settles nearly every case in a few dozen flops; when the interval contains zero, again
// in exact multi-precision floating point (CGAL::Mpzf over GMP). Zeros that follow from
// the names alone (a vertex made on plane Q lies on Q; the shadow of a corner lies on
// every plane through the light and that corner) are answered from the names, without
// arithmetic. docs/cut.md has the argument and the measurements.
#include "glint/core/math.h"

#include <gmpxx.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace glint::cut::exact {

using dvec3 = glm::dvec3;

/// A plane through three points of the point table, oriented by their order: its normal
/// is (p1 − p0) × (p2 − p0) and its value at x is normal · (x − p0).
struct PlaneDef {
  std::array<std::uint32_t, 3> p{};
  /// The same plane whatever the order or orientation: the sorted point ids.
  std::array<std::uint32_t, 3> key() const;
  bool samePlaneAs(const PlaneDef& other) const { return key() == other.key(); }
  bool contains(std::uint32_t point) const { return p[0] == point || p[1] == point || p[2] == point; }
  /// The reversed orientation.
  PlaneDef flipped() const { return {{p[0], p[2], p[1]}}; }
};

// 32 bits: a VertexDef has no padding, so shard files are the same bytes on every run.
enum class VertexKind : std::uint32_t {
  Point,        ///< an input point: a
  LinePlane,    ///< line (a, b) meets plane q
  ThreePlanes,  ///< planes q, r and s meet
};

/// A vertex, by name. Two defs with the same fields are the same point; different defs
/// can be the same point too (equalAlongLine decides for points on one line).
struct VertexDef {
  VertexKind kind = VertexKind::Point;
  std::uint32_t a = 0, b = 0;  ///< Point: a; LinePlane: the line through a and b
  PlaneDef q, r, s;            ///< LinePlane: q; ThreePlanes: q, r, s
  bool operator==(const VertexDef& other) const;
  /// A hash of the name (for deduplication tables).
  std::uint64_t hash() const;
};

/// [lo, hi] with lo ≤ value ≤ hi, for the filter.
struct Range {
  double lo = 0.0, hi = 0.0;
};

/// A plane with its coefficients as intervals (n · x + d), computed once.
struct PlaneRec {
  PlaneDef def;
  std::array<Range, 4> coeffs{};  ///< a, b, c, d of a·x + b·y + c·z + d
  std::array<std::uint32_t, 3> key{};
};

/// A vertex with an interval box that contains it (infinite when its planes are too close
/// to parallel for the filter) and a midpoint approximation.
struct VertexRec {
  VertexDef def;
  std::array<Range, 3> box{};
  dvec3 approx{0.0};
  bool boxed = false;  ///< false: the box is unbounded, every test goes exact
};

/// Counters of how predicates were decided (per thread, summed by the caller).
struct PredicateStats {
  std::uint64_t symbolic = 0;  ///< answered from the names
  std::uint64_t filtered = 0;  ///< answered by interval arithmetic
  std::uint64_t exact = 0;     ///< needed multi-precision arithmetic
  void add(const PredicateStats& o) {
    symbolic += o.symbolic;
    filtered += o.filtered;
    exact += o.exact;
  }
};

/// The point table and the predicates over it. Read-only after construction: any number
/// of threads may use one Geometry, each with its own PredicateStats.
class Geometry {
public:
  explicit Geometry(std::vector<dvec3> points) : m_points(std::move(points)) {}
  const std::vector<dvec3>& points() const { return m_points; }
  const dvec3& point(std::uint32_t id) const { return m_points[id]; }

  PlaneRec plane(const PlaneDef& def) const;
  VertexRec vertex(const VertexDef& def) const;

  /// Sign (−1, 0, +1) of the plane's value at an input point, exactly.
  int side(std::uint32_t point, const PlaneRec& plane, PredicateStats& stats) const;
  int side(std::uint32_t point, const PlaneDef& plane, PredicateStats& stats) const;
  /// Sign of the plane's value at a vertex, exactly.
  int side(const VertexRec& v, const PlaneRec& plane, PredicateStats& stats) const;
  /// side() for several vertices against one plane (one rounding-mode switch).
  void sides(std::span<const VertexRec* const> vertices, const PlaneRec& plane, std::span<int> out,
             PredicateStats& stats) const;
  /// Whether the plane has a zero normal (its three points are collinear), exactly.
  bool degenerate(const PlaneDef& def) const;

  /// For two planes crossing the line through points u and v: sign of t(q) − t(r), with
  /// t the parameter of the crossing along u → v. 0 when they cross at the same point.
  int compareAlongLine(std::uint32_t u, std::uint32_t v, const PlaneRec& q, const PlaneRec& r,
                       PredicateStats& stats) const;

  /// The vertex's position, correctly rounded to about a double's precision (exact
  /// arithmetic where the box is wide), and exact where its name says the input's numbers
  /// are (snapped()).
  dvec3 position(const VertexRec& v) const;

  /// `x`, a position of vertex `def`, with the coordinates that the input fixes exactly
  /// made exact: a vertex that is an input point (a line's end on its plane; a point of one
  /// of three planes on the other two, decided exactly) is that point; a coordinate that
  /// every point of one of its lines or planes shares (an axis-aligned floor, wall or edge)
  /// is that coordinate. So a floor at y = 0 stays at y = 0, not −1e-16. A function of the
  /// name only: the same vertex gets the same position in every receiver and shard.
  dvec3 snapped(const VertexDef& def, dvec3 x) const;

  /// Sign of the dot product of the two planes' normals, exactly.
  int normalsDot(const PlaneDef& p, const PlaneDef& q) const;

  /// The vertex's coordinates as exact rationals: for the few constructions that need
  /// points, not signs against planes (regions.cpp triangulates with them).
  std::array<mpq_class, 3> exactPosition(const VertexDef& v) const;

private:
  int exactSide(const VertexDef& v, const PlaneDef& plane) const;
  /// position() before snapped().
  dvec3 rawPosition(const VertexRec& v) const;
  std::vector<dvec3> m_points;
};

/// Zero decided from the names alone: the vertex is on the plane by construction. Vertex
/// defs name their planes by key (PlaneDef::key), as the cutter makes them.
bool onPlaneByName(const VertexDef& v, const PlaneDef& plane);
bool onPlaneByName(const VertexDef& v, const PlaneDef& plane, const std::array<std::uint32_t, 3>& key);

}  // namespace glint::cut::exact
