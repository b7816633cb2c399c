// The exact predicates (exact.h). This file is compiled with -frounding-math: the
// interval filter runs with the rounding mode set upwards (CGAL::Protect_FPU_rounding)
// and the compiler must not fold or reorder floating-point operations across that.
#include "exact.h"

#include "glint/core/hash.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint::cut::exact {

namespace {

using I = CGAL::Interval_nt<false>;  // needs the rounding mode upwards: see Guard

#if defined(__SSE2__)
/// Rounding upwards for the interval filter, and no flush-to-zero or denormals-are-zero
/// while it runs: with those (Embree asks applications to set them on threads that trace
/// rays, and a process may do both) a tiny interval bound would become 0 and a sign
/// uncertain in truth could look certain. The whole MXCSR is restored afterwards.
class Guard {
public:
  Guard() : m_saved(_mm_getcsr()) { _mm_setcsr((m_saved & ~(0x8000u | 0x0040u | _MM_ROUND_MASK)) | _MM_ROUND_UP); }
  ~Guard() { _mm_setcsr(m_saved); }
  Guard(const Guard&) = delete;
  Guard& operator=(const Guard&) = delete;

private:
  unsigned int m_saved;
};
#else
using Guard = CGAL::Protect_FPU_rounding<true>;
#endif
using E = CGAL::Mpzf;

/// A 3-vector of an exact or interval number type: the same arithmetic for both.
template <class T>
struct V3 {
  T x, y, z;
};
template <class T>
V3<T> sub(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
T dot(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
V3<T> to(const dvec3& p) {
  return {T(p.x), T(p.y), T(p.z)};
}
using I3 = V3<I>;
using E3 = V3<E>;
I3 toI(const dvec3& p) { return to<I>(p); }
E3 toE(const dvec3& p) { return to<E>(p); }

int signOf(const E& e) { return int(e.sign()); }

/// The sign of an interval when it is certain: +1, −1, 0 (only for [0, 0]); 2 when not.
constexpr int kUnsure = 2;
int signOf(const I& v) {
  if (v.inf() > 0.0) return 1;
  if (v.sup() < 0.0) return -1;
  if (v.inf() == 0.0 && v.sup() == 0.0) return 0;
  return kUnsure;
}

Range range(const I& v) { return {v.inf(), v.sup()}; }
I interval(const Range& r) { return I(r.lo, r.hi); }

/// An exact plane: n · x + d.
struct EPlane {
  E3 n;
  E d;
};

}  // namespace

std::array<std::uint32_t, 3> PlaneDef::key() const {
  std::array<std::uint32_t, 3> k = p;
  if (k[0] > k[1]) std::swap(k[0], k[1]);
  if (k[1] > k[2]) std::swap(k[1], k[2]);
  if (k[0] > k[1]) std::swap(k[0], k[1]);
  return k;
}

bool VertexDef::operator==(const VertexDef& o) const {
  return kind == o.kind && a == o.a && b == o.b && q.p == o.q.p && r.p == o.r.p && s.p == o.s.p;
}

std::uint64_t VertexDef::hash() const {
  Fnv1a h;
  h.add(std::uint32_t(kind)).add(a).add(b);
  for (const PlaneDef* p : {&q, &r, &s}) h.add(p->p);
  return h.value();
}

bool onPlaneByName(const VertexDef& v, const PlaneDef& plane) { return onPlaneByName(v, plane, plane.key()); }

bool onPlaneByName(const VertexDef& v, const PlaneDef& plane, const std::array<std::uint32_t, 3>& key) {
  // The planes a VertexDef names are stored by key (vertex defs are canonical).
  switch (v.kind) {
    case VertexKind::Point: return plane.contains(v.a);
    case VertexKind::LinePlane: return (plane.contains(v.a) && plane.contains(v.b)) || v.q.p == key;
    case VertexKind::ThreePlanes: return v.q.p == key || v.r.p == key || v.s.p == key;
  }
  return false;
}

PlaneRec Geometry::plane(const PlaneDef& def) const {
  PlaneRec rec;
  rec.def = def;
  rec.key = def.key();
  Guard guard;
  const I3 p0 = toI(point(def.p[0]));
  const I3 n = cross(sub(toI(point(def.p[1])), p0), sub(toI(point(def.p[2])), p0));
  const I d = -dot(n, p0);
  rec.coeffs = {range(n.x), range(n.y), range(n.z), range(d)};
  return rec;
}

bool Geometry::degenerate(const PlaneDef& def) const {
  const E3 p0 = toE(point(def.p[0]));
  const E3 n = cross(sub(toE(point(def.p[1])), p0), sub(toE(point(def.p[2])), p0));
  return n.x.sign() == CGAL::ZERO && n.y.sign() == CGAL::ZERO && n.z.sign() == CGAL::ZERO;
}

namespace {

/// Interval value of a plane at a box.
I evalBox(const PlaneRec& plane, const std::array<Range, 3>& box) {
  return interval(plane.coeffs[0]) * interval(box[0]) + interval(plane.coeffs[1]) * interval(box[1]) +
         interval(plane.coeffs[2]) * interval(box[2]) + interval(plane.coeffs[3]);
}

I evalPoint(const PlaneRec& plane, const dvec3& p) {
  return interval(plane.coeffs[0]) * I(p.x) + interval(plane.coeffs[1]) * I(p.y) +
         interval(plane.coeffs[2]) * I(p.z) + interval(plane.coeffs[3]);
}

}  // namespace

VertexRec Geometry::vertex(const VertexDef& def) const {
  VertexRec rec;
  rec.def = def;
  {
    Guard guard;
    switch (def.kind) {
      case VertexKind::Point: {
        const dvec3& p = point(def.a);
        rec.box = {Range{p.x, p.x}, Range{p.y, p.y}, Range{p.z, p.z}};
        rec.boxed = true;
        break;
      }
      case VertexKind::LinePlane: {
        const PlaneRec q = plane(def.q);
        const dvec3& a = point(def.a);
        const dvec3& b = point(def.b);
        const I qa = evalPoint(q, a);
        const I den = qa - evalPoint(q, b);
        if (signOf(den) == 1 || signOf(den) == -1) {
          const I t = qa / den;
          const I3 ia = toI(a);
          const I3 x{ia.x + t * (I(b.x) - ia.x), ia.y + t * (I(b.y) - ia.y), ia.z + t * (I(b.z) - ia.z)};
          rec.box = {range(x.x), range(x.y), range(x.z)};
          rec.boxed = true;
        }
        break;
      }
      case VertexKind::ThreePlanes: {
        const PlaneRec planes[3] = {plane(def.q), plane(def.r), plane(def.s)};
        I3 n[3];
        I d[3];
        for (int i = 0; i < 3; ++i) {
          n[i] = {interval(planes[i].coeffs[0]), interval(planes[i].coeffs[1]), interval(planes[i].coeffs[2])};
          d[i] = interval(planes[i].coeffs[3]);
        }
        const I3 c12 = cross(n[1], n[2]), c20 = cross(n[2], n[0]), c01 = cross(n[0], n[1]);
        const I det = dot(n[0], c12);
        if (signOf(det) == 1 || signOf(det) == -1) {
          const I3 num{-(d[0] * c12.x + d[1] * c20.x + d[2] * c01.x), -(d[0] * c12.y + d[1] * c20.y + d[2] * c01.y),
                       -(d[0] * c12.z + d[1] * c20.z + d[2] * c01.z)};
          const I3 x{num.x / det, num.y / det, num.z / det};
          rec.box = {range(x.x), range(x.y), range(x.z)};
          rec.boxed = true;
        }
        break;
      }
    }
  }
  // Finite boxes only: an overflow to infinity makes the box useless.
  if (rec.boxed)
    for (const Range& r : rec.box)
      if (!std::isfinite(r.lo) || !std::isfinite(r.hi)) rec.boxed = false;
  if (rec.boxed) {
    rec.approx = dvec3(0.5 * (rec.box[0].lo + rec.box[0].hi), 0.5 * (rec.box[1].lo + rec.box[1].hi),
                       0.5 * (rec.box[2].lo + rec.box[2].hi));
  } else {
    const double inf = std::numeric_limits<double>::infinity();
    rec.box = {Range{-inf, inf}, Range{-inf, inf}, Range{-inf, inf}};
    rec.approx = position(rec);
  }
  return rec;
}

int Geometry::side(std::uint32_t p, const PlaneRec& plane, PredicateStats& stats) const {
  return side(p, plane.def, stats);
}

int Geometry::side(std::uint32_t p, const PlaneDef& plane, PredicateStats& stats) const {
  if (plane.contains(p)) {
    ++stats.symbolic;
    return 0;
  }
  // Four input points: CGAL's own orientation predicate (a static error bound first,
  // then intervals, then exact), the same sign as n · (x − p0).
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const auto cg = [&](std::uint32_t id) {
    const dvec3& q = point(id);
    return K::Point_3(q.x, q.y, q.z);
  };
  ++stats.filtered;
  return int(CGAL::orientation(cg(plane.p[0]), cg(plane.p[1]), cg(plane.p[2]), cg(p)));
}

int Geometry::side(const VertexRec& v, const PlaneRec& plane, PredicateStats& stats) const {
  if (onPlaneByName(v.def, plane.def, plane.key)) {
    ++stats.symbolic;
    return 0;
  }
  if (v.boxed) {
    int s;
    {
      Guard guard;
      s = signOf(evalBox(plane, v.box));
    }
    if (s != kUnsure) {
      ++stats.filtered;
      return s;
    }
  }
  ++stats.exact;
  return exactSide(v.def, plane.def);
}

void Geometry::sides(std::span<const VertexRec* const> vertices, const PlaneRec& plane, std::span<int> out,
                     PredicateStats& stats) const {
  {
    Guard guard;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      const VertexRec& v = *vertices[i];
      if (onPlaneByName(v.def, plane.def, plane.key)) {
        ++stats.symbolic;
        out[i] = 0;
      } else if (v.boxed) {
        out[i] = signOf(evalBox(plane, v.box));
        if (out[i] != kUnsure) ++stats.filtered;
      } else {
        out[i] = kUnsure;
      }
    }
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (out[i] != kUnsure) continue;
    ++stats.exact;
    out[i] = exactSide(vertices[i]->def, plane.def);
  }
}

namespace {

/// n · (x − p0) exactly, the plane through a, b, c at x.
E evalExact(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& x) {
  const E3 p0 = toE(a);
  const E3 n = cross(sub(toE(b), p0), sub(toE(c), p0));
  return dot(n, sub(toE(x), p0));
}

EPlane planeExact(const dvec3& a, const dvec3& b, const dvec3& c) {
  const E3 p0 = toE(a);
  EPlane pl;
  pl.n = cross(sub(toE(b), p0), sub(toE(c), p0));
  pl.d = -dot(pl.n, p0);
  return pl;
}

E det3(const E3& a, const E3& b, const E3& c) { return dot(a, cross(b, c)); }

}  // namespace

int Geometry::exactSide(const VertexDef& v, const PlaneDef& plane) const {
  const dvec3& r0 = point(plane.p[0]);
  const dvec3& r1 = point(plane.p[1]);
  const dvec3& r2 = point(plane.p[2]);
  switch (v.kind) {
    case VertexKind::Point: return signOf(evalExact(r0, r1, r2, point(v.a)));
    case VertexKind::LinePlane: {
      const dvec3& q0 = point(v.q.p[0]);
      const dvec3& q1 = point(v.q.p[1]);
      const dvec3& q2 = point(v.q.p[2]);
      const E qa = evalExact(q0, q1, q2, point(v.a));
      const E qb = evalExact(q0, q1, q2, point(v.b));
      const E ra = evalExact(r0, r1, r2, point(v.a));
      const E rb = evalExact(r0, r1, r2, point(v.b));
      return signOf(qa * rb - qb * ra) * signOf(qa - qb);
    }
    case VertexKind::ThreePlanes: {
      EPlane m[4];
      const PlaneDef* defs[4] = {&v.q, &v.r, &v.s, &plane};
      for (int i = 0; i < 4; ++i)
        m[i] = planeExact(point(defs[i]->p[0]), point(defs[i]->p[1]), point(defs[i]->p[2]));
      // det4 of the rows (n_i, d_i), expanded along the last column: Σ ±d_i · det3(the other normals).
      const E det4 = -m[0].d * det3(m[1].n, m[2].n, m[3].n) + m[1].d * det3(m[0].n, m[2].n, m[3].n) -
                     m[2].d * det3(m[0].n, m[1].n, m[3].n) + m[3].d * det3(m[0].n, m[1].n, m[2].n);
      return signOf(det4) * signOf(det3(m[0].n, m[1].n, m[2].n));
    }
  }
  return 0;
}

int Geometry::normalsDot(const PlaneDef& p, const PlaneDef& q) const {
  const EPlane a = planeExact(point(p.p[0]), point(p.p[1]), point(p.p[2]));
  const EPlane b = planeExact(point(q.p[0]), point(q.p[1]), point(q.p[2]));
  return signOf(dot(a.n, b.n));
}

std::array<mpq_class, 3> Geometry::exactPosition(const VertexDef& v) const {
  const auto q3 = [](const E3& e) { return std::array<mpq_class, 3>{mpq_class(e.x), mpq_class(e.y), mpq_class(e.z)}; };
  switch (v.kind) {
    case VertexKind::Point: break;
    case VertexKind::LinePlane: {
      // a + t (b − a) with t = Q(a) / (Q(a) − Q(b)): (Q(a) b − Q(b) a) / (Q(a) − Q(b)).
      const dvec3 &q0 = point(v.q.p[0]), &q1 = point(v.q.p[1]), &q2 = point(v.q.p[2]);
      const E qa = evalExact(q0, q1, q2, point(v.a)), qb = evalExact(q0, q1, q2, point(v.b));
      const E3 a = toE(point(v.a)), b = toE(point(v.b));
      const mpq_class w(qa - qb);
      std::array<mpq_class, 3> x = q3({qa * b.x - qb * a.x, qa * b.y - qb * a.y, qa * b.z - qb * a.z});
      for (mpq_class& c : x) c /= w;
      return x;
    }
    case VertexKind::ThreePlanes: {
      // n_i · x + d_i = 0 for the three planes: x = −(d_q n_r×n_s + d_r n_s×n_q + d_s n_q×n_r) / det(n_q, n_r, n_s).
      const PlaneDef* defs[3] = {&v.q, &v.r, &v.s};
      EPlane m[3];
      for (int i = 0; i < 3; ++i) m[i] = planeExact(point(defs[i]->p[0]), point(defs[i]->p[1]), point(defs[i]->p[2]));
      const E3 rs = cross(m[1].n, m[2].n), sq = cross(m[2].n, m[0].n), qr = cross(m[0].n, m[1].n);
      const mpq_class w(-dot(m[0].n, rs));
      std::array<mpq_class, 3> x = q3({m[0].d * rs.x + m[1].d * sq.x + m[2].d * qr.x, m[0].d * rs.y + m[1].d * sq.y + m[2].d * qr.y,
                                        m[0].d * rs.z + m[1].d * sq.z + m[2].d * qr.z});
      for (mpq_class& c : x) c /= w;
      return x;
    }
  }
  const dvec3& p = point(v.a);
  return {mpq_class(p.x), mpq_class(p.y), mpq_class(p.z)};
}

int Geometry::compareAlongLine(std::uint32_t u, std::uint32_t v, const PlaneRec& q, const PlaneRec& r,
                               PredicateStats& stats) const {
  if (q.key == r.key) {
    ++stats.symbolic;
    return 0;
  }
  // t(q) − t(r) has the sign of (r(u)·q(v) − q(u)·r(v)) · sign(q(u) − q(v)) · sign(r(u) − r(v)).
  {
    Guard guard;
    const I qu = evalPoint(q, point(u)), qv = evalPoint(q, point(v));
    const I ru = evalPoint(r, point(u)), rv = evalPoint(r, point(v));
    const int a = signOf(ru * qv - qu * rv), b = signOf(qu - qv), c = signOf(ru - rv);
    if (a != kUnsure && b != kUnsure && c != kUnsure) {
      ++stats.filtered;
      return a * b * c;
    }
  }
  ++stats.exact;
  const auto eval = [&](const PlaneDef& pl, std::uint32_t x) {
    return evalExact(point(pl.p[0]), point(pl.p[1]), point(pl.p[2]), point(x));
  };
  const E qu = eval(q.def, u), qv = eval(q.def, v), ru = eval(r.def, u), rv = eval(r.def, v);
  return signOf(ru * qv - qu * rv) * signOf(qu - qv) * signOf(ru - rv);
}

dvec3 Geometry::position(const VertexRec& v) const {
  return v.def.kind == VertexKind::Point ? point(v.def.a) : snapped(v.def, rawPosition(v));
}

dvec3 Geometry::snapped(const VertexDef& d, dvec3 x) const {
  if (d.kind == VertexKind::Point) return point(d.a);
  // Only points within a hair of x can be the vertex: the exact tests run for those only.
  const auto near = [&](std::uint32_t id) {
    const dvec3& p = point(id);
    const double tolerance = 1e-9 * std::max({1.0, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return std::abs(x.x - p.x) <= tolerance && std::abs(x.y - p.y) <= tolerance && std::abs(x.z - p.z) <= tolerance;
  };
  // Coordinates in which all of `ids` agree are every point's of their line or plane.
  const auto keepShared = [&](std::span<const std::uint32_t> ids, dvec3& out) {
    for (int k = 0; k < 3; ++k) {
      const double c = point(ids[0])[k];
      bool shared = true;
      for (std::uint32_t id : ids) shared = shared && point(id)[k] == c;
      if (shared) out[k] = c;
    }
  };
  PredicateStats ignored;
  if (d.kind == VertexKind::LinePlane) {
    // The line meets q at one point; when an end of the line lies on q, that end is it.
    for (std::uint32_t id : {d.a, d.b})
      if (near(id) && side(id, d.q, ignored) == 0) return point(id);
    const std::array<std::uint32_t, 2> line{d.a, d.b};
    keepShared(line, x);
    keepShared(d.q.p, x);
    return x;
  }
  const PlaneDef* planes[3] = {&d.q, &d.r, &d.s};
  for (const PlaneDef* named : planes)
    for (std::uint32_t id : named->p)
      if (near(id) && side(id, d.q, ignored) == 0 && side(id, d.r, ignored) == 0 && side(id, d.s, ignored) == 0)
        return point(id);
  for (const PlaneDef* plane : planes) keepShared(plane->p, x);
  return x;
}

dvec3 Geometry::rawPosition(const VertexRec& v) const {
  if (v.boxed) {
    // A narrow box: its midpoint is the point to well under a float's precision.
    bool narrow = true;
    for (const Range& r : v.box)
      narrow = narrow && (r.hi - r.lo) <= 1e-12 * std::max({1.0, std::abs(r.lo), std::abs(r.hi)});
    if (narrow) return v.approx;
  }
  const VertexDef& d = v.def;
  switch (d.kind) {
    case VertexKind::Point: return point(d.a);
    case VertexKind::LinePlane: {
      const dvec3 &a = point(d.a), &b = point(d.b);
      const dvec3 &q0 = point(d.q.p[0]), &q1 = point(d.q.p[1]), &q2 = point(d.q.p[2]);
      const E qa = evalExact(q0, q1, q2, a);
      const E den = qa - evalExact(q0, q1, q2, b);
      const double dd = den.to_double();
      if (dd == 0.0) return a;
      // x = a + qa/den · (b − a): numerators exact, one rounding per division.
      const E3 ea = toE(a), eb = toE(b);
      const E3 num{ea.x * den + qa * (eb.x - ea.x), ea.y * den + qa * (eb.y - ea.y), ea.z * den + qa * (eb.z - ea.z)};
      return dvec3(num.x.to_double() / dd, num.y.to_double() / dd, num.z.to_double() / dd);
    }
    case VertexKind::ThreePlanes: {
      EPlane m[3];
      const PlaneDef* defs[3] = {&d.q, &d.r, &d.s};
      for (int i = 0; i < 3; ++i) m[i] = planeExact(point(defs[i]->p[0]), point(defs[i]->p[1]), point(defs[i]->p[2]));
      const E3 c12 = cross(m[1].n, m[2].n), c20 = cross(m[2].n, m[0].n), c01 = cross(m[0].n, m[1].n);
      const E det = dot(m[0].n, c12);
      const double dd = det.to_double();
      if (dd == 0.0) return point(d.q.p[0]);
      const E3 num{-(m[0].d * c12.x + m[1].d * c20.x + m[2].d * c01.x), -(m[0].d * c12.y + m[1].d * c20.y + m[2].d * c01.y),
                   -(m[0].d * c12.z + m[1].d * c20.z + m[2].d * c01.z)};
      return dvec3(num.x.to_double() / dd, num.y.to_double() / dd, num.z.to_double() / dd);
    }
  }
  return dvec3(0.0);
}

}  // namespace glint::cut::exact
