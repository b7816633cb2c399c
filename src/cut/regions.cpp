// A receiver's light-mask regions triangulated with their turning vertices only (regions.h).
#include "regions.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <deque>
#include <unordered_map>

namespace glint::cut {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = K::Point_2;
constexpr std::uint32_t kNoId = 0xFFFFFFFFu;
/// Faces carry their nesting level: −1 unknown, 0 outside, 1 inside the outline, 2 in a
/// hole, ... (odd: inside the region).
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Constraints only ever meet at their end points (the loops are outlines of one region of
// a planar subdivision); anything else throws, and the caller keeps the convex faces.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

}  // namespace

struct RegionTriangulator::Impl {
  const exact::Geometry& g;
  int u = 0, v = 1;
  bool flipped = false;  ///< the projection turns A's counter-clockwise into clockwise
  std::unordered_map<std::uint32_t, Point> points;  ///< by vertex id, this receiver

  const Point& point(std::span<const exact::VertexRec> vertices, std::uint32_t id) {
    auto it = points.find(id);
    if (it == points.end()) {
      const auto x = g.exactPosition(vertices[id].def);
      it = points.emplace(id, Point(K::FT(x[std::size_t(u)]), K::FT(x[std::size_t(v)]))).first;
    }
    return it->second;
  }
};

RegionTriangulator::RegionTriangulator(const exact::Geometry& geometry) : m(std::make_unique<Impl>(Impl{geometry})) {}
RegionTriangulator::~RegionTriangulator() = default;

void RegionTriangulator::reset(int axisU, int axisV, const std::array<exact::VertexDef, 3>& corners) {
  m->u = axisU;
  m->v = axisV;
  m->points.clear();
  std::array<Point, 3> p;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto x = m->g.exactPosition(corners[k]);
    p[k] = Point(K::FT(x[std::size_t(axisU)]), K::FT(x[std::size_t(axisV)]));
  }
  m->flipped = CGAL::orientation(p[0], p[1], p[2]) == CGAL::CLOCKWISE;
}

bool RegionTriangulator::triangulate(std::span<const exact::VertexRec> vertices, std::span<const std::uint32_t> loopVertices,
                                     std::span<const std::uint32_t> loopStart, std::vector<std::uint32_t>& triangles) {
  Cdt cdt;
  try {
    for (std::size_t l = 0; l + 1 < loopStart.size(); ++l) {
      const std::uint32_t a = loopStart[l], z = loopStart[l + 1];
      if (z - a < 3) return false;
      Cdt::Vertex_handle first, previous;
      for (std::uint32_t i = a; i < z; ++i) {
        const std::uint32_t id = loopVertices[i];
        const std::size_t count = cdt.number_of_vertices();
        const Cdt::Vertex_handle h = cdt.insert(m->point(vertices, id));
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
  // Nesting levels from the infinite face inwards: crossing a constraint goes one deeper.
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
  const std::size_t before = triangles.size();
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info() % 2 == 0) continue;
    const std::uint32_t a = f->vertex(0)->info(), b = f->vertex(1)->info(), c = f->vertex(2)->info();
    if (m->flipped) triangles.insert(triangles.end(), {a, c, b});
    else triangles.insert(triangles.end(), {a, b, c});
  }
  // Every outline edge has the region on exactly one side; otherwise the loops were not
  // the outline of one region.
  for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e) {
    if (!cdt.is_constrained(*e)) continue;
    const bool in = e->first->info() % 2 == 1, out = e->first->neighbor(e->second)->info() % 2 == 1;
    if (in == out) {
      triangles.resize(before);
      return false;
    }
  }
  return true;
}

}  // namespace glint::cut
