// Preparing a scene for cutting, in four steps: the triangles (which can be cut), the
// connected surfaces, the closed convex solids among them, and warnings about lights in
// odd places. cutShard runs all four; mergeShards needs only the first two.
#include "glint/core/union_find.h"
#include "glint/core/error.h"
#include "glint/core/hash.h"

#include "lights.h"
#include "pieces.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

namespace glint::cut {

namespace {

/// Solid angle of triangle (a, b, c) seen from the origin (van Oosterom–Strackee).
double solidAngle(const dvec3& a, const dvec3& b, const dvec3& c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double det = glm::dot(a, glm::cross(b, c));
  const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(det, den);
}

/// The points exact::Geometry names vertices by: the welded input points, then the lights.
std::unique_ptr<SceneData> makeSceneData(const EdgeMap& edges, const std::vector<Light>& lights) {
  std::vector<dvec3> points;
  points.reserve(edges.positions().size() + lights.size());
  for (const vec3& p : edges.positions()) points.emplace_back(p);
  const std::uint32_t lightBase = std::uint32_t(points.size());
  for (const Light& l : lights) points.emplace_back(l.position);
  double radius = 1.0;
  for (const dvec3& p : points) radius = std::max(radius, glm::length(p));
  auto scene = std::make_unique<SceneData>(std::move(points));
  scene->lightBase = lightBase;
  scene->lightCount = int(lights.size());
  scene->radius = radius;
  return scene;
}

/// 1. Triangles: collapsed (two corners weld to one point), degenerate (no area) or
///    usable; the usable ones' bounding boxes in `lo` and `hi`, for the BVH.
void classifyTriangles(Prepared& out, std::vector<dvec3>& lo, std::vector<dvec3>& hi) {
  SceneData& s = *out.scene;
  const std::size_t n = out.edges.faceCount();
  s.triangles.resize(n);
  s.usable.assign(n, 0);
  out.state.assign(n, Prepared::kUsable);
  lo.assign(n, dvec3(0.0));
  hi.assign(n, dvec3(0.0));
  std::uint64_t degenerate = 0, collapsed = 0;
  for (std::uint32_t f = 0; f < n; ++f) {
    const auto c = out.edges.corners(f);
    s.triangles[f] = c;
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      out.state[f] = Prepared::kCollapsed;
      ++collapsed;
      continue;
    }
    if (s.geometry.degenerate(exact::PlaneDef{{c[0], c[1], c[2]}})) {
      out.state[f] = Prepared::kDegenerate;
      ++degenerate;
      continue;
    }
    s.usable[f] = 1;
    const dvec3 &a = s.geometry.point(c[0]), &b = s.geometry.point(c[1]), &d = s.geometry.point(c[2]);
    lo[f] = glm::min(a, glm::min(b, d));
    hi[f] = glm::max(a, glm::max(b, d));
  }
  if (degenerate > 0)
    out.warnings.push_back(fmt::format("{} degenerate (zero-area) triangle(s): kept unlit, they cast no shadow", degenerate));
  if (collapsed > 0)
    out.warnings.push_back(fmt::format("{} triangle(s) with two corners at one position dropped", collapsed));
}

/// 2. Connected surfaces (triangles joined by edges), numbered in triangle order.
void numberSurfaces(const EdgeMap& edges, SceneData& s) {
  const std::size_t n = s.triangles.size();
  UnionFind sets(n);
  const auto root = [&](std::uint32_t x) { return sets.find(x); };
  for (const Edge& edge : edges.edges()) {
    const auto faces = edges.faces(edge);
    for (std::size_t i = 1; i < faces.size(); ++i) sets.unite(faces[0].face, faces[i].face);
  }
  std::vector<std::uint32_t> number(n, 0xFFFFFFFFu);
  s.component.resize(n);
  std::uint32_t count = 0;
  for (std::uint32_t f = 0; f < n; ++f) {
    const std::uint32_t r = root(f);
    if (number[r] == 0xFFFFFFFFu) number[r] = count++;
    s.component[f] = number[r];
  }
  s.convexOutside.assign(count, 0);
}

/// 3. Closed convex surfaces: every face with area, every edge shared by two faces running
///    it in opposite directions and bending outwards (or flat), and the topology of a sphere
///    (V − E + F = 2), which with local convexity makes the surface the boundary of a convex
///    solid. Decided exactly, like everything the cut depends on. Then, per convex surface,
///    the lights outside it (SceneData::convexOutside).
void findConvexSolids(const EdgeMap& edges, SceneData& s) {
  const std::size_t n = s.triangles.size();
  const std::size_t count = s.convexOutside.size();
  std::vector<std::uint8_t> convex(count, 1);
  std::vector<std::int64_t> euler(count, 0);
  exact::PredicateStats ignored;
  for (std::uint32_t f = 0; f < n; ++f) {
    if (!s.usable[f]) convex[s.component[f]] = 0;
    euler[s.component[f]] += 1;
  }
  std::vector<std::uint32_t> pointComponent(edges.positions().size(), 0xFFFFFFFFu);
  for (std::uint32_t f = 0; f < n; ++f)
    for (std::uint32_t c : s.triangles[f])
      if (pointComponent[c] == 0xFFFFFFFFu) {
        pointComponent[c] = s.component[f];
        euler[s.component[f]] += 1;
      } else if (pointComponent[c] != s.component[f]) {
        convex[s.component[f]] = convex[pointComponent[c]] = 0;  // surfaces meeting at a point
      }
  for (const Edge& edge : edges.edges()) {
    const auto faces = edges.faces(edge);
    const std::uint32_t c = s.component[faces[0].face];
    euler[c] -= 1;
    if (!convex[c]) continue;
    if (edges.kind(edge) != EdgeKind::Manifold) {
      convex[c] = 0;
      continue;
    }
    // The corner of the second face off the edge, against the first face's plane.
    const auto& t1 = s.triangles[faces[0].face];
    const auto& t2 = s.triangles[faces[1].face];
    std::uint32_t apex = t2[0];
    for (std::uint32_t v : t2)
      if (v != edge.a && v != edge.b) apex = v;
    if (s.geometry.side(apex, exact::PlaneDef{{t1[0], t1[1], t1[2]}}, ignored) > 0) convex[c] = 0;
  }
  for (std::size_t c = 0; c < count; ++c)
    if (euler[c] != 2) convex[c] = 0;
  // A light is outside a convex solid when some face of it faces the light.
  for (std::uint32_t f = 0; f < n; ++f) {
    const std::uint32_t c = s.component[f];
    if (!convex[c]) continue;
    const auto& t = s.triangles[f];
    const exact::PlaneDef plane{{t[0], t[1], t[2]}};
    for (int l = 0; l < s.lightCount; ++l)
      if (!(s.convexOutside[c] & (LightMask(1) << l)) && s.geometry.side(s.lightBase + std::uint32_t(l), plane, ignored) > 0)
        s.convexOutside[c] |= LightMask(1) << l;
  }
}

/// 4. Lights in odd places: on a surface, or inside a closed mesh. Both still give a
///    well-defined result, so they are warnings. Needs the BVH.
void warnAboutLights(const std::vector<Light>& lights, const SceneData& s, std::vector<std::string>& warnings) {
  std::vector<std::uint32_t> near;
  for (std::size_t l = 0; l < lights.size(); ++l) {
    const dvec3 L = s.geometry.point(s.lightBase + std::uint32_t(l));
    const std::string name = lightName(lights[l], l);
    // On (or within a hair of) a surface: that surface grazes the light and stays dark.
    const double eps = 1e-6 * s.radius;
    bool onSurface = false;
    near.clear();
    s.bvh.query(L - eps, L + eps, {}, near);
    for (std::uint32_t f : near) {
      const auto& c = s.triangles[f];
      const dvec3 a = s.geometry.point(c[0]), b = s.geometry.point(c[1]), d = s.geometry.point(c[2]);
      const dvec3 nrm = glm::normalize(glm::cross(b - a, d - a));
      const double dist = glm::dot(L - a, nrm);
      const dvec3 q = L - dist * nrm;
      const bool inside = glm::dot(glm::cross(b - a, q - a), nrm) >= -eps && glm::dot(glm::cross(d - b, q - b), nrm) >= -eps &&
                          glm::dot(glm::cross(a - d, q - d), nrm) >= -eps;
      if (std::abs(dist) <= eps && inside) {
        warnings.push_back(fmt::format("light '{}' lies on a surface (triangle {}): it lights nothing there", name, f));
        onSurface = true;
        break;
      }
    }
    // Inside a closed mesh whose normals point out: the generalized winding number is 1.
    // (Not decided for a light on a surface, where it is half-way by definition.)
    if (onSurface) continue;
    double winding = 0.0;
    for (std::uint32_t f = 0; f < s.triangles.size(); ++f) {
      if (!s.usable[f]) continue;
      const auto& c = s.triangles[f];
      winding += solidAngle(s.geometry.point(c[0]) - L, s.geometry.point(c[1]) - L, s.geometry.point(c[2]) - L);
    }
    winding /= 4.0 * 3.14159265358979323846;
    if (winding > 0.5)
      warnings.push_back(fmt::format("light '{}' is inside a closed mesh (winding number {:.2f}): only the inside "
                                     "of it can be lit", name, winding));
  }
}

}  // namespace

std::uint64_t inputHash(const Mesh& mesh, const std::vector<Light>& lights) {
  Fnv1a h;
  h.add(mesh.positions).add(mesh.indices);
  for (const Light& l : lights) h.add(l.position);
  return h.value();
}

Prepared prepare(const Mesh& mesh, const std::vector<Light>& lights, bool bvh) {
  checkLights(lights);
  Prepared out;
  out.edges = EdgeMap::build(mesh);  // validates: Error(Input) for empty, NaN, bad indices
  out.hash = inputHash(mesh, lights);
  out.scene = makeSceneData(out.edges, lights);
  std::vector<dvec3> lo, hi;
  classifyTriangles(out, lo, hi);
  numberSurfaces(out.edges, *out.scene);
  if (!bvh) return out;
  SceneData& s = *out.scene;
  s.bvh = TriangleBvh(lo, hi, s.usable);
  findConvexSolids(out.edges, s);
  warnAboutLights(lights, s, out.warnings);
  return out;
}

}  // namespace glint::cut
