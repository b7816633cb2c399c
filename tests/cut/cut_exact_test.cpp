// The cutter's predicates (src/cut/exact.h) against an independent exact computation:
// the vertex solved in GMP rationals (mpq_class), the plane evaluated there. Random
// configurations, exact coincidences built on purpose (concurrent planes, points on
// planes: zeros only exact arithmetic finds), and one-ulp perturbations of them.
#include "exact.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace glint::cut::exact;

namespace {

struct Q3 {
  mpq_class x, y, z;
};
Q3 q(const dvec3& p) { return {mpq_class(p.x), mpq_class(p.y), mpq_class(p.z)}; }
Q3 sub(const Q3& a, const Q3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Q3 cross(const Q3& a, const Q3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
mpq_class dot(const Q3& a, const Q3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

struct QPlane {
  Q3 n;
  mpq_class d;
  mpq_class at(const Q3& x) const { return dot(n, x) + d; }
};
QPlane qplane(const Geometry& g, const PlaneDef& def) {
  const Q3 a = q(g.point(def.p[0]));
  QPlane p{cross(sub(q(g.point(def.p[1])), a), sub(q(g.point(def.p[2])), a)), 0};
  p.d = -dot(p.n, a);
  return p;
}

/// The vertex solved exactly (Cramer's rule, or the line's parameter).
Q3 solve(const Geometry& g, const VertexDef& v) {
  if (v.kind == VertexKind::Point) return q(g.point(v.a));
  if (v.kind == VertexKind::LinePlane) {
    const QPlane pl = qplane(g, v.q);
    const Q3 a = q(g.point(v.a)), b = q(g.point(v.b));
    const mpq_class fa = pl.at(a), fb = pl.at(b);
    const mpq_class t = fa / (fa - fb);
    return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
  }
  const QPlane p[3] = {qplane(g, v.q), qplane(g, v.r), qplane(g, v.s)};
  const Q3 c12 = cross(p[1].n, p[2].n), c20 = cross(p[2].n, p[0].n), c01 = cross(p[0].n, p[1].n);
  const mpq_class det = dot(p[0].n, c12);
  return {-(p[0].d * c12.x + p[1].d * c20.x + p[2].d * c01.x) / det, -(p[0].d * c12.y + p[1].d * c20.y + p[2].d * c01.y) / det,
          -(p[0].d * c12.z + p[1].d * c20.z + p[2].d * c01.z) / det};
}

int oracleSide(const Geometry& g, const VertexDef& v, const PlaneDef& plane) { return sgn(qplane(g, plane).at(solve(g, v))); }

PlaneDef plane(std::uint32_t a, std::uint32_t b, std::uint32_t c) { return {{a, b, c}}; }

VertexDef linePlane(std::uint32_t a, std::uint32_t b, PlaneDef p) {
  VertexDef v;
  v.kind = VertexKind::LinePlane;
  v.a = a;
  v.b = b;
  v.q = p;
  return v;
}
VertexDef threePlanes(PlaneDef p, PlaneDef r, PlaneDef s) {
  VertexDef v;
  v.kind = VertexKind::ThreePlanes;
  v.q = p;
  v.r = r;
  v.s = s;
  return v;
}

bool independent(const Geometry& g, const VertexDef& v) {
  if (v.kind == VertexKind::LinePlane) {
    const QPlane pl = qplane(g, v.q);
    return pl.at(q(g.point(v.a))) != pl.at(q(g.point(v.b)));
  }
  const QPlane p[3] = {qplane(g, v.q), qplane(g, v.r), qplane(g, v.s)};
  return dot(p[0].n, cross(p[1].n, p[2].n)) != 0;
}

}  // namespace

TEST(CutExact, RandomVerticesAgreeWithRationals) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  std::vector<dvec3> points;
  for (int i = 0; i < 40; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  const Geometry g(points);
  std::uniform_int_distribution<std::uint32_t> id(0, 39);
  PredicateStats stats;
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    const PlaneDef p1 = plane(id(rng), id(rng), id(rng)), p2 = plane(id(rng), id(rng), id(rng)),
                   p3 = plane(id(rng), id(rng), id(rng)), test = plane(id(rng), id(rng), id(rng));
    if (g.degenerate(p1) || g.degenerate(p2) || g.degenerate(p3) || g.degenerate(test)) continue;
    for (const VertexDef& v : {linePlane(id(rng), id(rng), p1), threePlanes(p1, p2, p3)}) {
      if ((v.kind == VertexKind::LinePlane && v.a == v.b) || !independent(g, v)) continue;
      const VertexRec rec = g.vertex(v);
      ASSERT_EQ(g.side(rec, g.plane(test), stats), oracleSide(g, v, test));
      ++checked;
    }
  }
  EXPECT_GT(checked, 4000);
}

TEST(CutExact, BuiltInCoincidencesAreExactZeros) {
  // Planes through a common point X meet exactly at X; X lies on every other plane
  // through it, and so does the vertex, whatever its name. Random floats (24-bit
  // mantissas): the triple products overflow a double's 53 bits, so intervals cannot
  // certify these zeros and the exact path has to.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  PredicateStats stats;
  int zeros = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<dvec3> points{dvec3(u(rng), u(rng), u(rng))};  // X = point 0
    for (int i = 0; i < 10; ++i) points.emplace_back(u(rng), u(rng), u(rng));
    // Points on the line through X and point 1: X + k (p1 − X).
    for (int k = 2; k <= 3; ++k) points.push_back(points[0] + double(k) * (points[1] - points[0]));
    const Geometry g(points);
    const PlaneDef a = plane(0, 2, 3), b = plane(0, 4, 5), c = plane(0, 6, 7), test = plane(0, 8, 9);
    if (g.degenerate(a) || g.degenerate(b) || g.degenerate(c) || g.degenerate(test)) continue;
    const VertexDef v = threePlanes(a, b, c);
    if (!independent(g, v)) continue;
    const VertexRec rec = g.vertex(v);
    EXPECT_EQ(g.side(rec, g.plane(test), stats), 0);
    EXPECT_EQ(oracleSide(g, v, test), 0);
    // The line through points 11 and 12 (on the line X–p1) meets plane b at X exactly:
    // any plane through X and p1 holds the vertex.
    const VertexDef w = linePlane(11, 12, b);
    if (independent(g, w)) {
      EXPECT_EQ(g.side(g.vertex(w), g.plane(plane(1, 0, 9)), stats), 0);
      EXPECT_EQ(oracleSide(g, w, plane(1, 0, 9)), 0);
    }
    ++zeros;
  }
  EXPECT_GT(zeros, 150);
  EXPECT_GT(stats.exact, 150u);  // zeros that only exact arithmetic certifies
}

TEST(CutExact, OneUlpOffAPlaneIsNotOnIt) {
  // A vertex exactly on a plane, then the plane's third point moved by one ulp in each
  // direction: the sign flips, and the predicates see it as the rationals do.
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> u(-40, 40);
  PredicateStats stats;
  int flips = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<dvec3> points;
    for (int i = 0; i < 9; ++i) points.emplace_back(u(rng), u(rng), u(rng));
    points.push_back(points[0]);  // 9: the vertex's point again, to be nudged
    points[9].y = std::nextafter(points[9].y, trial % 2 ? 1e9 : -1e9);
    const Geometry g(points);
    // ThreePlanes through point 0; test plane through 9 (≈ 0) and two others.
    const PlaneDef a = plane(0, 1, 2), b = plane(0, 3, 4), c = plane(0, 5, 6), test = plane(9, 7, 8);
    if (g.degenerate(a) || g.degenerate(b) || g.degenerate(c) || g.degenerate(test)) continue;
    const VertexDef v = threePlanes(a, b, c);
    if (!independent(g, v)) continue;
    const int expected = oracleSide(g, v, test);
    EXPECT_EQ(g.side(g.vertex(v), g.plane(test), stats), expected);
    flips += expected != 0;
  }
  EXPECT_GT(flips, 200);
}

TEST(CutExact, OrderAlongALineMatchesRationals) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  std::vector<dvec3> points;
  for (int i = 0; i < 30; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  const Geometry g(points);
  PredicateStats stats;
  std::uniform_int_distribution<std::uint32_t> id(2, 29);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const PlaneDef p = plane(id(rng), id(rng), id(rng)), r = plane(id(rng), id(rng), id(rng));
    const VertexDef vp = linePlane(0, 1, p), vr = linePlane(0, 1, r);
    if (g.degenerate(p) || g.degenerate(r) || !independent(g, vp) || !independent(g, vr)) continue;
    // t along 0 → 1, exactly.
    const Q3 a = q(g.point(0)), b = q(g.point(1)), xp = solve(g, vp), xr = solve(g, vr);
    const Q3 ab = sub(b, a);
    const int expected = sgn(dot(sub(xp, a), ab) - dot(sub(xr, a), ab));
    EXPECT_EQ(g.compareAlongLine(0, 1, g.plane(p), g.plane(r), stats), expected);
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

#if defined(__SSE2__)
#include <xmmintrin.h>

TEST(CutExact, FlushToZeroOnTheThreadDoesNotFoolTheFilter) {
  // A plane value of about 1e-316, a subnormal: with flush-to-zero set on the calling
  // thread (as ray tracers ask for), an interval bound would become 0 and the sign look
  // certainly zero. The predicates clear those modes while they work.
  const Geometry g({dvec3(0.0), dvec3(1e-103, 0.0, 0.0), dvec3(0.0, 1e-103, 0.0), dvec3(0.0, 0.0, 1e-110)});
  const PlaneRec p = g.plane(plane(0, 1, 2));
  VertexDef v;
  v.kind = VertexKind::Point;
  v.a = 3;
  PredicateStats stats;
  const unsigned int saved = _mm_getcsr();
  _mm_setcsr(saved | 0x8040u);  // FTZ | DAZ
  const int inside = g.side(g.vertex(v), p, stats);
  const unsigned int after = _mm_getcsr();
  _mm_setcsr(saved);
  EXPECT_EQ(inside, 1);
  EXPECT_EQ(after & ~0x3Fu, (saved | 0x8040u) & ~0x3Fu);  // the caller's modes are given back (not the status flags)
}
#endif
