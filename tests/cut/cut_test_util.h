#pragma once
// What the cutter's tests share: small scenes and the independent checks (Embree shadow
// rays, areas per input triangle, edge topology).
#include "glint/cut/cutter.h"
#include "glint/mesh/adjacency.h"
#include "glint/mesh/mesh.h"
#include "glint/raytrace/raytracer.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace glint::cut::testing {

/// A closed box between lo and hi (12 triangles, outward, corners shared).
inline Mesh makeBox(vec3 lo, vec3 hi) {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return m;
}

/// One triangle.
inline Mesh makeTriangle(vec3 a, vec3 b, vec3 c) {
  Mesh m;
  m.positions = {a, b, c};
  m.indices = {0, 1, 2};
  return m;
}

struct OracleResult {
  std::size_t samples = 0, agree = 0;
  std::size_t skipped = 0;  ///< pieces too thin for float rays (mean width < 1e-5 of the scene)
  double agreement() const { return samples ? double(agree) / double(samples) : 1.0; }
};

/// Shadow rays (Embree, against the input scene) from random points inside every piece,
/// pulled towards the piece's centre by `inset` of the way, to every light; compared
/// with the piece's mask. Grazing pieces (the light in their plane) are skipped.
inline OracleResult shadowOracle(const Mesh& scene, const CutMesh& mesh, const std::vector<Light>& lights,
                                 int samplesPerPiece, std::uint32_t seed = 1, double inset = 1e-3) {
  raytrace::Scene rt(scene);
  const float sceneSize = scene.bounds().diagonal();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<raytrace::Ray> rays;
  std::vector<std::uint8_t> expected;
  std::vector<std::uint32_t> source;
  OracleResult r;
  for (std::size_t p = 0; p < mesh.polygonCount(); ++p) {
    const std::uint32_t s = mesh.polygonStart[p];
    const std::size_t n = mesh.cornerCount(p);
    dvec3 centre(0.0);
    for (std::size_t i = 0; i < n; ++i) centre += mesh.precisePositions[mesh.corners[s + i]];
    centre /= double(n);
    const double area = polygonArea(mesh, p);
    const dvec3 a = mesh.precisePositions[mesh.corners[s]];
    dvec3 normal(0.0);
    for (std::size_t i = 1; i + 1 < n; ++i)
      normal += glm::cross(mesh.precisePositions[mesh.corners[s + i]] - a, mesh.precisePositions[mesh.corners[s + i + 1]] - a);
    // Pieces thinner than the float rays can resolve (2·area / perimeter, their mean
    // width, under 1e-5 of the scene) are counted, not sampled.
    double perimeter = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      perimeter += glm::length(mesh.precisePositions[mesh.corners[s + (i + 1) % n]] - mesh.precisePositions[mesh.corners[s + i]]);
    if (2.0 * area <= 1e-5 * double(sceneSize) * perimeter || glm::length(normal) == 0.0) {
      ++r.skipped;
      continue;
    }
    normal = glm::normalize(normal);
    for (int k = 0; k < samplesPerPiece; ++k) {
      // A random point of a random fan triangle (area-weighted), pulled inwards.
      double pick = u01(rng) * area * 2.0;
      std::size_t t = 1;
      for (; t + 2 < n; ++t) {
        const double at = glm::length(glm::cross(mesh.precisePositions[mesh.corners[s + t]] - a,
                                                 mesh.precisePositions[mesh.corners[s + t + 1]] - a));
        if (pick < at) break;
        pick -= at;
      }
      double x = u01(rng), y = u01(rng);
      if (x + y > 1.0) {
        x = 1.0 - x;
        y = 1.0 - y;
      }
      const dvec3 b = mesh.precisePositions[mesh.corners[s + t]], c = mesh.precisePositions[mesh.corners[s + t + 1]];
      dvec3 q = a + x * (b - a) + y * (c - a);
      q = centre + (1.0 - inset) * (q - centre);
      for (std::size_t l = 0; l < lights.size(); ++l) {
        const dvec3 L(lights[l].position);
        if (std::abs(glm::dot(L - q, normal)) < 1e-9 * glm::length(L - q)) continue;  // grazing
        const dvec3 d = L - q;
        rays.push_back({.origin = vec3(q), .direction = vec3(d), .tnear = 1e-7f, .tfar = 1.0f - 1e-6f});
        expected.push_back((mesh.polygonMask[p] >> l) & 1);
        source.push_back(mesh.polygonSource[p]);
      }
    }
  }
  // Closest hits, not any hit: a hit on the piece's own input triangle (the origin is
  // rounded to float, so it may lie a hair behind its surface) is stepped over and the
  // ray cast again from there. Tiny tnear then, and nothing near the piece is missed.
  std::vector<std::uint8_t> blocked(rays.size(), 0);
  std::vector<std::size_t> pending(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) pending[i] = i;
  for (int round = 0; round < 4 && !pending.empty(); ++round) {
    std::vector<raytrace::Ray> batch;
    for (std::size_t i : pending) batch.push_back(rays[i]);
    const auto hits = rt.intersectBatch(batch);
    std::vector<std::size_t> again;
    for (std::size_t k = 0; k < pending.size(); ++k) {
      const std::size_t i = pending[k];
      if (!hits[k]) continue;
      // A piece of a merged patch lies in the plane of all its triangles: a hit on any of
      // them is the piece's own surface.
      const std::uint32_t hit = hits[k]->triangle;
      if (hit == source[i] || (hit < mesh.trianglePatch.size() && mesh.trianglePatch[hit] == source[i])) {
        rays[i].tnear = hits[k]->t + 1e-7f;
        again.push_back(i);
      } else {
        blocked[i] = 1;
      }
    }
    pending.swap(again);
  }
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ++r.samples;
    r.agree += (blocked[i] == 0) == (expected[i] == 1);
  }
  return r;
}

/// The largest relative difference between the area of an input triangle, or of a patch
/// of coplanar triangles merged (CutMesh::trianglePatch), and the summed area of its
/// pieces (precise positions), over those with area.
inline double worstAreaError(const Mesh& scene, const CutMesh& mesh) {
  std::vector<double> sum(scene.triangleCount(), 0.0), input(scene.triangleCount(), 0.0);
  for (std::size_t p = 0; p < mesh.polygonCount(); ++p) sum[mesh.polygonSource[p]] += polygonArea(mesh, p);
  for (std::size_t t = 0; t < scene.triangleCount(); ++t) {
    const dvec3 a(scene.positions[scene.indices[3 * t]]), b(scene.positions[scene.indices[3 * t + 1]]),
        c(scene.positions[scene.indices[3 * t + 2]]);
    input[mesh.trianglePatch.empty() ? t : mesh.trianglePatch[t]] += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  double worst = 0.0;
  for (std::size_t t = 0; t < scene.triangleCount(); ++t) {
    if (input[t] == 0.0) continue;
    worst = std::max(worst, std::abs(sum[t] - input[t]) / input[t]);
  }
  return worst;
}

/// The connected surfaces of a mesh (triangles joined by edges): a label per triangle.
inline std::vector<std::uint32_t> surfaces(const Mesh& mesh) {
  const EdgeMap map = EdgeMap::build(mesh);
  std::vector<std::uint32_t> label(mesh.triangleCount());
  for (std::uint32_t i = 0; i < label.size(); ++i) label[i] = i;
  const auto root = [&](std::uint32_t x) {
    while (label[x] != x) x = label[x] = label[label[x]];
    return x;
  };
  for (const Edge& e : map.edges()) {
    const auto faces = map.faces(e);
    for (std::size_t i = 1; i < faces.size(); ++i) {
      const std::uint32_t a = root(faces[0].face), b = root(faces[i].face);
      if (a != b) label[std::max(a, b)] = std::min(a, b);
    }
  }
  for (std::uint32_t i = 0; i < label.size(); ++i) label[i] = root(i);
  return label;
}

/// Edge topology of each input surface's pieces on its own: "" when every surface that
/// was a closed manifold still is one, else what is wrong. (Surfaces that touch in the
/// input get vertices at the same positions, so the output as a whole is checked per
/// surface; EdgeMap welds by position.)
inline std::string surfacesStillClosed(const Mesh& scene, const CutMesh& mesh) {
  const std::vector<std::uint32_t> label = surfaces(scene);
  const Triangles tris = triangulate(mesh);
  std::string problems;
  std::vector<std::uint32_t> roots(label);
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  for (std::uint32_t r : roots) {
    Mesh in, out;
    in.positions = scene.positions;
    for (std::size_t t = 0; t < scene.triangleCount(); ++t)
      if (label[t] == r) in.indices.insert(in.indices.end(), scene.indices.begin() + std::ptrdiff_t(3 * t),
                                           scene.indices.begin() + std::ptrdiff_t(3 * t + 3));
    if (!EdgeMap::build(in).isClosedManifold()) continue;
    out.positions = tris.mesh.positions;
    for (std::size_t t = 0; t < tris.trianglePolygon.size(); ++t)
      if (label[mesh.polygonSource[tris.trianglePolygon[t]]] == r)
        out.indices.insert(out.indices.end(), tris.mesh.indices.begin() + std::ptrdiff_t(3 * t),
                           tris.mesh.indices.begin() + std::ptrdiff_t(3 * t + 3));
    const EdgeMap map = EdgeMap::build(out);
    if (!map.isClosedManifold())
      problems += "surface of triangle " + std::to_string(r) + ": " + std::to_string(map.count(EdgeKind::Open)) + " open, " +
                  std::to_string(map.count(EdgeKind::NonManifold)) + " non-manifold, " +
                  std::to_string(map.count(EdgeKind::Inconsistent)) + " inconsistent, " +
                  std::to_string(map.degenerateFaces()) + " degenerate; ";
  }
  return problems;
}

}  // namespace glint::cut::testing
