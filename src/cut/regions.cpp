// A receiver's light-mask regions triangulated with their turning vertices only (regions.h).
#include "regions.h"
#include "glint/core/union_find.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <deque>
#include <unordered_map>

namespace glint::cut {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = K::Point_2;
/// Faces carry their nesting level: −1 unknown, 0 outside, 1 inside the outline, 2 in a
/// hole, ... (odd: inside the region).
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Constraints only ever meet at their end points (the loops are outlines of one region of
// a planar subdivision); anything else throws, and the caller keeps the convex faces.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

/// A rational as the kernel's number: its exact type is GMP's mpq_class or Boost's
/// gmp_rational, as CGAL was configured; both take an mpq_t.
K::FT kernelNumber(const mpq_class& q) { return K::FT(K::FT::ET(q.get_mpq_t())); }

/// Sets every face's nesting level, from the infinite face inwards: crossing a constraint
/// goes one deeper.
void markNesting(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::deque<Cdt::Face_handle> border{cdt.infinite_face()};
  cdt.infinite_face()->info() = 0;
  std::deque<Cdt::Face_handle> queue;
  while (!border.empty()) {
    const Cdt::Face_handle start = border.front();
    border.pop_front();
    const int level = start->info();
    queue.assign(1, start);
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          n->info() = level + 1;
          border.push_back(n);
        } else {
          n->info() = level;
          queue.push_back(n);
        }
      }
    }
  }
}

/// Whether every outline edge has the region (an odd nesting level) on exactly one side.
bool regionOnOneSide(Cdt& cdt) {
  for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e) {
    if (!cdt.is_constrained(*e)) continue;
    const bool in = e->first->info() % 2 == 1, out = e->first->neighbor(e->second)->info() % 2 == 1;
    if (in == out) return false;
  }
  return true;
}

}  // namespace

struct RegionTriangulator::Impl {
  const exact::Geometry& g;
  int u = 0, v = 1;
  bool flipped = false;  ///< the projection turns A's counter-clockwise into clockwise
  Defs defs;
  std::unordered_map<std::uint32_t, Point> points;  ///< by vertex id, this plane

  const Point& point(std::uint32_t id) {
    auto it = points.find(id);
    if (it == points.end()) {
      const auto x = g.exactPosition(defs(id));
      it = points.emplace(id, Point(kernelNumber(x[std::size_t(u)]), kernelNumber(x[std::size_t(v)]))).first;
    }
    return it->second;
  }

  /// Inserts the loops' vertices and their edges as constraints; false when a loop has
  /// fewer than three vertices, two vertices lie at one point, or CGAL throws.
  bool insertLoops(Cdt& cdt, std::span<const std::uint32_t> loopVertices, std::span<const std::uint32_t> loopStart) {
    try {
      for (std::size_t l = 0; l + 1 < loopStart.size(); ++l) {
        const std::uint32_t a = loopStart[l], z = loopStart[l + 1];
        if (z - a < 3) return false;
        Cdt::Vertex_handle first, previous;
        for (std::uint32_t i = a; i < z; ++i) {
          const std::uint32_t id = loopVertices[i];
          const std::size_t count = cdt.number_of_vertices();
          const Cdt::Vertex_handle h = cdt.insert(point(id));
          if (cdt.number_of_vertices() > count) h->info() = id;
          else if (h->info() != id) return false;  // two vertices at one point: a zero-length edge
          if (i == a) first = h;
          else cdt.insert_constraint(previous, h);
          previous = h;
        }
        cdt.insert_constraint(previous, first);
      }
    } catch (const CGAL::Failure_exception&) {
      return false;
    } catch (const std::exception&) {
      return false;
    }
    return true;
  }
};

RegionTriangulator::RegionTriangulator(const exact::Geometry& geometry) : m(std::make_unique<Impl>(Impl{geometry})) {}
RegionTriangulator::~RegionTriangulator() = default;

void RegionTriangulator::reset(int axisU, int axisV, const std::array<exact::VertexDef, 3>& corners, Defs defs) {
  m->u = axisU;
  m->v = axisV;
  m->defs = std::move(defs);
  m->points.clear();
  std::array<Point, 3> p;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto x = m->g.exactPosition(corners[k]);
    p[k] = Point(kernelNumber(x[std::size_t(axisU)]), kernelNumber(x[std::size_t(axisV)]));
  }
  m->flipped = CGAL::orientation(p[0], p[1], p[2]) == CGAL::CLOCKWISE;
}

bool RegionTriangulator::collinear(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  return CGAL::orientation(m->point(a), m->point(b), m->point(c)) == CGAL::COLLINEAR;
}

bool RegionTriangulator::triangulate(std::span<const std::uint32_t> loopVertices,
                                     std::span<const std::uint32_t> loopStart, ConvexPieces& out) {
  Cdt cdt;
  if (!m->insertLoops(cdt, loopVertices, loopStart)) return false;
  // Nesting levels from the infinite face inwards: crossing a constraint goes one deeper.
  markNesting(cdt);
  // Every outline edge has the region on exactly one side; otherwise the loops were not
  // the outline of one region.
  if (!regionOnOneSide(cdt)) return false;
  // The region's triangles, each a polygon (counter-clockwise in the projection), then
  // joined greedily across diagonals where both ends stay convex.
  std::vector<Cdt::Face_handle> faces;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info() % 2 == 1) {
      f->info() = 2 * int(faces.size()) + 1;  // odd still: inside, and its index
      faces.push_back(f);
    }
  const auto index = [](Cdt::Face_handle f) { return std::uint32_t((f->info() - 1) / 2); };
  UnionFind sets(faces.size());
  std::vector<std::vector<Cdt::Vertex_handle>> cycle(faces.size());
  for (std::uint32_t i = 0; i < faces.size(); ++i) cycle[i] = {faces[i]->vertex(0), faces[i]->vertex(1), faces[i]->vertex(2)};
  const auto find = [&](std::uint32_t x) { return sets.find(x); };
  // Rotates c so that it starts at v.
  const auto startAt = [](std::vector<Cdt::Vertex_handle>& c, Cdt::Vertex_handle v) {
    std::rotate(c.begin(), std::find(c.begin(), c.end(), v), c.end());
  };
  for (std::uint32_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const Cdt::Face_handle n = faces[i]->neighbor(k);
      if (cdt.is_infinite(n) || n->info() % 2 == 0 || index(n) < i) continue;
      const std::uint32_t p = find(i), q = find(index(n));
      if (p == q) continue;
      // In f the diagonal runs a → b; in its neighbour b → a.
      const Cdt::Vertex_handle a = faces[i]->vertex(Cdt::ccw(k)), b = faces[i]->vertex(Cdt::cw(k));
      std::vector<Cdt::Vertex_handle>& P = cycle[p];
      std::vector<Cdt::Vertex_handle>& Q = cycle[q];
      startAt(P, b);  // b ... a
      startAt(Q, a);  // a ... b
      if (P.back() != a || Q.back() != b) continue;  // not a side of both (cannot happen)
      const auto convex = [](Cdt::Vertex_handle x, Cdt::Vertex_handle y, Cdt::Vertex_handle z) {
        return CGAL::orientation(x->point(), y->point(), z->point()) != CGAL::RIGHT_TURN;
      };
      if (!convex(P[P.size() - 2], a, Q[1]) || !convex(Q[Q.size() - 2], b, P[1])) continue;
      P.insert(P.end(), Q.begin() + 1, Q.end() - 1);
      Q.clear();
      sets.attach(q, p);  // p keeps the merged cycle
    }
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (find(i) != i) continue;
    std::vector<Cdt::Vertex_handle>& c = cycle[i];
    if (m->flipped) std::reverse(c.begin(), c.end());
    const std::size_t k = c.size();
    for (std::size_t j = 0; j < k; ++j) {
      out.corners.push_back(c[j]->info());
      out.straight.push_back(CGAL::orientation(c[(j + k - 1) % k]->point(), c[j]->point(), c[(j + 1) % k]->point()) ==
                             CGAL::COLLINEAR);
    }
    out.end.push_back(std::uint32_t(out.corners.size()));
  }
  return true;
}

}  // namespace glint::cut
