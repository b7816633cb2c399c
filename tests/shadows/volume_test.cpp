// The edge map and shadow-volume construction without a GL context: topology counted
// by hand, volumes checked for watertightness, and stencil counts (winding numbers of
// the volume) checked against brute-force counts of the triangles between the light
// and a point — an independent computation of what the stencil buffer should hold.
#include "glint/core/error.h"
#include "glint/mesh/adjacency.h"
#include "glint/shadows/volume.h"
#include "glint/shadows/world.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

using namespace glint;
using namespace glint::shadows;

namespace {

// Three quads sharing one edge along +Y: one non-manifold edge, open edges elsewhere.
Mesh fins() {
  Mesh m;
  for (int k = 0; k < 3; ++k) {
    const float a = float(k) * 2.0f * kPi / 3.0f;
    const vec3 d{std::cos(a), 0.0f, std::sin(a)};
    const auto b = std::uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {vec3(0, -0.5f, 0), d + vec3(0, -0.5f, 0), d + vec3(0, 0.5f, 0), vec3(0, 0.5f, 0)});
    m.indices.insert(m.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
  }
  return m;
}

// An icosphere with a cap of triangles removed: one hole.
Mesh openSphere() {
  Mesh m = makeIcosphere(1.0f, 2);
  std::vector<std::uint32_t> kept;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const vec3 c = (m.positions[m.indices[3 * t]] + m.positions[m.indices[3 * t + 1]] + m.positions[m.indices[3 * t + 2]]) / 3.0f;
    if (c.y > -0.75f) kept.insert(kept.end(), m.indices.begin() + long(3 * t), m.indices.begin() + long(3 * t + 3));
  }
  m.indices = kept;
  return m;
}

TEST(EdgeMap, CubeWeldsItsSplitVerticesIntoAClosedManifold) {
  const Mesh cube = makeCube(2.0f);
  ASSERT_EQ(cube.vertexCount(), 24u);
  const EdgeMap map = EdgeMap::build(cube);
  EXPECT_EQ(map.positions().size(), 8u);
  EXPECT_EQ(map.edges().size(), 18u);  // 12 box edges + 6 face diagonals
  EXPECT_EQ(map.count(EdgeKind::Manifold), 18u);
  EXPECT_TRUE(map.isClosedManifold());
  EXPECT_EQ(map.borderLoops(), 0u);
  for (const Edge& e : map.edges()) {
    ASSERT_EQ(map.faces(e).size(), 2u);
    EXPECT_EQ(map.faces(e)[0].orientation, -map.faces(e)[1].orientation);
  }
}

TEST(EdgeMap, SphereIsClosedAndEulerCharacteristicIsTwo) {
  const EdgeMap map = EdgeMap::build(makeUvSphere(1.0f, 24, 12));
  EXPECT_TRUE(map.isClosedManifold());
  EXPECT_EQ(long(map.positions().size()) - long(map.edges().size()) + long(map.faceCount() - map.degenerateFaces()), 2);
}

TEST(EdgeMap, PlaneHasFourOpenEdgesInOneLoop) {
  const EdgeMap map = EdgeMap::build(makePlane());
  EXPECT_EQ(map.count(EdgeKind::Open), 4u);
  EXPECT_EQ(map.count(EdgeKind::Manifold), 1u);
  EXPECT_EQ(map.borderLoops(), 1u);
  EXPECT_FALSE(map.isClosedManifold());
}

TEST(EdgeMap, FinsHaveOneNonManifoldEdge) {
  const EdgeMap map = EdgeMap::build(fins());
  EXPECT_EQ(map.count(EdgeKind::NonManifold), 1u);
  for (const Edge& e : map.edges()) {
    if (map.kind(e) == EdgeKind::NonManifold) {
      EXPECT_EQ(map.faces(e).size(), 3u);
    }
  }
  EXPECT_EQ(map.count(EdgeKind::Open), 3u * 3u);  // each fin's three outer sides
}

TEST(EdgeMap, FlippedTriangleMakesInconsistentEdgesAndDegenerateOnesAreSkipped) {
  Mesh m = makeCube(2.0f);
  std::swap(m.indices[1], m.indices[2]);
  m.indices.insert(m.indices.end(), {0, 0, 1});
  const EdgeMap map = EdgeMap::build(m);
  EXPECT_EQ(map.degenerateFaces(), 1u);
  EXPECT_GE(map.count(EdgeKind::Inconsistent), 2u);
  EXPECT_FALSE(map.isClosedManifold());
  EXPECT_EQ(map.faceEdges(std::uint32_t(m.triangleCount() - 1))[0], EdgeMap::kNone);
}

// ---------------------------------------------------------------------------
// Volumes as finite triangle soups: w = 0 vertices placed far along their direction.
constexpr double kFar = 1.0e4;

using Tri = std::array<glm::dvec3, 3>;

std::vector<Tri> finite(const std::vector<vec4>& v, vec3 light) {
  std::vector<Tri> out;
  for (std::size_t i = 0; i + 2 < v.size(); i += 3) {
    Tri t;
    for (int k = 0; k < 3; ++k) {
      const vec4 p = v[i + std::size_t(k)];
      t[std::size_t(k)] = p.w == 0.0f ? glm::dvec3(light) + kFar * glm::normalize(glm::dvec3(p)) : glm::dvec3(p);
    }
    out.push_back(t);
  }
  return out;
}

// Möller–Trumbore in double: ray parameter of the hit, or negative.
double hit(const glm::dvec3& o, const glm::dvec3& d, const Tri& t) {
  const glm::dvec3 e1 = t[1] - t[0], e2 = t[2] - t[0], p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-14) return -1.0;
  const glm::dvec3 s = o - t[0];
  const double u = glm::dot(s, p) / det;
  if (u < 0.0 || u > 1.0) return -1.0;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det;
  if (v < 0.0 || u + v > 1.0) return -1.0;
  return glm::dot(e2, q) / det;
}

// Winding number of a closed, outward-oriented soup around p: signed crossings of a ray.
int winding(const std::vector<Tri>& soup, const glm::dvec3& p, const glm::dvec3& dir) {
  int w = 0;
  for (const Tri& t : soup) {
    if (hit(p, dir, t) > 0.0) {
      const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
      w += glm::dot(n, dir) > 0.0 ? 1 : -1;  // leaving through an outward face
    }
  }
  return w;
}

// Triangles of the caster between the light and p.
int trianglesBetween(const Mesh& m, vec3 light, const glm::dvec3& p) {
  int n = 0;
  const glm::dvec3 l(light);
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const Tri tri{glm::dvec3(m.positions[m.indices[3 * t]]), glm::dvec3(m.positions[m.indices[3 * t + 1]]),
                  glm::dvec3(m.positions[m.indices[3 * t + 2]])};
    const double s = hit(l, p - l, tri);
    if (s > 0.0 && s < 1.0) ++n;
  }
  return n;
}

// Every directed edge matched by its reverse: a closed, consistently oriented surface.
std::size_t unmatchedEdges(const std::vector<vec4>& v) {
  std::map<std::pair<std::array<float, 4>, std::array<float, 4>>, int> count;
  const auto key = [](vec4 a) { return std::array<float, 4>{a.x, a.y, a.z, a.w}; };
  for (std::size_t i = 0; i + 2 < v.size(); i += 3)
    for (std::size_t k = 0; k < 3; ++k) {
      const vec4 a = v[i + k], b = v[i + (k + 1) % 3];
      ++count[{key(a), key(b)}];
      --count[{key(b), key(a)}];
    }
  std::size_t bad = 0;
  for (const auto& [edge, c] : count) bad += std::size_t(std::abs(c));
  return bad / 2;
}

struct Case {
  const char* name;
  Mesh mesh;
};

std::vector<Case> casters() {
  return {{"sphere", makeUvSphere(1.0f, 16, 8)}, {"torus", makeTorus(1.0f, 0.35f, 16, 8)}, {"open sphere", openSphere()},
          {"fins", fins()}, {"plane", makePlane(1.5f)}};
}

TEST(ShadowVolume, ClosedAndTwoSidedVolumesAreWatertightOnAnyMesh) {
  const vec3 light{0.7f, 4.0f, 0.4f};
  for (const auto& c : casters()) {
    const EdgeMap map = EdgeMap::build(c.mesh);
    for (CasterMode mode : {CasterMode::Closed, CasterMode::TwoSided}) {
      const ShadowVolume v = buildShadowVolume(map, light, mode, true);
      EXPECT_GT(v.sideTriangles, 0u) << c.name;
      EXPECT_EQ(unmatchedEdges(v.vertices), 0u) << c.name << " mode " << int(mode);
    }
  }
  // The textbook rule leaves the open meshes' volumes unclosed: that is the leak.
  // (Lit from below, so that the faces around the hole face the light.)
  const ShadowVolume naive =
      buildShadowVolume(EdgeMap::build(openSphere()), {0.7f, -4.0f, 0.4f}, CasterMode::Naive, true);
  EXPECT_GT(unmatchedEdges(naive.vertices), 0u);
}

TEST(ShadowVolume, ClosedModeOnAClosedMeshIsTheClassicSilhouette) {
  // A sphere lit from above: the silhouette is one ring of edges, each with one quad.
  const Mesh sphere = makeUvSphere(1.0f, 16, 8);
  const EdgeMap map = EdgeMap::build(sphere);
  const ShadowVolume v = buildShadowVolume(map, {0.0f, 5.0f, 0.0f}, CasterMode::Closed, false);
  EXPECT_EQ(v.sideTriangles, 2 * v.silhouetteEdges);
  EXPECT_GE(v.silhouetteEdges, 16u);
  EXPECT_LE(v.silhouetteEdges, 32u);
  EXPECT_EQ(v.capTriangles, 0u);
}

// The stencil count z-fail computes at a point is the volume's winding number there.
TEST(ShadowVolume, WindingNumberCountsTheTrianglesBetweenLightAndPoint) {
  const vec3 light{1.8f, 2.2f, 0.6f};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xz(-3.0, 2.0), y(-2.5, 1.0);
  for (const auto& c : casters()) {
    const EdgeMap map = EdgeMap::build(c.mesh);
    const auto twoSided = finite(buildShadowVolume(map, light, CasterMode::TwoSided, true).vertices, light);
    const auto closed = finite(buildShadowVolume(map, light, CasterMode::Closed, true).vertices, light);
    // The GPU method, its vertex shader emulated: faces turned from the light go to infinity.
    const ExtrusionMesh ex = buildExtrusionMesh(map, true);
    std::vector<vec4> gpu;
    for (std::uint32_t i : ex.indices) {
      const vec3 p = ex.positions[i];
      gpu.push_back(glm::dot(ex.faceNormals[i], light - p) > 0.0f ? vec4(p, 1.0f) : vec4(p - light, 0.0f));
    }
    const auto gpuSoup = finite(gpu, light);
    int checked = 0, shadowed = 0;
    for (int i = 0; i < 300; ++i) {
      const glm::dvec3 p{xz(rng), y(rng), xz(rng)};
      const glm::dvec3 dir = glm::normalize(glm::dvec3(0.31, -0.77, 0.56));  // arbitrary, not axis-aligned
      const int between = trianglesBetween(c.mesh, light, p);
      EXPECT_EQ(winding(twoSided, p, dir), between) << c.name << " two-sided at " << p.x << "," << p.y << "," << p.z;
      EXPECT_EQ(winding(gpuSoup, p, dir), between) << c.name << " GPU at " << p.x << "," << p.y << "," << p.z;
      // Closed mode counts light-facing triangles only: zero exactly where nothing is between.
      const int closedCount = winding(closed, p, dir);
      EXPECT_GE(closedCount, 0) << c.name;
      if (between == 0) {
        EXPECT_EQ(closedCount, 0) << c.name;
      }
      ++checked;
      shadowed += between > 0;
    }
    EXPECT_GT(shadowed, 10) << c.name << ": too few points in shadow to mean anything";
    EXPECT_EQ(checked, 300);
  }
}

TEST(ShadowVolume, OneSidedGpuExtrusionNeedsAClosedMesh) {
  EXPECT_THROW(buildExtrusionMesh(EdgeMap::build(makePlane()), false), Error);
  const ExtrusionMesh m = buildExtrusionMesh(EdgeMap::build(makeCube(1.0f)), false);
  EXPECT_EQ(m.faceTriangles, 12u);
  EXPECT_EQ(m.quadTriangles, 2u * 18u);  // one degenerate quad per edge
  EXPECT_EQ(m.positions.size(), 36u);    // faces do not share vertices
}

}  // namespace
