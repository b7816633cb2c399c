// Unit tests for glint/mesh: generators checked against analytic geometry
// (areas, volumes, normals, topology), mesh operations against hand-computed
// answers, and the importer against small files written by the tests themselves.
#include "glint/core/error.h"
#include "glint/mesh/mesh.h"

#include <gtest/gtest.h>

#include "support/files.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;

namespace {

constexpr double kPiD = 3.14159265358979323846;

// ---------------------------------------------------------------------------
// Geometry helpers, in double so that they measure the mesh, not their own
// rounding.

glm::dvec3 dv(const vec3& v) { return glm::dvec3(v); }

glm::dvec3 corner(const Mesh& m, std::size_t tri, int k) { return dv(m.positions[m.indices[3 * tri + std::size_t(k)]]); }

/// Twice-area vector of a triangle; points to the side from which it is counter-clockwise.
glm::dvec3 faceCross(const Mesh& m, std::size_t tri) {
  const glm::dvec3 a = corner(m, tri, 0), b = corner(m, tri, 1), c = corner(m, tri, 2);
  return glm::cross(b - a, c - a);
}

double surfaceArea(const Mesh& m) {
  double area = 0.0;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) area += 0.5 * glm::length(faceCross(m, t));
  return area;
}

/// Divergence theorem: sum of signed tetrahedra (origin, triangle). Positive for a
/// closed mesh whose counter-clockwise sides face outwards.
double signedVolume(const Mesh& m) {
  double volume = 0.0;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    volume += glm::dot(corner(m, t, 0), glm::cross(corner(m, t, 1), corner(m, t, 2))) / 6.0;
  }
  return volume;
}

/// Smallest distance from the origin to a triangle's plane (the inradius of a convex polyhedron).
double minPlaneDistance(const Mesh& m) {
  double d = 1e30;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    d = std::min(d, glm::dot(glm::normalize(faceCross(m, t)), corner(m, t, 0)));
  }
  return d;
}

struct Topology {
  bool closed = true;  ///< every directed edge has exactly one opposite twin
  std::string problem;
  long vertices = 0, edges = 0, faces = 0;
  long euler() const { return vertices - edges + faces; }
};

/// Welds coincident positions (UV seams, poles, cube corners) and checks that
/// every edge is shared by exactly two triangles that traverse it in opposite
/// directions, i.e. the surface is closed and consistently oriented.
Topology topology(const Mesh& m) {
  std::map<std::array<long long, 3>, long> ids;
  std::vector<long> weld(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const vec3& p = m.positions[i];
    // 1e-5 grid: far finer than any edge in these tests, far coarser than rounding.
    const std::array<long long, 3> key{std::llround(p.x * 1e5), std::llround(p.y * 1e5), std::llround(p.z * 1e5)};
    weld[i] = ids.try_emplace(key, long(ids.size())).first->second;
  }
  Topology topo;
  topo.vertices = long(ids.size());
  topo.faces = long(m.triangleCount());
  std::map<std::pair<long, long>, int> directed;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const long v[3] = {weld[m.indices[3 * t]], weld[m.indices[3 * t + 1]], weld[m.indices[3 * t + 2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      topo.closed = false;
      topo.problem = "degenerate triangle " + std::to_string(t);
    }
    for (int k = 0; k < 3; ++k) ++directed[{v[k], v[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    const auto twin = directed.find({edge.second, edge.first});
    if (count != 1 || twin == directed.end() || twin->second != 1) {
      topo.closed = false;
      topo.problem = "edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) + " used " +
                     std::to_string(count) + "x, opposite " +
                     std::to_string(twin == directed.end() ? 0 : twin->second) + "x";
    }
  }
  topo.edges = long(directed.size() / 2);
  return topo;
}

/// Every triangle's counter-clockwise side agrees with its vertex normals, so
/// back-face culling and shading see the same "outside".
void expectFrontFacesAgreeWithNormals(const Mesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  int bad = 0;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const glm::dvec3 n = faceCross(m, t);
    for (int k = 0; k < 3; ++k) {
      if (glm::dot(n, dv(m.normals[m.indices[3 * t + std::size_t(k)]])) <= 0.0) ++bad;
    }
  }
  EXPECT_EQ(bad, 0) << "triangle corners whose winding disagrees with the vertex normal";
}

void expectUnitNormals(const Mesh& m) {
  for (std::size_t i = 0; i < m.normals.size(); ++i) {
    ASSERT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-5f) << "normal " << i;
  }
}

void expectUvsIn(const Mesh& m, float lo, float hi) {
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  for (const vec2& uv : m.uvs) {
    ASSERT_GE(uv.x, lo);
    ASSERT_LE(uv.x, hi);
    ASSERT_GE(uv.y, lo);
    ASSERT_LE(uv.y, hi);
  }
}

/// Tangents must match the direction in which u grows across each triangle
/// (the standard UV-gradient tangent), and w must pick the bitangent along +v.
/// `minCos` allows for the tangent's rotation across one tessellation step.
void expectTangentsFollowUvs(const Mesh& m, double minCos) {
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  for (std::size_t i = 0; i < m.tangents.size(); ++i) {
    const vec3 t(m.tangents[i]);
    ASSERT_NEAR(glm::length(t), 1.0f, 1e-5f);
    ASSERT_NEAR(glm::dot(t, m.normals[i]), 0.0f, 1e-5f) << "tangent " << i << " not perpendicular";
    ASSERT_EQ(std::abs(m.tangents[i].w), 1.0f);
  }
  for (std::size_t tri = 0; tri < m.triangleCount(); ++tri) {
    const std::uint32_t i0 = m.indices[3 * tri], i1 = m.indices[3 * tri + 1], i2 = m.indices[3 * tri + 2];
    const glm::dvec3 e1 = dv(m.positions[i1] - m.positions[i0]), e2 = dv(m.positions[i2] - m.positions[i0]);
    const glm::dvec2 d1 = glm::dvec2(m.uvs[i1] - m.uvs[i0]), d2 = glm::dvec2(m.uvs[i2] - m.uvs[i0]);
    const double det = d1.x * d2.y - d2.x * d1.y;
    ASSERT_GT(std::abs(det), 1e-12) << "triangle " << tri << " has degenerate UVs";
    const glm::dvec3 dpdu = glm::normalize((e1 * d2.y - e2 * d1.y) / det);
    const glm::dvec3 dpdv = (e2 * d1.x - e1 * d2.x) / det;
    for (std::uint32_t i : {i0, i1, i2}) {
      const glm::dvec3 t = dv(vec3(m.tangents[i])), n = dv(m.normals[i]);
      ASSERT_GT(glm::dot(t, dpdu), minCos) << "triangle " << tri << " vertex " << i;
      ASSERT_GT(glm::dot(glm::cross(n, t) * double(m.tangents[i].w), dpdv), 0.0) << "triangle " << tri << " vertex " << i;
    }
  }
}

Mesh oneTriangle() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  return m;
}

using glint::testing::captureError;

}  // namespace

// ---------------------------------------------------------------------------
// Mesh operations

TEST(MeshBounds, EmptyMeshHasZeroBounds) {
  const Bounds b = Mesh{}.bounds();
  EXPECT_EQ(b.min, vec3(0.0f));
  EXPECT_EQ(b.max, vec3(0.0f));
  EXPECT_EQ(b.diagonal(), 0.0f);
}

TEST(MeshBounds, CoverAllPositions) {
  Mesh m;
  m.positions = {{1, -2, 3}, {-4, 5, 0.5f}, {2, 0, -6}};
  const Bounds b = m.bounds();
  EXPECT_EQ(b.min, vec3(-4, -2, -6));
  EXPECT_EQ(b.max, vec3(2, 5, 3));
  EXPECT_EQ(b.center(), vec3(-1, 1.5f, -1.5f));
  EXPECT_FLOAT_EQ(b.diagonal(), std::sqrt(36.0f + 49.0f + 81.0f));
}

TEST(MeshValidate, AcceptsWellFormedMeshes) {
  EXPECT_NO_THROW(oneTriangle().validate());
  EXPECT_NO_THROW(makeUvSphere().validate());
  EXPECT_NO_THROW(makeTorus().validate());
}

TEST(MeshValidate, RejectsMalformedMeshesAsInputErrors) {
  struct Case {
    const char* name;
    void (*breakIt)(Mesh&);
    const char* expectInMessage;
  };
  const Case cases[] = {
      {"no triangles", [](Mesh& m) { m.indices.clear(); }, "no triangles"},
      {"ragged indices", [](Mesh& m) { m.indices.push_back(0); }, "multiple of 3"},
      {"index out of range", [](Mesh& m) { m.indices[2] = 3; }, "out of range"},
      {"NaN position", [](Mesh& m) { m.positions[1].y = std::nanf(""); }, "not finite"},
      {"infinite position", [](Mesh& m) { m.positions[0].z = INFINITY; }, "not finite"},
      {"short normals", [](Mesh& m) { m.normals.assign(2, vec3(0, 0, 1)); }, "normals"},
      {"long uvs", [](Mesh& m) { m.uvs.assign(4, vec2(0)); }, "uvs"},
      {"short tangents", [](Mesh& m) { m.tangents.assign(1, vec4(1, 0, 0, 1)); }, "tangents"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Mesh m = oneTriangle();
    c.breakIt(m);
    const Error e = captureError([&] { m.validate("thing.obj"); });
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    const std::string msg = e.what();
    EXPECT_NE(msg.find("thing.obj"), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expectInMessage), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(MeshAppend, RebasesIndicesAndKeepsOnlySharedAttributes) {
  Mesh a = oneTriangle();
  a.normals.assign(3, vec3(0, 0, 1));
  a.uvs.assign(3, vec2(0.25f));
  Mesh b = oneTriangle();
  for (vec3& p : b.positions) p += vec3(10, 0, 0);
  b.normals.assign(3, vec3(0, 0, 1));  // normals on both, UVs only on a

  a.append(b);
  ASSERT_EQ(a.vertexCount(), 6u);
  EXPECT_EQ(a.indices, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(a.positions[4], vec3(11, 0, 0));
  EXPECT_EQ(a.normals.size(), 6u);
  EXPECT_TRUE(a.uvs.empty()) << "UVs cannot be invented for the appended part";
  EXPECT_NO_THROW(a.validate());
}

TEST(MeshAppend, EmptyMeshTakesOverTheOthersAttributes) {
  Mesh acc;
  const Mesh cube = makeCube();
  acc.append(cube);
  EXPECT_EQ(acc.positions, cube.positions);
  EXPECT_EQ(acc.uvs.size(), cube.vertexCount());
  EXPECT_EQ(acc.tangents.size(), cube.vertexCount());
  acc.append(cube);
  EXPECT_EQ(acc.triangleCount(), 24u);
  EXPECT_EQ(acc.indices[36], 24u);
  EXPECT_NEAR(signedVolume(acc), 16.0, 1e-4);
}

TEST(MeshTransform, NonUniformScaleTransformsNormalsByInverseTranspose) {
  Mesh m = makeUvSphere(1.0f, 32, 16);
  const vec3 scale(3.0f, 1.0f, 0.5f), offset(1.0f, -2.0f, 4.0f);
  m.transform(glm::scale(glm::translate(mat4(1.0f), offset), scale));
  expectUnitNormals(m);
  for (std::size_t i = 0; i < m.vertexCount(); ++i) {
    // Ellipsoid x²/a² + y²/b² + z²/c² = 1: the normal is its gradient (x/a², y/b², z/c²).
    const vec3 p = m.positions[i] - offset;
    ASSERT_NEAR(glm::dot(p / scale, p / scale), 1.0f, 1e-5f) << "position " << i;
    const vec3 expected = glm::normalize(p / (scale * scale));
    ASSERT_GT(glm::dot(m.normals[i], expected), 1.0f - 1e-5f) << "normal " << i;
    // Transforming the tangent by the matrix itself keeps it in the surface.
    ASSERT_NEAR(glm::dot(vec3(m.tangents[i]), m.normals[i]), 0.0f, 1e-5f) << "tangent " << i;
  }
  expectFrontFacesAgreeWithNormals(m);
  // Closed, so the signed volume ignores the translation: ≈ 4/3·π·abc, less the inscribed-mesh deficit.
  EXPECT_NEAR(signedVolume(m), 4.0 / 3.0 * kPiD * 3.0 * 1.0 * 0.5, 0.02 * 2.0 * kPiD);
}

TEST(MeshTransform, MirrorKeepsFrontFacesOutward) {
  Mesh m = makeCube(2.0f);
  m.transform(glm::scale(mat4(1.0f), vec3(-1.0f, 1.0f, 1.0f)));
  // A mirrored cube is still the same cube: outward normals, positive volume.
  EXPECT_NEAR(signedVolume(m), 8.0, 1e-5);
  for (std::size_t i = 0; i < m.vertexCount(); ++i) ASSERT_GT(glm::dot(m.normals[i], m.positions[i]), 0.0f);
  expectFrontFacesAgreeWithNormals(m);
  // The UV layout is mirrored too, so the bitangent sign must flip to follow +v.
  expectTangentsFollowUvs(m, 0.999);
}

TEST(ComputeNormals, WeightsFacesByArea) {
  // Two triangles meeting at the origin with a right angle each there: one in
  // the XZ plane (normal +Y, area 2), one in the XY plane (normal +Z, area 0.5).
  // Area weighting gives (0, 4, 1)/√17; angle or uniform weighting would give
  // (0, 1, 1)/√2.
  Mesh m;
  m.positions = {{0, 0, 0}, {0, 0, 2}, {2, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2, 0, 3, 4};
  computeNormals(m);
  ASSERT_EQ(m.normals.size(), 5u);
  const vec3 expected = glm::normalize(vec3(0, 4, 1));
  EXPECT_NEAR(m.normals[0].x, expected.x, 1e-6f);
  EXPECT_NEAR(m.normals[0].y, expected.y, 1e-6f);
  EXPECT_NEAR(m.normals[0].z, expected.z, 1e-6f);
  EXPECT_EQ(m.normals[1], vec3(0, 1, 0));
  EXPECT_EQ(m.normals[4], vec3(0, 0, 1));
}

TEST(ComputeNormals, ReproducesFlatCubeAndRadialIcosphereNormals) {
  Mesh cube = makeCube();
  const std::vector<vec3> generated = cube.normals;
  computeNormals(cube);
  for (std::size_t i = 0; i < generated.size(); ++i) EXPECT_EQ(cube.normals[i], generated[i]);

  // Each face's plane normal is as far from the direction of each of its corners
  // as the face's angular circumradius (≤ 5.45° at level 3, see the icosphere
  // test), and an average of vectors inside that cone stays inside it.
  Mesh ico = makeIcosphere(2.0f, 3);
  computeNormals(ico);
  expectUnitNormals(ico);
  for (std::size_t i = 0; i < ico.vertexCount(); ++i) {
    ASSERT_GT(glm::dot(ico.normals[i], glm::normalize(ico.positions[i])), std::cos(glm::radians(5.5f)));
  }
}

TEST(ComputeNormals, UnreferencedVertexGetsAUnitNormal) {
  Mesh m = oneTriangle();
  m.positions.push_back({5, 5, 5});
  computeNormals(m);
  expectUnitNormals(m);
  EXPECT_EQ(m.normals[0], vec3(0, 0, 1));
}

// ---------------------------------------------------------------------------
// Generators

TEST(MakePlane, IsAnUpwardSquareWithScaledUvs) {
  const Mesh m = makePlane(3.0f, 4.0f);
  ASSERT_NO_THROW(m.validate());
  EXPECT_EQ(m.vertexCount(), 4u);
  EXPECT_EQ(m.triangleCount(), 2u);
  EXPECT_NEAR(surfaceArea(m), 9.0, 1e-6);
  EXPECT_EQ(m.bounds().min, vec3(-1.5f, 0.0f, -1.5f));
  EXPECT_EQ(m.bounds().max, vec3(1.5f, 0.0f, 1.5f));
  for (std::size_t t = 0; t < m.triangleCount(); ++t) EXPECT_GT(faceCross(m, t).y, 0.0) << "CCW from above";
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(m.normals[i], vec3(0, 1, 0));
    // u grows along +X and v along -Z (away from a viewer looking down -Z).
    EXPECT_FLOAT_EQ(m.uvs[i].x, 4.0f * (m.positions[i].x + 1.5f) / 3.0f);
    EXPECT_FLOAT_EQ(m.uvs[i].y, 4.0f * (1.5f - m.positions[i].z) / 3.0f);
  }
  expectUvsIn(m, 0.0f, 4.0f);
  expectTangentsFollowUvs(m, 0.9999);
}

TEST(MakeGrid, HasDocumentedCountsAndCoversThePlane) {
  const Mesh m = makeGrid(5, 3, 2.0f, 2.0f);
  ASSERT_NO_THROW(m.validate());
  EXPECT_EQ(m.vertexCount(), 6u * 4u);
  EXPECT_EQ(m.triangleCount(), 2u * 5u * 3u);
  EXPECT_NEAR(surfaceArea(m), 4.0, 1e-5);
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    ASSERT_GT(faceCross(m, t).y, 0.0) << "CCW from above";
    ASSERT_NEAR(0.5 * glm::length(faceCross(m, t)), 4.0 / 30.0, 1e-6) << "equal cells";
  }
  for (const vec3& n : m.normals) ASSERT_EQ(n, vec3(0, 1, 0));
  for (const vec3& p : m.positions) ASSERT_EQ(p.y, 0.0f);
  expectUvsIn(m, 0.0f, 2.0f);
  expectTangentsFollowUvs(m, 0.9999);
  // An open sheet: boundary edges (used once) number 2 * (5 + 3).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = m.indices[3 * t + std::size_t(k)], b = m.indices[3 * t + std::size_t((k + 1) % 3)];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  int boundary = 0;
  for (const auto& [e, n] : edges) boundary += n == 1;
  EXPECT_EQ(boundary, 16);
  EXPECT_THROW(makeGrid(0, 3), Error);
}

TEST(MakeCube, IsAClosedOutwardCubeWithFlatFaces) {
  const float s = 1.5f;
  const Mesh m = makeCube(s);
  ASSERT_NO_THROW(m.validate());
  EXPECT_EQ(m.vertexCount(), 24u);
  EXPECT_EQ(m.triangleCount(), 12u);
  EXPECT_EQ(m.bounds().min, vec3(-0.75f));
  EXPECT_EQ(m.bounds().max, vec3(0.75f));
  EXPECT_NEAR(surfaceArea(m), 6.0 * s * s, 1e-5);
  EXPECT_NEAR(signedVolume(m), double(s) * s * s, 1e-5);
  const Topology topo = topology(m);
  EXPECT_TRUE(topo.closed) << topo.problem;
  EXPECT_EQ(topo.vertices, 8);
  EXPECT_EQ(topo.euler(), 2);
  // Flat shading: each triangle's vertex normals equal its geometric normal,
  // which is one of the six axes and points away from the centre.
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const vec3 n = vec3(glm::normalize(faceCross(m, t)));
    for (int k = 0; k < 3; ++k) ASSERT_EQ(m.normals[m.indices[3 * t + std::size_t(k)]], n);
    ASSERT_NEAR(glm::dot(vec3(corner(m, t, 0)), n), 0.75f, 1e-6f);
  }
  // Every face maps the full 0..1 square.
  for (std::size_t face = 0; face < 6; ++face) {
    vec2 lo(1e9f), hi(-1e9f);
    for (std::size_t i = 4 * face; i < 4 * face + 4; ++i) {
      lo = glm::min(lo, m.uvs[i]);
      hi = glm::max(hi, m.uvs[i]);
    }
    EXPECT_EQ(lo, vec2(0.0f));
    EXPECT_EQ(hi, vec2(1.0f));
  }
  expectTangentsFollowUvs(m, 0.9999);
}

// Spheres: the polyhedron is convex and inscribed, so it lies between the
// sphere and the ball of radius d (its smallest face-plane distance). Convex
// bodies that nest have nested areas and volumes, which gives rigorous bounds
//   4πd² ≤ A ≤ 4πr²   and   4/3πd³ ≤ V ≤ 4/3πr³,
// and a quad of angular size Δφ × Δθ has d ≥ r·cos(Δφ/2)·cos(Δθ/2) (its corners
// lie within that angle of the quad's centre), which turns them into a-priori
// tolerances from the tessellation alone.
TEST(MakeUvSphere, MatchesTheAnalyticSphere) {
  const float r = 1.7f;
  const int segments = 48, rings = 24;
  const Mesh m = makeUvSphere(r, segments, rings);
  ASSERT_NO_THROW(m.validate());
  EXPECT_EQ(m.vertexCount(), std::size_t(2 * segments + (rings - 1) * (segments + 1)));
  EXPECT_EQ(m.triangleCount(), std::size_t(2 * segments * (rings - 1)));
  expectUnitNormals(m);
  for (std::size_t i = 0; i < m.vertexCount(); ++i) {
    ASSERT_NEAR(glm::length(m.positions[i]), r, 1e-5f * r);
    ASSERT_GT(glm::dot(m.normals[i], m.positions[i]), 0.0f) << "normal " << i << " points inwards";
    ASSERT_GT(glm::dot(m.normals[i], m.positions[i] / r), 1.0f - 1e-6f) << "normal " << i << " not radial";
    // v runs from the south pole (0) to the north pole (1).
    ASSERT_NEAR(m.uvs[i].y, std::acos(-m.positions[i].y / r) / kPi, 1e-4f);
  }
  expectUvsIn(m, 0.0f, 1.0f);
  expectFrontFacesAgreeWithNormals(m);
  const Topology topo = topology(m);
  EXPECT_TRUE(topo.closed) << topo.problem;
  EXPECT_EQ(topo.euler(), 2);

  const double d = minPlaneDistance(m);
  const double dPrior = r * std::cos(kPiD / segments) * std::cos(kPiD / (2 * rings));  // ≈ 0.9957 r
  EXPECT_GE(d, dPrior * (1.0 - 1e-6));
  const double area = surfaceArea(m), volume = signedVolume(m);
  EXPECT_LE(area, 4.0 * kPiD * r * r);
  EXPECT_GE(area, 4.0 * kPiD * dPrior * dPrior);  // within 0.86 %
  EXPECT_LE(volume, 4.0 / 3.0 * kPiD * r * r * r);
  EXPECT_GE(volume, 4.0 / 3.0 * kPiD * dPrior * dPrior * dPrior);  // within 1.3 %
  expectTangentsFollowUvs(m, std::cos(kPiD / segments) - 1e-3);
}

TEST(MakeUvSphere, ErrorShrinksQuadraticallyWithTessellation) {
  // Chord-vs-arc errors are O(h²): doubling both counts divides them by ~4.
  const double exact = 4.0 * kPiD;
  const double coarse = exact - surfaceArea(makeUvSphere(1.0f, 24, 12));
  const double fine = exact - surfaceArea(makeUvSphere(1.0f, 48, 24));
  EXPECT_GT(fine, 0.0);
  EXPECT_NEAR(coarse / fine, 4.0, 0.3);
}

TEST(MakeIcosphere, VerticesLieExactlyOnTheSphere) {
  const float r = 2.5f;
  for (int n = 0; n <= 4; ++n) {
    SCOPED_TRACE(n);
    const Mesh m = makeIcosphere(r, n);
    ASSERT_NO_THROW(m.validate());
    const std::size_t pow4 = std::size_t(1) << (2 * n);
    EXPECT_EQ(m.vertexCount(), 10 * pow4 + 2);
    EXPECT_EQ(m.triangleCount(), 20 * pow4);
    EXPECT_FALSE(m.hasUvs());
    expectUnitNormals(m);
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
      // "Exactly" = up to float rounding of a normalized vector times r.
      ASSERT_NEAR(glm::length(dv(m.positions[i])), double(r), 4e-7 * r);
      ASSERT_GT(glm::dot(m.normals[i], m.positions[i] / r), 1.0f - 1e-6f);
    }
    expectFrontFacesAgreeWithNormals(m);
    const Topology topo = topology(m);
    EXPECT_TRUE(topo.closed) << topo.problem;
    EXPECT_EQ(topo.vertices, long(m.vertexCount())) << "no duplicated vertices";
    EXPECT_EQ(topo.euler(), 2);
  }
}

TEST(MakeIcosphere, AreaAndVolumeConvergeToTheSphere) {
  const float r = 1.0f;
  const Mesh m = makeIcosphere(r, 3);
  // Level-3 faces have edges of up to 9.4° (the 63.4° icosahedron edge / 8,
  // stretched by the projection onto the sphere); their circumcircles subtend at
  // most 5.45° (computed once for this midpoint scheme), so d ≥ cos 5.5° ≈ 0.9954.
  const double dPrior = std::cos(5.5 * kPiD / 180.0);
  EXPECT_GE(minPlaneDistance(m), dPrior);
  const double area = surfaceArea(m), volume = signedVolume(m);
  EXPECT_LE(area, 4.0 * kPiD);
  EXPECT_GE(area, 4.0 * kPiD * dPrior * dPrior);
  EXPECT_LE(volume, 4.0 / 3.0 * kPiD);
  EXPECT_GE(volume, 4.0 / 3.0 * kPiD * dPrior * dPrior * dPrior);
  // Each subdivision halves the edges: area error drops by ~4.
  const double e3 = 4.0 * kPiD - area, e4 = 4.0 * kPiD - surfaceArea(makeIcosphere(r, 4));
  EXPECT_NEAR(e3 / e4, 4.0, 0.3);
}

// Torus with Δφ = 2π/segments, Δθ = 2π/sides. Each quad is a planar isosceles
// trapezoid with parallel sides 2ρ·sin(Δφ/2) (ρ = R + r·cos θ) and height
// ≈ rΔθ·(1 − Δθ²/24 − sin²θ·Δφ²/8) (the tube chord, shortened because its two
// ends sit at different ρ). Expanding to second order and summing (cos θ terms
// cancel, ρ·sin²θ averages to R/2) gives A ≈ 4π²Rr·(1 − Δθ²/24 − 5Δφ²/48). For the
// volume, the cross-section polygon loses Δθ²/6 and chords around the axis lose
// Δφ²/6: V ≈ 2π²Rr²·(1 − (Δφ² + Δθ²)/6). The neglected terms are O(h⁴), i.e.
// about deficit² relative, so 5 % of the deficit is ample slack (measured: 0.1 %
// and 0.3 %); a wrong winding, radius or tessellation count misses by far more.
TEST(MakeTorus, MatchesTheAnalyticTorus) {
  const float R = 2.0f, r = 0.5f;
  const int segments = 64, sides = 32;
  const Mesh m = makeTorus(R, r, segments, sides);
  ASSERT_NO_THROW(m.validate());
  EXPECT_EQ(m.vertexCount(), std::size_t((segments + 1) * (sides + 1)));
  EXPECT_EQ(m.triangleCount(), std::size_t(2 * segments * sides));
  expectUnitNormals(m);
  for (std::size_t i = 0; i < m.vertexCount(); ++i) {
    const vec3 p = m.positions[i];
    // Nearest point on the tube's centre circle (around +Y, radius R).
    const vec3 tubeCentre = R * glm::normalize(vec3(p.x, 0.0f, p.z));
    ASSERT_NEAR(glm::length(p - tubeCentre), r, 1e-5f);
    ASSERT_GT(glm::dot(m.normals[i], (p - tubeCentre) / r), 1.0f - 1e-5f) << "normal " << i;
  }
  expectUvsIn(m, 0.0f, 1.0f);
  expectFrontFacesAgreeWithNormals(m);
  const Topology topo = topology(m);
  EXPECT_TRUE(topo.closed) << topo.problem;
  EXPECT_EQ(topo.vertices, long(segments * sides));
  EXPECT_EQ(topo.euler(), 0);

  const double dphi = 2.0 * kPiD / segments, dtheta = 2.0 * kPiD / sides;
  const double areaExact = 4.0 * kPiD * kPiD * R * r, volumeExact = 2.0 * kPiD * kPiD * R * r * r;
  const double areaDeficit = dtheta * dtheta / 24.0 + 5.0 * dphi * dphi / 48.0;  // ≈ 0.26 %
  const double volumeDeficit = (dphi * dphi + dtheta * dtheta) / 6.0;  // ≈ 0.80 %
  const double areaErr = 1.0 - surfaceArea(m) / areaExact;
  const double volumeErr = 1.0 - signedVolume(m) / volumeExact;
  EXPECT_NEAR(areaErr, areaDeficit, 0.05 * areaDeficit);
  EXPECT_NEAR(volumeErr, volumeDeficit, 0.05 * volumeDeficit);
  expectTangentsFollowUvs(m, std::cos(kPiD / sides));
}

TEST(Generators, RejectDegenerateTessellations) {
  EXPECT_THROW(makeUvSphere(1.0f, 2, 8), Error);
  EXPECT_THROW(makeUvSphere(1.0f, 8, 1), Error);
  EXPECT_THROW(makeIcosphere(1.0f, -1), Error);
  EXPECT_THROW(makeTorus(1.0f, 0.3f, 8, 2), Error);
}

// ---------------------------------------------------------------------------
// Import

namespace {

fs::path outDir() { return glint::testing::testOutputDir("mesh"); }

fs::path writeFile(const std::string& name, const std::string& contents) {
  return glint::testing::writeTestFile(outDir(), name, contents);
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0u, b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0u;
    const unsigned v = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

bool hasPosition(const Mesh& m, const vec3& p, std::size_t* at = nullptr) {
  for (std::size_t i = 0; i < m.vertexCount(); ++i) {
    if (glm::length(m.positions[i] - p) < 1e-6f) {
      if (at) *at = i;
      return true;
    }
  }
  return false;
}

}  // namespace

TEST(LoadMesh, ObjQuadWithNormalsIsTriangulated) {
  const fs::path path = writeFile("quad.obj",
                                  "# unit quad facing +Z\n"
                                  "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
                                  "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                  "vn 0 0 1\n"
                                  "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  ::testing::internal::CaptureStderr();
  const Mesh m = loadMesh(path);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << "normals were present: no warning";
  EXPECT_EQ(m.triangleCount(), 2u);
  EXPECT_EQ(m.vertexCount(), 4u) << "identical corners are joined";
  EXPECT_NEAR(surfaceArea(m), 2.0, 1e-6);
  for (const vec3& p : {vec3(0, 0, 0), vec3(2, 0, 0), vec3(2, 1, 0), vec3(0, 1, 0)}) EXPECT_TRUE(hasPosition(m, p));
  for (const vec3& n : m.normals) EXPECT_EQ(n, vec3(0, 0, 1));
  ASSERT_EQ(m.uvs.size(), 4u);
  std::size_t i = 0;
  ASSERT_TRUE(hasPosition(m, vec3(2, 1, 0), &i));
  EXPECT_EQ(m.uvs[i], vec2(1, 1)) << "v stays up (no flip)";
  expectFrontFacesAgreeWithNormals(m);
}

TEST(LoadMesh, ObjWithoutNormalsGetsSmoothNormalsAndAWarning) {
  // Octahedron: every vertex touches four congruent faces symmetrically, so the
  // smooth normal is exactly the radial direction.
  const fs::path path = writeFile("octahedron.obj",
                                  "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                                  "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\n"
                                  "f 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n");
  ::testing::internal::CaptureStderr();
  const Mesh m = loadMesh(path);
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(log.find("warning:"), std::string::npos) << log;
  EXPECT_NE(log.find("no normals"), std::string::npos) << log;
  EXPECT_EQ(m.vertexCount(), 6u);
  EXPECT_EQ(m.triangleCount(), 8u);
  EXPECT_NEAR(signedVolume(m), 4.0 / 3.0, 1e-6);
  ASSERT_TRUE(m.hasNormals());
  for (std::size_t i = 0; i < m.vertexCount(); ++i) {
    EXPECT_GT(glm::dot(m.normals[i], m.positions[i]), 1.0f - 1e-6f) << "vertex " << i;
  }
  expectFrontFacesAgreeWithNormals(m);
}

TEST(LoadMesh, ObjCubeOfQuadsIsClosedAfterTriangulation) {
  const fs::path path = writeFile("cube.obj",
                                  "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                                  "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                                  "f 5 6 7 8\nf 2 1 4 3\nf 6 2 3 7\nf 1 5 8 4\nf 8 7 3 4\nf 1 2 6 5\n");
  ::testing::internal::CaptureStderr();
  const Mesh m = loadMesh(path);
  ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(m.triangleCount(), 12u);
  EXPECT_EQ(m.vertexCount(), 8u);
  EXPECT_NEAR(signedVolume(m), 8.0, 1e-5);
  const Topology topo = topology(m);
  EXPECT_TRUE(topo.closed) << topo.problem;
  for (std::size_t i = 0; i < m.vertexCount(); ++i) EXPECT_GT(glm::dot(m.normals[i], m.positions[i]), 0.0f);
}

TEST(LoadMesh, AsciiPlyWithNormals) {
  // A unit square in the XZ plane facing +Y, as one quad, with per-vertex normals.
  const fs::path path = writeFile("square.ply",
                                  "ply\nformat ascii 1.0\n"
                                  "element vertex 4\n"
                                  "property float x\nproperty float y\nproperty float z\n"
                                  "property float nx\nproperty float ny\nproperty float nz\n"
                                  "element face 1\nproperty list uchar int vertex_indices\n"
                                  "end_header\n"
                                  "0 0 0 0 1 0\n0 0 1 0 1 0\n1 0 1 0 1 0\n1 0 0 0 1 0\n"
                                  "4 0 1 2 3\n");
  const Mesh m = loadMesh(path);
  EXPECT_EQ(m.vertexCount(), 4u);
  EXPECT_EQ(m.triangleCount(), 2u);
  EXPECT_FALSE(m.hasUvs());
  EXPECT_EQ(m.bounds().min, vec3(0, 0, 0));
  EXPECT_EQ(m.bounds().max, vec3(1, 0, 1));
  for (const vec3& n : m.normals) EXPECT_EQ(n, vec3(0, 1, 0));
  for (std::size_t t = 0; t < m.triangleCount(); ++t) EXPECT_GT(faceCross(m, t).y, 0.0);
}

TEST(LoadMesh, GltfNodeTransformsAreBakedIn) {
  // One triangle with normal (1, 0, 1)/√2, instanced by two nodes: one under a
  // parent scaled (2, 1, 1) and translated (0, 5, 0) itself, one untransformed.
  // Under the scale the normal becomes diag(1/2, 1, 1)·n ∝ (1, 0, 2).
  const float data[18] = {0, 0, 0, 1, 0, -1, 0, 1, 0,  // positions
                          0.70710678f, 0, 0.70710678f, 0.70710678f, 0, 0.70710678f, 0.70710678f, 0, 0.70710678f};
  std::vector<unsigned char> bytes(sizeof data);
  std::memcpy(bytes.data(), data, sizeof data);
  const std::string gltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,2]}],
    "nodes":[{"scale":[2,1,1],"children":[1]},{"translation":[0,5,0],"mesh":0},{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}}]}],
    "buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)" +
                           base64(bytes) + R"("}],
    "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":36}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[1,1,0]},
                 {"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"}]})";
  const Mesh m = loadMesh(writeFile("instanced.gltf", gltf));
  ASSERT_EQ(m.triangleCount(), 2u);
  ASSERT_EQ(m.vertexCount(), 6u);
  const vec3 scaledNormal = glm::normalize(vec3(1, 0, 2)), plainNormal = glm::normalize(vec3(1, 0, 1));
  for (const vec3& p : {vec3(0, 5, 0), vec3(2, 5, -1), vec3(0, 6, 0)}) {
    std::size_t i = 0;
    ASSERT_TRUE(hasPosition(m, p, &i)) << p.x << " " << p.y << " " << p.z;
    EXPECT_GT(glm::dot(m.normals[i], scaledNormal), 1.0f - 1e-6f);
  }
  for (const vec3& p : {vec3(0, 0, 0), vec3(1, 0, -1), vec3(0, 1, 0)}) {
    std::size_t i = 0;
    ASSERT_TRUE(hasPosition(m, p, &i)) << p.x << " " << p.y << " " << p.z;
    EXPECT_GT(glm::dot(m.normals[i], plainNormal), 1.0f - 1e-6f);
  }
  expectFrontFacesAgreeWithNormals(m);
}

TEST(LoadMesh, PointsAndLinesAreDropped) {
  const fs::path path = writeFile("mixed.obj",
                                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nvn 0 0 1\n"
                                  "f 1//1 2//1 3//1\nl 1 4\np 4\n");
  const Mesh m = loadMesh(path);
  EXPECT_EQ(m.triangleCount(), 1u);
  EXPECT_EQ(m.vertexCount(), 3u);
  EXPECT_FALSE(hasPosition(m, vec3(5, 5, 5)));
}

TEST(LoadMesh, FileWithoutTrianglesIsAnInputError) {
  const fs::path path = writeFile("wire.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\np 1\n");
  const Error e = captureError([&] { loadMesh(path); });
  EXPECT_EQ(e.kind(), ErrorKind::Input);
  EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("no triangles"), std::string::npos) << e.what();
}

TEST(LoadMesh, MissingFileIsAnInputError) {
  const fs::path path = outDir() / "does-not-exist.obj";
  const Error e = captureError([&] { loadMesh(path); });
  EXPECT_EQ(e.kind(), ErrorKind::Input);
  EXPECT_EQ(std::string(e.what()), "cannot read '" + path.string() + "': no such file");
}

TEST(LoadMesh, CorruptFileIsAOneLineInputErrorWithAssimpsReason) {
  // ASCII STL cut off in the middle of a vertex line.
  const fs::path path = writeFile("truncated.stl", "solid broken\nfacet normal 0 0 1\n outer loop\n  vertex 0 0\n");
  const Error e = captureError([&] { loadMesh(path); });
  EXPECT_EQ(e.kind(), ErrorKind::Input);
  const std::string msg = e.what();
  const std::string prefix = "cannot read mesh '" + path.string() + "': ";
  EXPECT_EQ(msg.rfind(prefix, 0), 0u) << msg;
  EXPECT_GT(msg.size(), prefix.size()) << "Assimp's reason follows";
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(LoadMesh, TruncatedPlyIsRejectedInsteadOfCrashing) {
  // The header promises three vertices and a face; the body stops early. Assimp
  // accepts this with an empty face, which would abort() in its Triangulate step.
  const fs::path path = writeFile("truncated.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 3\n"
                                  "property float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                  "0 0\n");
  const Error e = captureError([&] { loadMesh(path); });
  EXPECT_EQ(e.kind(), ErrorKind::Input);
  const std::string msg = e.what();
  EXPECT_EQ(msg.rfind("cannot read mesh '" + path.string() + "': ", 0), 0u) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(LoadMesh, DamagedPlyLayoutsAreOneLineErrors) {
  // Each of these passes Draco's own header parser, which then reads past the end of the
  // file or reserves memory the file cannot fill; the layout check refuses them first.
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                             "property float x\nproperty float y\nproperty float z\n";
  const std::string face = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string ascii = "ply\nformat ascii 1.0\n" + header.substr(header.find("element")) + face;
  const std::string vertices(36, '\0');
  const std::string triangle = std::string("\x03", 1) + std::string("\0\0\0\0\1\0\0\0\2\0\0\0", 12);
  const struct {
    const char* name;
    std::string text;
    const char* reason;
  } cases[] = {
      {"vertices past the end", header + face + vertices.substr(0, 20), "ends inside its binary element 'vertex'"},
      {"a list longer than the file", header + face + vertices + "\xff" + triangle.substr(1), "ends inside"},
      {"a huge element count", "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n0\n",
       "count the file cannot hold"},
      {"an element without properties", "ply\nformat ascii 1.0\nelement pad 5\n" + header.substr(header.find("element")) + face + "0",
       "no properties"},
      {"a tab in the header", "ply\nformat ascii 1.0\nelement\tvertex 3\nend_header\n", "control character"},
      {"a vertical tab in the header", "ply\nformat ascii 1.0\nelement v\v99999999999 vertex 3\nend_header\n",
       "control character"},
      {"a list in the vertex element", "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\nend_header\n1 0\n",
       "list property outside the face element"},
      {"no end_header", header + face.substr(0, face.size() - 11), "no end_header"},
      {"an element declared twice", header + header.substr(header.find("element")) + face + vertices + vertices + triangle,
       "declared twice"},
      {"a negative list length", header + "element face 1\nproperty list char int vertex_indices\nend_header\n" + vertices +
           "\xff" + triangle.substr(1), "negative list length"},
      {"faces without vertex indices", header + "element face 1\nproperty list uchar int corners\nend_header\n" + vertices +
           triangle, "no face element with a vertex_indices list"},
      {"a big-endian file without a vertex element",
       "ply\nformat binary_big_endian 1.0\nelement point 3\nproperty float x\nproperty float y\nproperty float z\n" + face +
           vertices + triangle,
       "no vertex element with x, y and z"},
      {"a NUL inside an ASCII line", ascii + std::string("0 0 0\n1 0 0\n0 1 0\n3 0 1\0 2\n", 27), "control character"},
      {"two entries on one ASCII line", ascii + "0 0 0 1 0 0\n0 1 0\n3 0 1 2\n", "more values than its properties"},
      {"an ASCII list length that is not a count", ascii + "0 0 0\n1 0 0\n0 1 0\n3x 0 1 2\n", "not a count"},
  };
  for (const auto& c : cases) {
    const fs::path path = writeFile("damaged.ply", c.text);
    const Error e = captureError([&] { loadMesh(path); });
    EXPECT_EQ(e.kind(), ErrorKind::Input) << c.name;
    const std::string msg = e.what();
    EXPECT_NE(msg.find(c.reason), std::string::npos) << c.name << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << c.name << ": " << msg;
  }
  // The same layout, whole, loads: the check refuses only what is damaged.
  const Mesh m = loadMesh(writeFile("whole.ply", header + face + vertices + triangle));
  EXPECT_EQ(m.triangleCount(), 1u);
}

TEST(LoadMesh, DirectoryIsNotAMeshFile) {
  const Error e = captureError([&] { loadMesh(outDir()); });
  EXPECT_EQ(e.kind(), ErrorKind::Input);
}
