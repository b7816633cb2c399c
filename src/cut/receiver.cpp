#include "receiver.h"

#include "glint/core/hash.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

namespace glint::cut {

using exact::PlaneDef;
using exact::VertexDef;
using exact::VertexKind;

namespace {

/// Relaxation of the approximate (double) tests, relative to the scene radius. Their
/// rounding errors are ~1e-15 of that; 1e-9 keeps them conservative with a wide margin
/// and still far below any feature the input can represent in floats.
constexpr double kRelax = 1e-9;

/// An approximate plane o(x) = n·x + d through a, b, c, oriented so that `inside` is
/// the sign of its inner side; returned with the outer side positive and moved outwards
/// by the relaxation (a point is "outside" only when clearly so).
glm::dvec4 outward(const dvec3& a, const dvec3& b, const dvec3& c, int inside, double radius) {
  const dvec3 e1 = b - a, e2 = c - a;
  const dvec3 n = glm::cross(e1, e2);
  const double d = -glm::dot(n, a);
  const double slack = kRelax * radius * (glm::length(e1) * glm::length(e2)) + 1e-300;
  const double s = inside > 0 ? -1.0 : 1.0;
  return {s * n.x, s * n.y, s * n.z, s * d - slack};
}

double value(const glm::dvec4& p, const dvec3& x) { return p.x * x.x + p.y * x.y + p.z * x.z + p.w; }

/// Keeps the part of a convex polygon with o(x) ≤ 0.
void clipApprox(std::vector<dvec3>& poly, const glm::dvec4& o, std::vector<dvec3>& scratch) {
  scratch.clear();
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const dvec3& a = poly[i];
    const dvec3& b = poly[(i + 1) % n];
    const double va = value(o, a), vb = value(o, b);
    if (va <= 0.0) scratch.push_back(a);
    if ((va < 0.0 && vb > 0.0) || (va > 0.0 && vb < 0.0)) scratch.push_back(a + (va / (va - vb)) * (b - a));
  }
  poly.swap(scratch);
}

std::array<std::uint32_t, 2> sharedPair(const PlaneDef& x, const PlaneDef& y, bool& found) {
  std::array<std::uint32_t, 2> out{};
  int n = 0;
  for (std::uint32_t id : x.p)
    if (y.contains(id) && n < 2 && (n == 0 || out[0] != id)) out[std::size_t(n++)] = id;
  found = n == 2;
  if (out[0] > out[1]) std::swap(out[0], out[1]);
  return out;
}

VertexDef linePlane(std::uint32_t u, std::uint32_t v, const PlaneDef& q) {
  VertexDef d;
  d.kind = VertexKind::LinePlane;
  d.a = std::min(u, v);
  d.b = std::max(u, v);
  d.q.p = q.key();
  return d;
}

}  // namespace

void ReceiverPieces::clear() {
  vertices.clear();
  positions.clear();
  polygonStart.clear();
  corners.clear();
  cornerFlags.clear();
  masks.clear();
}

void ReceiverStats::add(const ReceiverStats& o) {
  candidates += o.candidates;
  occluders += o.occluders;
  clippedPairs += o.clippedPairs;
  cuts += o.cuts;
  splits += o.splits;
  facesBeforeMerge += o.facesBeforeMerge;
  grazing += o.grazing;
  selfShadowed += o.selfShadowed;
  predicates.add(o.predicates);
}


template <typename Equal>
std::uint32_t ReceiverCutter::NameIndex::find(std::uint64_t hash, Equal&& equal, std::uint32_t fresh) {
  if (2 * (m_used.size() + 1) > m_slots.size()) grow();
  const std::uint32_t h = std::uint32_t(hash ^ (hash >> 32));
  const std::size_t mask = m_slots.size() - 1;
  for (std::size_t i = h & mask;; i = (i + 1) & mask) {
    auto& slot = m_slots[i];
    if (slot.second == 0) {
      slot = {h, fresh + 1};
      m_used.push_back(std::uint32_t(i));
      return fresh;
    }
    if (slot.first == h && equal(slot.second - 1)) return slot.second - 1;
  }
}

void ReceiverCutter::NameIndex::grow() {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> old;
  old.reserve(m_used.size());
  for (std::uint32_t i : m_used) old.push_back(m_slots[i]);
  m_slots.assign(std::max<std::size_t>(64, 2 * m_slots.size()), {0, 0});
  m_used.clear();
  const std::size_t mask = m_slots.size() - 1;
  for (const auto& entry : old) {
    std::size_t i = entry.first & mask;
    while (m_slots[i].second != 0) i = (i + 1) & mask;
    m_slots[i] = entry;
    m_used.push_back(std::uint32_t(i));
  }
}

void ReceiverCutter::NameIndex::clear() {
  if (m_slots.size() > 16384) {  // released after a large receiver
    m_slots.clear();
    m_slots.shrink_to_fit();
  } else {
    for (std::uint32_t i : m_used) m_slots[i] = {0, 0};
  }
  m_used.clear();
}

ReceiverCutter::ReceiverCutter(const SceneData& scene, const std::atomic<bool>* cancel)
    : m_scene(scene), m_g(scene.geometry), m_cancel(cancel), m_triangulator(scene.geometry) {}

void ReceiverCutter::reset(std::uint32_t face) {
  m_face = face;
  m_corner = m_scene.triangles[face];
  m_plane = m_g.plane(PlaneDef{{m_corner[0], m_corner[1], m_corner[2]}});
  // Project onto the two axes other than the normal's dominant one.
  const dvec3 n(0.5 * (m_plane.coeffs[0].lo + m_plane.coeffs[0].hi), 0.5 * (m_plane.coeffs[1].lo + m_plane.coeffs[1].hi),
                0.5 * (m_plane.coeffs[2].lo + m_plane.coeffs[2].hi));
  const dvec3 an = glm::abs(n);
  const int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  m_axisU = (axis + 1) % 3;
  m_axisV = (axis + 2) % 3;
  m_planes.clear();
  m_vertices.clear();
  m_edges.clear();
  m_faces.clear();
  m_planeIndex.clear();
  m_vertexIndex.clear();

  // One face: the triangle, its edges on A's edge lines.
  Face f;
  f.edge = 0;
  f.mask = m_scene.lightCount >= 32 ? ~LightMask(0) : ((LightMask(1) << m_scene.lightCount) - 1);
  m_faces.push_back(f);
  for (int k = 0; k < 3; ++k) {
    VertexDef d;
    d.kind = VertexKind::Point;
    d.a = m_corner[std::size_t(k)];
    const std::uint32_t v = vertexIndex(d);
    HalfEdge e;
    e.origin = v;
    e.next = std::uint32_t((k + 1) % 3);
    e.prev = std::uint32_t((k + 2) % 3);
    e.face = 0;
    e.line = -1 - k;
    m_edges.push_back(e);
  }
  updateBox(0);
}

std::uint32_t ReceiverCutter::planeIndex(const PlaneDef& def, int& orientation) {
  const auto key = def.key();
  const std::uint32_t fresh = std::uint32_t(m_planes.size());
  const std::uint32_t index =
      m_planeIndex.find(hashKey(key[0], key[1], key[2]), [&](std::uint32_t i) { return m_planes[i].key == key; }, fresh);
  if (index == fresh) {
    m_planes.push_back(m_g.plane(def));
    orientation = 1;
    return index;
  }
  // Same plane, maybe the other orientation: an even permutation of the stored points
  // (a rotation) keeps it.
  const auto& s = m_planes[index].def.p;
  const auto& p = def.p;
  const bool same = (p[0] == s[0] && p[1] == s[1]) || (p[0] == s[1] && p[1] == s[2]) || (p[0] == s[2] && p[1] == s[0]);
  orientation = same ? 1 : -1;
  return index;
}

std::uint32_t ReceiverCutter::vertexIndex(const VertexDef& def) {
  const std::uint32_t fresh = std::uint32_t(m_vertices.size());
  const std::uint32_t index =
      m_vertexIndex.find(def.hash(), [&](std::uint32_t i) { return m_vertices[i].def == def; }, fresh);
  if (index == fresh) m_vertices.push_back(m_g.vertex(def));
  return index;
}

VertexDef ReceiverCutter::meet(std::int32_t line, std::uint32_t plane) const {
  const PlaneDef& q = m_planes[plane].def;
  if (line < 0) {
    const int k = -1 - line;
    return linePlane(m_corner[std::size_t(k)], m_corner[std::size_t((k + 1) % 3)], q);
  }
  const PlaneDef& p = m_plane.def;
  const PlaneDef& r = m_planes[std::size_t(line)].def;
  // Two of the three planes through two common points meet in the line through them:
  // name the vertex by that line (lower degree, and equal vertices get equal names).
  bool found = false;
  auto pair = sharedPair(r, q, found);
  if (found) return linePlane(pair[0], pair[1], p);
  pair = sharedPair(p, r, found);
  if (found) return linePlane(pair[0], pair[1], q);
  pair = sharedPair(p, q, found);
  if (found) return linePlane(pair[0], pair[1], r);
  std::array<std::array<std::uint32_t, 3>, 3> keys{p.key(), r.key(), q.key()};
  std::sort(keys.begin(), keys.end());
  VertexDef d;
  d.kind = VertexKind::ThreePlanes;
  d.q.p = keys[0];
  d.r.p = keys[1];
  d.s.p = keys[2];
  return d;
}

glm::dvec2 ReceiverCutter::project(const exact::Range* box, bool upper) const {
  return upper ? glm::dvec2(box[m_axisU].hi, box[m_axisV].hi) : glm::dvec2(box[m_axisU].lo, box[m_axisV].lo);
}

void ReceiverCutter::updateBox(std::uint32_t face) {
  Face& f = m_faces[face];
  f.lo = glm::dvec2(std::numeric_limits<double>::infinity());
  f.hi = -f.lo;
  std::uint32_t e = f.edge;
  do {
    const exact::VertexRec& v = m_vertices[m_edges[e].origin];
    f.lo = glm::min(f.lo, project(v.box.data(), false));
    f.hi = glm::max(f.hi, project(v.box.data(), true));
    e = m_edges[e].next;
  } while (e != f.edge);
}

void ReceiverCutter::classify(const std::vector<std::uint32_t>& vertices, const HalfSpace& h, std::vector<int>& out) {
  m_recs.clear();
  for (std::uint32_t v : vertices) m_recs.push_back(&m_vertices[v]);
  out.resize(vertices.size());
  m_g.sides(m_recs, m_planes[h.plane], out, *m_pstats);
  for (int& s : out) s *= h.sign;
}

bool ReceiverCutter::findOccluders(int light, std::vector<Occluder>& out, ReceiverStats& stats) {
  out.clear();
  const std::uint32_t lid = m_scene.lightBase + std::uint32_t(light);
  const int sA = m_g.side(lid, m_plane, *m_pstats);
  if (sA == 0) return false;
  const dvec3& L = m_g.point(lid);
  const dvec3 a[3] = {m_g.point(m_corner[0]), m_g.point(m_corner[1]), m_g.point(m_corner[2])};
  const double R = m_scene.radius;

  // The near beam: the tetrahedron (L, A). Its face on A's plane has L inside (sign sA);
  // a face through L and an edge of A has A's third corner inside, sign −sA (exact.h).
  std::array<glm::dvec4, 4> beam{outward(a[0], a[1], a[2], sA, R), outward(L, a[0], a[1], -sA, R),
                                 outward(L, a[1], a[2], -sA, R), outward(L, a[2], a[0], -sA, R)};
  dvec3 lo = glm::min(L, glm::min(a[0], glm::min(a[1], a[2]))) - kRelax * R;
  dvec3 hi = glm::max(L, glm::max(a[0], glm::max(a[1], a[2]))) + kRelax * R;
  m_candidates.clear();
  m_scene.bvh.query(lo, hi, beam, m_candidates);
  stats.candidates += m_candidates.size();

  std::vector<dvec3> poly, scratch;
  for (std::uint32_t t : m_candidates) {
    if (t == m_face) continue;
    const auto& bc = m_scene.triangles[t];
    const dvec3 b[3] = {m_g.point(bc[0]), m_g.point(bc[1]), m_g.point(bc[2])};
    // B wholly outside one face of the near beam cannot be in it.
    bool separated = false;
    for (const glm::dvec4& p : beam)
      if (value(p, b[0]) > 0.0 && value(p, b[1]) > 0.0 && value(p, b[2]) > 0.0) separated = true;
    if (separated) continue;
    const PlaneDef pb{{bc[0], bc[1], bc[2]}};
    const int sB = m_g.side(lid, pb, *m_pstats);
    if (sB == 0) continue;  // the light in B's plane: B casts no shadow with area
    // A convex solid's shadow is cast by its faces towards the light (receiver.h).
    if (sB < 0 && (m_scene.convexOutside[m_scene.component[t]] >> light & 1)) continue;
    // B's far beam: inside the three planes (L, b_i, b_i+1) (their inner side has sign
    // −sB) and beyond B's plane from the light (sign −sB).
    const std::array<glm::dvec4, 4> far{outward(L, b[0], b[1], -sB, R), outward(L, b[1], b[2], -sB, R),
                                        outward(L, b[2], b[0], -sB, R), outward(b[0], b[1], b[2], -sB, R)};
    for (const glm::dvec4& p : far)
      if (value(p, a[0]) > 0.0 && value(p, a[1]) > 0.0 && value(p, a[2]) > 0.0) separated = true;
    if (separated) continue;
    poly.assign(a, a + 3);
    for (const glm::dvec4& p : far) {
      clipApprox(poly, p, scratch);
      if (poly.empty()) break;
    }
    if (poly.size() < 3) continue;
    Occluder o;
    o.triangle = t;
    o.approx = far;
    o.lo = glm::dvec2(std::numeric_limits<double>::infinity());
    o.hi = -o.lo;
    dvec3 areaVector(0.0);
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const glm::dvec2 q(poly[i][m_axisU], poly[i][m_axisV]);
      o.lo = glm::min(o.lo, q);
      o.hi = glm::max(o.hi, q);
      areaVector += glm::cross(poly[i], poly[(i + 1) % poly.size()]);
    }
    o.lo -= kRelax * R;
    o.hi += kRelax * R;
    o.area = glm::length(areaVector);
    const PlaneDef defs[4] = {{{lid, bc[0], bc[1]}}, {{lid, bc[1], bc[2]}}, {{lid, bc[2], bc[0]}}, pb};
    for (int i = 0; i < 4; ++i) {
      int orientation = 1;
      o.halfSpaces[std::size_t(i)].plane = planeIndex(defs[i], orientation);
      o.halfSpaces[std::size_t(i)].sign = -sB * orientation;
    }
    out.push_back(o);
  }
  stats.occluders += out.size();
  // Big shadows first: later beams then often land on faces already shadowed and cost
  // nothing. Ties by triangle index, so the order (and the output) is deterministic.
  std::sort(out.begin(), out.end(), [](const Occluder& x, const Occluder& y) {
    return x.area > y.area || (x.area == y.area && x.triangle < y.triangle);
  });
  return true;
}

void ReceiverCutter::cut(std::uint32_t face, ReceiverPieces& out, ReceiverStats& stats) {
  m_pstats = &stats.predicates;
  reset(face);
  for (int light = 0; light < m_scene.lightCount; ++light) {
    const LightMask bit = LightMask(1) << light;
    if ((m_scene.convexOutside[m_scene.component[face]] & bit) &&
        m_g.side(m_scene.lightBase + std::uint32_t(light), m_plane, *m_pstats) < 0) {
      // A face of a convex solid turned away from the light: in the solid's own shadow.
      ++stats.selfShadowed;
      for (Face& f : m_faces) f.mask &= ~bit;
      continue;
    }
    if (!findOccluders(light, m_occluders, stats)) {
      // The light lies in A's plane: it grazes A, which receives none of it (N·L = 0).
      ++stats.grazing;
      for (Face& f : m_faces) f.mask &= ~bit;
      continue;
    }
    m_lit.clear();
    for (std::uint32_t f = 0; f < m_faces.size(); ++f)
      if (m_faces[f].alive && (m_faces[f].mask & bit)) m_lit.push_back(f);
    for (const Occluder& o : m_occluders) {
      if (m_lit.empty()) break;
      if (m_cancel && m_cancel->load(std::memory_order_relaxed)) break;
      const std::size_t before = m_faces.size();  // faces added now lie outside this beam
      bool changed = false;
      for (const std::uint32_t f : m_lit) {
        const Face& face = m_faces[f];
        if (face.lo.x > o.hi.x || face.lo.y > o.hi.y || face.hi.x < o.lo.x || face.hi.y < o.lo.y) continue;
        if (separated(f, o)) continue;
        changed |= cutFace(f, o, bit, stats);
      }
      if (!changed) continue;
      m_nextLit.clear();
      for (const std::uint32_t f : m_lit)
        if (m_faces[f].mask & bit) m_nextLit.push_back(f);
      for (std::uint32_t f = std::uint32_t(before); f < m_faces.size(); ++f)
        if (m_faces[f].mask & bit) m_nextLit.push_back(f);
      m_lit.swap(m_nextLit);
    }
  }
  std::size_t alive = 0;
  for (const Face& f : m_faces) alive += f.alive;
  stats.facesBeforeMerge += alive;
  merge();
  emit(out);
}

bool ReceiverCutter::separated(std::uint32_t f, const Occluder& o) const {
  // All corners clearly outside one of the four planes (approximate, relaxed): no overlap.
  for (const glm::dvec4& p : o.approx) {
    bool outside = true;
    std::uint32_t e = m_faces[f].edge;
    do {
      outside = value(p, m_vertices[m_edges[e].origin].approx) > 0.0;
      e = m_edges[e].next;
    } while (outside && e != m_faces[f].edge);
    if (outside) return true;
  }
  return false;
}

bool ReceiverCutter::cutFace(std::uint32_t f, const Occluder& o, LightMask bit, ReceiverStats& stats) {
  ++stats.clippedPairs;
  // Dry run on a copy of the face's outline: does it meet the far beam with area, and
  // which of the four planes cross it? Nothing in the subdivision changes unless it does.
  m_polyV.clear();
  m_polyLine.clear();
  std::uint32_t e = m_faces[f].edge;
  do {
    m_polyV.push_back(m_edges[e].origin);
    m_polyLine.push_back(m_edges[e].line);
    e = m_edges[e].next;
  } while (e != m_faces[f].edge);
  std::array<bool, 4> crosses{};
  for (std::size_t k = 0; k < 4; ++k) {
    const HalfSpace& h = o.halfSpaces[k];
    classify(m_polyV, h, m_signs);
    const auto [mn, mx] = std::minmax_element(m_signs.begin(), m_signs.end());
    if (*mx <= 0) return false;  // outside (or touching) this half-space: no shadow here
    if (*mn >= 0) continue;      // wholly inside it
    crosses[k] = true;
    m_nextV.clear();
    m_nextLine.clear();
    const std::size_t n = m_polyV.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if (m_signs[i] >= 0) {
        m_nextV.push_back(m_polyV[i]);
        // The edge leaving a kept vertex keeps its line unless it ends outside, where the
        // cut begins; a vertex on the plane followed by an outside one starts the cut edge.
        m_nextLine.push_back(m_signs[j] < 0 && m_signs[i] == 0 ? std::int32_t(h.plane) : m_polyLine[i]);
      }
      if ((m_signs[i] > 0 && m_signs[j] < 0) || (m_signs[i] < 0 && m_signs[j] > 0)) {
        m_nextV.push_back(vertexIndex(meet(m_polyLine[i], h.plane)));
        m_nextLine.push_back(m_signs[i] > 0 ? std::int32_t(h.plane) : m_polyLine[i]);
      }
    }
    m_polyV.swap(m_nextV);
    m_polyLine.swap(m_nextLine);
  }
  // Commit: split along each crossing plane, keeping the inside part.
  std::uint32_t inside = f;
  for (std::size_t k = 0; k < 4; ++k)
    if (crosses[k]) inside = splitFace(inside, o.halfSpaces[k], stats);
  m_faces[inside].mask &= ~bit;
  ++stats.cuts;
  return true;
}

std::uint32_t ReceiverCutter::splitEdge(std::uint32_t e, std::uint32_t vertex) {
  // e: a → b becomes e: a → v and n: v → b; its twin t: b → a becomes t: b → v, m: v → a.
  const std::uint32_t n = std::uint32_t(m_edges.size());
  HalfEdge ne = m_edges[e];
  ne.origin = vertex;
  ne.prev = e;
  ne.twin = kNone;
  m_edges.push_back(ne);
  m_edges[m_edges[e].next].prev = n;
  m_edges[e].next = n;
  const std::uint32_t t = m_edges[e].twin;
  if (t != kNone) {
    const std::uint32_t m = std::uint32_t(m_edges.size());
    HalfEdge me = m_edges[t];
    me.origin = vertex;
    me.prev = t;
    m_edges.push_back(me);
    m_edges[m_edges[t].next].prev = m;
    m_edges[t].next = m;
    // e (a → v) pairs with m (v → a); n (v → b) with t (b → v).
    m_edges[e].twin = m;
    m_edges[m].twin = e;
    m_edges[n].twin = t;
    m_edges[t].twin = n;
  }
  return n;
}

std::uint32_t ReceiverCutter::splitFace(std::uint32_t f, const HalfSpace& h, ReceiverStats& stats) {
  ++stats.splits;
  std::vector<std::uint32_t> edges;
  std::uint32_t e = m_faces[f].edge;
  do {
    edges.push_back(e);
    e = m_edges[e].next;
  } while (e != m_faces[f].edge);
  m_polyV.clear();
  for (std::uint32_t x : edges) m_polyV.push_back(m_edges[x].origin);
  classify(m_polyV, h, m_signs);
  const std::size_t n = edges.size();
  // The inside run starts at vertex i (s_i > 0, s_{i−1} ≤ 0) and ends at vertex j
  // (s_j > 0, s_{j+1} ≤ 0); a convex face has exactly one such run.
  std::size_t i = 0, j = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (m_signs[k] > 0 && m_signs[(k + n - 1) % n] <= 0) i = k;
    if (m_signs[k] > 0 && m_signs[(k + 1) % n] <= 0) j = k;
  }
  const std::size_t before = (i + n - 1) % n, after = (j + 1) % n;
  // Entry point: vertex `before` when on the plane, else a new vertex on edge before → i.
  std::uint32_t startIn, endOut;    // inside face: starts with startIn ... ends with endIn
  std::uint32_t startOut, endIn;    // outside face: starts with startOut ... ends with endOut
  if (m_signs[before] == 0) {
    startIn = edges[before];
    endOut = edges[(before + n - 1) % n];
  } else {
    const std::uint32_t v = vertexIndex(meet(m_edges[edges[before]].line, h.plane));
    startIn = splitEdge(edges[before], v);
    endOut = edges[before];
  }
  if (m_signs[after] == 0) {
    endIn = edges[j];
    startOut = edges[after];
  } else {
    const std::uint32_t v = vertexIndex(meet(m_edges[edges[j]].line, h.plane));
    startOut = splitEdge(edges[j], v);
    endIn = edges[j];
  }
  const std::uint32_t xa = m_edges[startIn].origin, xb = m_edges[startOut].origin;
  const std::uint32_t cin = std::uint32_t(m_edges.size()), cout = cin + 1;
  const std::uint32_t g = std::uint32_t(m_faces.size());
  HalfEdge in;
  in.origin = xb;
  in.line = std::int32_t(h.plane);
  in.inside = std::int8_t(h.sign);
  in.twin = cout;
  in.face = g;
  HalfEdge out = in;
  out.origin = xa;
  out.inside = std::int8_t(-h.sign);
  out.twin = cin;
  out.face = f;
  m_edges.push_back(in);
  m_edges.push_back(out);
  m_edges[endIn].next = cin;
  m_edges[cin].prev = endIn;
  m_edges[cin].next = startIn;
  m_edges[startIn].prev = cin;
  m_edges[endOut].next = cout;
  m_edges[cout].prev = endOut;
  m_edges[cout].next = startOut;
  m_edges[startOut].prev = cout;
  Face inside = m_faces[f];
  inside.edge = cin;
  m_faces.push_back(inside);
  m_faces[f].edge = cout;
  e = cin;
  do {
    m_edges[e].face = g;
    e = m_edges[e].next;
  } while (e != cin);
  updateBox(f);
  updateBox(g);
  return g;
}

bool ReceiverCutter::straight(std::uint32_t incoming, std::uint32_t outgoing) {
  const HalfEdge& a = m_edges[incoming];
  const HalfEdge& b = m_edges[outgoing];
  if (a.line == b.line) return true;
  if (a.line < 0 || b.line < 0) return false;  // an edge of A and a line inside A only cross
  const std::uint32_t z = m_edges[b.next].origin;
  return m_g.side(m_vertices[z], m_planes[std::size_t(a.line)], *m_pstats) == 0;
}

bool ReceiverCutter::convexAt(std::uint32_t e) {
  // Removing e (u → w) joins its face and its twin's. At u the joined outline turns from
  // a = prev(e) (x → u) into b = next(twin(e)) (u → z): convex when z is not outside a's line.
  const HalfEdge& a = m_edges[m_edges[e].prev];
  if (a.line < 0) return true;  // every vertex is inside A's edges
  const std::uint32_t b = m_edges[m_edges[e].twin].next;
  const std::uint32_t z = m_edges[m_edges[b].next].origin;
  return a.inside * m_g.side(m_vertices[z], m_planes[std::size_t(a.line)], *m_pstats) >= 0;
}

void ReceiverCutter::dropStraightVertex(std::uint32_t a) {
  // a (x → u) and b = next(a) (u → z) on one line, and u has no other edge: one edge x → z.
  const std::uint32_t b = m_edges[a].next;
  const std::uint32_t ta = m_edges[a].twin, tb = m_edges[b].twin;
  if ((ta == kNone) != (tb == kNone)) return;
  if (ta != kNone && m_edges[tb].next != ta) return;  // another edge leaves u between them
  if (!straight(a, b)) return;
  const std::uint32_t f = m_edges[a].face;
  m_edges[a].next = m_edges[b].next;
  m_edges[m_edges[b].next].prev = a;
  m_edges[b].alive = false;
  if (m_faces[f].edge == b) m_faces[f].edge = a;
  if (ta != kNone) {
    // In the other face tb (z → u) then ta (u → x) become tb: z → x.
    const std::uint32_t g = m_edges[tb].face;
    m_edges[tb].next = m_edges[ta].next;
    m_edges[m_edges[ta].next].prev = tb;
    m_edges[ta].alive = false;
    if (m_faces[g].edge == ta) m_faces[g].edge = tb;
    m_edges[a].twin = tb;
    m_edges[tb].twin = a;
  }
}

void ReceiverCutter::merge() {
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::uint32_t e = 0; e < m_edges.size(); ++e) {
      const HalfEdge& he = m_edges[e];
      if (!he.alive || he.twin == kNone || he.twin < e) continue;
      const std::uint32_t t = he.twin;
      const std::uint32_t f1 = he.face, f2 = m_edges[t].face;
      if (f1 == f2 || m_faces[f1].mask != m_faces[f2].mask) continue;
      if (!convexAt(e) || !convexAt(t)) continue;
      // Join f2 into f1: a = prev(e) → next(t) ... prev(t) → next(e).
      const std::uint32_t a = m_edges[e].prev, b = m_edges[t].next, c = m_edges[t].prev, d = m_edges[e].next;
      for (std::uint32_t x = b; x != t; x = m_edges[x].next) m_edges[x].face = f1;
      m_edges[a].next = b;
      m_edges[b].prev = a;
      m_edges[c].next = d;
      m_edges[d].prev = c;
      m_edges[e].alive = m_edges[t].alive = false;
      m_faces[f2].alive = false;
      m_faces[f1].edge = a;
      m_faces[f1].lo = glm::min(m_faces[f1].lo, m_faces[f2].lo);
      m_faces[f1].hi = glm::max(m_faces[f1].hi, m_faces[f2].hi);
      dropStraightVertex(a);
      if (m_edges[c].alive) dropStraightVertex(c);
      changed = true;
    }
  }
}

void ReceiverCutter::emitPolygon(ReceiverPieces& out, LightMask mask, std::span<const std::uint32_t> vertices,
                                 std::span<const std::uint8_t> flags) {
  out.polygonStart.push_back(std::uint32_t(out.corners.size()));
  out.masks.push_back(mask);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    std::uint32_t& l = m_local[vertices[i]];
    if (l == kNone) {
      l = std::uint32_t(out.vertices.size());
      out.vertices.push_back(m_vertices[vertices[i]].def);
      out.positions.push_back(m_g.position(m_vertices[vertices[i]]));
    }
    out.corners.push_back(l);
    out.cornerFlags.push_back(flags[i]);
  }
}

void ReceiverCutter::emitFaces(ReceiverPieces& out) {
  out.clear();
  m_local.assign(m_vertices.size(), kNone);
  for (std::uint32_t f = 0; f < m_faces.size(); ++f) {
    const Face& face = m_faces[f];
    if (!face.alive) continue;
    m_loopVertices.clear();
    m_polygonFlags.clear();
    std::uint32_t e = face.edge;
    do {
      const HalfEdge& he = m_edges[e];
      m_loopVertices.push_back(he.origin);
      std::uint8_t flags = he.line < 0 ? std::uint8_t(-1 - he.line) : std::uint8_t(kInterior);
      if (straight(he.prev, e)) flags |= kStraight;
      m_polygonFlags.push_back(flags);
      e = he.next;
    } while (e != face.edge);
    emitPolygon(out, face.mask, m_loopVertices, m_polygonFlags);
  }
  out.polygonStart.push_back(std::uint32_t(out.corners.size()));
}

bool ReceiverCutter::boundary(std::uint32_t e) const {
  const HalfEdge& he = m_edges[e];
  return he.twin == kNone || m_faces[m_edges[he.twin].face].mask != m_faces[he.face].mask;
}

namespace {

/// Groups the live faces into regions: faces joined across edges whose faces have the same
/// mask, numbered in order of their first face. Region r is faces
/// regionFaces[regionStart[r] .. regionStart[r + 1]); region[f] is face f's region.
template <typename Edges, typename Faces, typename Boundary>
void groupRegions(const Edges& edges, const Faces& faces, const Boundary& boundary, std::uint32_t none,
                  std::vector<std::uint32_t>& region, std::vector<std::uint32_t>& regionFaces,
                  std::vector<std::uint32_t>& regionStart, std::vector<std::uint32_t>& stack) {
  const std::uint32_t faceCount = std::uint32_t(faces.size());
  region.assign(faceCount, none);
  regionFaces.clear();
  regionStart.clear();
  for (std::uint32_t f = 0; f < faceCount; ++f) {
    if (!faces[f].alive || region[f] != none) continue;
    const std::uint32_t r = std::uint32_t(regionStart.size());
    regionStart.push_back(std::uint32_t(regionFaces.size()));
    region[f] = r;
    stack.assign(1, f);
    while (!stack.empty()) {
      const std::uint32_t g = stack.back();
      stack.pop_back();
      regionFaces.push_back(g);
      std::uint32_t e = faces[g].edge;
      do {
        const auto& he = edges[e];
        if (he.twin != none && !boundary(e)) {
          const std::uint32_t h = edges[he.twin].face;
          if (region[h] == none) {
            region[h] = r;
            stack.push_back(h);
          }
        }
        e = he.next;
      } while (e != faces[g].edge);
    }
  }
  regionStart.push_back(std::uint32_t(regionFaces.size()));
}

/// Counts the outline edges meeting at each vertex (A's edges count) into `degree`, and
/// marks in `onEdge` which of A's edges each vertex lies on (bit k: edge k).
template <typename Edges, typename Faces, typename Boundary>
void countOutlineEdges(const Edges& edges, const Faces& faces, const Boundary& boundary, std::uint32_t none,
                       std::size_t vertexCount, std::vector<std::uint8_t>& degree, std::vector<std::uint8_t>& onEdge) {
  degree.assign(vertexCount, 0);
  onEdge.assign(vertexCount, 0);
  for (std::uint32_t e = 0; e < edges.size(); ++e) {
    const auto& he = edges[e];
    if (!he.alive || !faces[he.face].alive) continue;
    const std::uint32_t to = edges[he.next].origin;
    if (he.line < 0) {
      onEdge[he.origin] |= std::uint8_t(1u << (-1 - he.line));
      onEdge[to] |= std::uint8_t(1u << (-1 - he.line));
    }
    if (!boundary(e) || (he.twin != none && he.twin < e)) continue;
    degree[he.origin] = std::uint8_t(std::min(degree[he.origin] + 1, 255));
    degree[to] = std::uint8_t(std::min(degree[to] + 1, 255));
  }
}

/// Traces the outlines of the region of faces `regionFaces`: from each unvisited outline
/// edge, around the region. Loop l is loopEdges[loopStart[l] .. loopStart[l + 1]).
template <typename Edges, typename Faces, typename Boundary>
void traceOutlines(const Edges& edges, const Faces& faces, const Boundary& boundary,
                   std::span<const std::uint32_t> regionFaces, std::vector<std::uint8_t>& visited,
                   std::vector<std::uint32_t>& loopEdges, std::vector<std::uint32_t>& loopStart) {
  loopEdges.clear();
  loopStart.clear();
  for (const std::uint32_t g : regionFaces) {
    std::uint32_t e0 = faces[g].edge;
    do {
      if (boundary(e0) && !visited[e0]) {
        loopStart.push_back(std::uint32_t(loopEdges.size()));
        std::uint32_t e = e0;
        do {
          visited[e] = 1;
          loopEdges.push_back(e);
          std::uint32_t x = edges[e].next;  // around the end vertex, through the region, to the next outline edge
          while (!boundary(x)) x = edges[edges[x].twin].next;
          e = x;
        } while (e != e0);
      }
      e0 = edges[e0].next;
    } while (e0 != faces[g].edge);
  }
  loopStart.push_back(std::uint32_t(loopEdges.size()));
}

}  // namespace

void ReceiverCutter::emit(ReceiverPieces& out) {
  const auto outline = [this](std::uint32_t e) { return boundary(e); };
  // Regions: faces joined across edges whose faces have the same mask, in order of their
  // first face (so the output does not depend on anything but the subdivision).
  groupRegions(m_edges, m_faces, outline, kNone, m_region, m_regionFaces, m_regionStart, m_stack);
  // How many outline edges meet at each vertex (A's edges count), and which of A's edges
  // each vertex lies on.
  countOutlineEdges(m_edges, m_faces, outline, kNone, m_vertices.size(), m_degree, m_onEdge);
  // A vertex stays where two outline edges turn or more than two meet; elsewhere it lies
  // on a straight outline between two regions (or inside one) and every face around it
  // agrees to drop it. On A's edges, a neighbouring receiver that keeps one puts it back
  // (merge.cpp, shared edges).
  const auto keep = [&](std::uint32_t incoming, std::uint32_t outgoing) {
    return m_degree[m_edges[outgoing].origin] != 2 || !straight(incoming, outgoing);
  };
  out.clear();
  m_local.assign(m_vertices.size(), kNone);
  m_visited.assign(m_edges.size(), 0);
  bool corners = false;
  for (std::uint32_t r = 0; r + 1 < m_regionStart.size(); ++r) {
    const std::uint32_t first = m_regionFaces[m_regionStart[r]];
    const LightMask mask = m_faces[first].mask;
    // The region's outlines: from each unvisited outline edge, around the region.
    traceOutlines(m_edges, m_faces, outline,
                  std::span(m_regionFaces).subspan(m_regionStart[r], m_regionStart[r + 1] - m_regionStart[r]),
                  m_visited, m_loopEdges, m_loopStart);
    // The corners kept, loop by loop.
    m_loopVertices.clear();
    m_polygonFlags.clear();
    std::vector<std::uint32_t> keptStart;
    for (std::size_t l = 0; l + 1 < m_loopStart.size(); ++l) {
      keptStart.push_back(std::uint32_t(m_loopVertices.size()));
      const std::uint32_t a = m_loopStart[l], z = m_loopStart[l + 1];
      for (std::uint32_t i = a; i < z; ++i) {
        const std::uint32_t in = m_loopEdges[i == a ? z - 1 : i - 1], e = m_loopEdges[i];
        if (!keep(in, e)) continue;
        m_loopVertices.push_back(m_edges[e].origin);
        std::uint8_t flags = m_edges[e].line < 0 ? std::uint8_t(-1 - m_edges[e].line) : std::uint8_t(kInterior);
        if (straight(in, e)) flags |= kStraight;
        m_polygonFlags.push_back(flags);
      }
    }
    keptStart.push_back(std::uint32_t(m_loopVertices.size()));
    if (m_regionStart[r + 1] - m_regionStart[r] == 1) {  // one convex face: its kept corners
      emitPolygon(out, mask, m_loopVertices, m_polygonFlags);
      continue;
    }
    if (!corners) {
      std::array<VertexDef, 3> defs;
      for (std::size_t k = 0; k < 3; ++k) defs[k] = VertexDef{.kind = VertexKind::Point, .a = m_corner[k]};
      m_triangulator.reset(m_axisU, m_axisV, defs, [this](std::uint32_t id) -> const VertexDef& { return m_vertices[id].def; });
      corners = true;
    }
    m_pieces.clear();
    if (!m_triangulator.triangulate(m_loopVertices, keptStart, m_pieces)) {
      emitFaces(out);  // keep every vertex everywhere, so that the regions still meet without T-junctions
      return;
    }
    for (std::size_t q = 0, s = 0; q < m_pieces.end.size(); s = m_pieces.end[q++]) {
      const std::size_t k = m_pieces.end[q] - s;
      m_polygonFlags.clear();
      for (std::size_t i = 0; i < k; ++i) {
        const std::uint8_t both = m_onEdge[m_pieces.corners[s + i]] & m_onEdge[m_pieces.corners[s + (i + 1) % k]];
        std::uint8_t flags = both == 0 ? std::uint8_t(kInterior) : std::uint8_t(std::countr_zero(both));
        if (m_pieces.straight[s + i]) flags |= kStraight;
        m_polygonFlags.push_back(flags);
      }
      emitPolygon(out, mask, std::span(m_pieces.corners).subspan(s, k), m_polygonFlags);
    }
  }
  out.polygonStart.push_back(std::uint32_t(out.corners.size()));
}

}  // namespace glint::cut
