// Unit tests for glint/mesh/tangents.h: MikkTSpace tangents checked against hand
// computations (a single triangle's dP/du, the angle-weighted average at a shared
// vertex), the analytic frames of the generators, the invariances MikkTSpace
// guarantees (triangle order, corner rotation, welding), mirrored UVs and the
// exact encode/decode pair the baker and the shader share.
#include "glint/core/error.h"
#include "glint/mesh/mesh.h"
#include "glint/mesh/tangents.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace glint;

namespace {

double angleDeg(const vec3& a, const vec3& b) {
  const double c = glm::dot(glm::normalize(glm::dvec3(a)), glm::normalize(glm::dvec3(b)));
  return glm::degrees(std::acos(std::clamp(c, -1.0, 1.0)));
}

/// dP/du of a triangle from the chain rule, solved in double (independent of the
/// implementation's formulation).
glm::dvec3 dpdu(const vec3& p0, const vec3& p1, const vec3& p2, const vec2& t0, const vec2& t1, const vec2& t2) {
  const glm::dvec3 e1 = glm::dvec3(p1 - p0), e2 = glm::dvec3(p2 - p0);
  const glm::dvec2 a = glm::dvec2(t1 - t0), b = glm::dvec2(t2 - t0);
  // [e1 e2] = [dPdu dPdv] [[a.x b.x], [a.y b.y]]  →  dPdu = (e1 b.y - e2 a.y) / det
  const double det = a.x * b.y - a.y * b.x;
  return (e1 * b.y - e2 * a.y) / det;
}

Mesh oneTriangle() {
  Mesh m;
  m.positions = {{0.0f, 0.0f, 0.0f}, {2.0f, 0.3f, 0.0f}, {0.4f, 1.5f, 0.0f}};
  m.normals.assign(3, vec3(0.0f, 0.0f, 1.0f));
  m.uvs = {{0.1f, 0.2f}, {0.9f, 0.35f}, {0.3f, 0.8f}};
  m.indices = {0, 1, 2};
  return m;
}

}  // namespace

TEST(Tangents, SingleTriangleIsDpDu) {
  const Mesh m = oneTriangle();
  const auto t = computeCornerTangents(m);
  ASSERT_EQ(t.size(), 3u);
  const glm::dvec3 expected = dpdu(m.positions[0], m.positions[1], m.positions[2], m.uvs[0], m.uvs[1], m.uvs[2]);
  for (const vec4& c : t) {
    EXPECT_LT(angleDeg(vec3(c), vec3(expected)), 1e-3);
    EXPECT_NEAR(glm::length(vec3(c)), 1.0f, 1e-6f);
    EXPECT_EQ(c.w, 1.0f);
  }
}

TEST(Tangents, GridGivesUAxisAndBitangentAlongV) {
  Mesh grid = makeGrid(4, 3, 2.0f);
  grid.tangents.clear();
  EXPECT_EQ(generateTangents(grid), 0u);  // nothing mirrored: no vertex split
  for (std::size_t i = 0; i < grid.vertexCount(); ++i) {
    EXPECT_NEAR(grid.tangents[i].x, 1.0f, 1e-6f);
    EXPECT_NEAR(grid.tangents[i].y, 0.0f, 1e-6f);
    EXPECT_NEAR(grid.tangents[i].z, 0.0f, 1e-6f);
    // v runs along -Z on this grid: the bitangent cross(n, t)·w must too.
    const vec3 b = grid.tangents[i].w * glm::cross(grid.normals[i], vec3(grid.tangents[i]));
    EXPECT_NEAR(b.z, -1.0f, 1e-6f);
  }
}

TEST(Tangents, SharedVertexAveragesByCornerAngle) {
  // Two triangles share vertex 0 and the edge 0-2; their UV mappings differ, so their
  // dP/du differ. At vertex 0 MikkTSpace weights each by the corner angle there.
  Mesh m;
  m.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.7f, 1.0f, 0.0f}, {-1.0f, 0.6f, 0.0f}};
  m.normals.assign(4, vec3(0.0f, 0.0f, 1.0f));
  m.uvs = {{0.0f, 0.0f}, {1.0f, 0.2f}, {0.5f, 1.0f}, {-1.0f, 0.9f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  const auto t = computeCornerTangents(m);
  const auto angleAt0 = [&](int a, int b) {
    return std::acos(glm::dot(glm::normalize(glm::dvec3(m.positions[std::size_t(a)])),
                              glm::normalize(glm::dvec3(m.positions[std::size_t(b)]))));
  };
  const glm::dvec3 d1 = glm::normalize(dpdu(m.positions[0], m.positions[1], m.positions[2], m.uvs[0], m.uvs[1], m.uvs[2]));
  const glm::dvec3 d2 = glm::normalize(dpdu(m.positions[0], m.positions[2], m.positions[3], m.uvs[0], m.uvs[2], m.uvs[3]));
  const glm::dvec3 expected = glm::normalize(angleAt0(1, 2) * d1 + angleAt0(2, 3) * d2);
  EXPECT_GT(angleDeg(vec3(d1), vec3(d2)), 5.0);  // the case is not trivial
  EXPECT_LT(angleDeg(vec3(t[0]), vec3(expected)), 1e-3);  // corner 0 of triangle 0
  EXPECT_LT(angleDeg(vec3(t[3]), vec3(expected)), 1e-3);  // corner 0 of triangle 1
  // Vertex 1 belongs to triangle 0 only.
  EXPECT_LT(angleDeg(vec3(t[1]), vec3(d1)), 1e-3);
}

TEST(Tangents, SphereAndTorusMatchAnalyticFrames) {
  for (Mesh mesh : {makeUvSphere(1.0f, 48, 24), makeTorus(1.0f, 0.35f, 48, 24)}) {
    const std::vector<vec4> analytic = mesh.tangents;
    const auto corners = computeCornerTangents(mesh);
    double worst = 0.0, sum = 0.0;
    std::size_t counted = 0;
    for (std::size_t c = 0; c < corners.size(); ++c) {
      const std::uint32_t v = mesh.indices[c];
      const vec3 n = mesh.normals[v];
      EXPECT_NEAR(glm::length(vec3(corners[c])), 1.0f, 1e-5f);
      EXPECT_NEAR(glm::dot(vec3(corners[c]), n), 0.0f, 1e-5f);  // in the tangent plane
      EXPECT_EQ(corners[c].w, analytic[v].w);
      if (std::abs(n.y) > 0.999f) continue;  // poles: dP/du degenerates, the frame is a convention
      const double a = angleDeg(vec3(corners[c]), vec3(analytic[v]));
      worst = std::max(worst, a);
      sum += a;
      ++counted;
    }
    // Each triangle's dP/du is a chord, half a segment angle (7.5° / 2) off the analytic
    // tangent at its corners. Inside a UV island the chords on either side of a vertex
    // average out; at the u = 0/1 seam the vertices are not shared (different UVs) and
    // only one side counts, so the worst case is half a segment angle.
    EXPECT_LT(worst, 3.75 + 0.05);
    EXPECT_LT(sum / double(counted), 0.5);
  }
}

TEST(Tangents, InvariantUnderTriangleOrderCornerRotationAndWelding) {
  const Mesh base = makeTorus(1.0f, 0.4f, 16, 8);
  const auto reference = computeCornerTangents(base);

  // Reverse the triangle order and rotate each triangle's corners by one.
  Mesh shuffled = base;
  const std::size_t n = base.triangleCount();
  for (std::size_t t = 0; t < n; ++t) {
    const std::size_t src = 3 * (n - 1 - t);
    shuffled.indices[3 * t + 0] = base.indices[src + 1];
    shuffled.indices[3 * t + 1] = base.indices[src + 2];
    shuffled.indices[3 * t + 2] = base.indices[src + 0];
  }
  const auto permuted = computeCornerTangents(shuffled);
  for (std::size_t t = 0; t < n; ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const vec4 a = reference[3 * (n - 1 - t) + (k + 1) % 3];
      const vec4 b = permuted[3 * t + k];
      EXPECT_LT(glm::length(vec3(a) - vec3(b)), 1e-5f);
      EXPECT_EQ(a.w, b.w);
    }
  }

  // Unwelded: every corner its own vertex. MikkTSpace welds identical vertices first.
  Mesh split;
  split.positions.reserve(base.indices.size());
  for (std::uint32_t i : base.indices) {
    split.positions.push_back(base.positions[i]);
    split.normals.push_back(base.normals[i]);
    split.uvs.push_back(base.uvs[i]);
    split.indices.push_back(std::uint32_t(split.indices.size()));
  }
  const auto unwelded = computeCornerTangents(split);
  for (std::size_t c = 0; c < reference.size(); ++c) EXPECT_EQ(reference[c], unwelded[c]);
}

TEST(Tangents, MirroredUvsFlipTheSignAndSplitVertices) {
  // A grid whose right half has u mirrored (u = 1 - |2x|), a common layout for symmetric
  // models. The centre column of vertices is shared by both halves.
  Mesh grid = makeGrid(4, 2, 2.0f);
  grid.tangents.clear();
  for (std::size_t i = 0; i < grid.vertexCount(); ++i) grid.uvs[i].x = 1.0f - std::abs(grid.positions[i].x);
  const std::size_t before = grid.vertexCount();
  const std::size_t added = generateTangents(grid);
  EXPECT_EQ(added, 3u);  // the three centre vertices get a mirrored twin
  EXPECT_EQ(grid.vertexCount(), before + added);
  for (std::size_t c = 0; c < grid.indices.size(); ++c) {
    const std::uint32_t v = grid.indices[c];
    // Triangle centroid tells the half.
    const std::size_t t = c / 3;
    const float cx = (grid.positions[grid.indices[3 * t]].x + grid.positions[grid.indices[3 * t + 1]].x +
                      grid.positions[grid.indices[3 * t + 2]].x) / 3.0f;
    const vec3 expectedDpDu = cx < 0.0f ? vec3(1.0f, 0.0f, 0.0f) : vec3(-1.0f, 0.0f, 0.0f);
    EXPECT_LT(glm::length(vec3(grid.tangents[v]) - expectedDpDu), 1e-5f);
    EXPECT_EQ(grid.tangents[v].w, cx < 0.0f ? 1.0f : -1.0f);
    // In both halves the reconstructed bitangent follows dP/dv = -Z.
    const vec3 b = grid.tangents[v].w * glm::cross(grid.normals[v], vec3(grid.tangents[v]));
    EXPECT_NEAR(b.z, -1.0f, 1e-5f);
  }
  grid.validate();
}

TEST(Tangents, DegenerateTrianglesCopyTheirNeighbours) {
  Mesh m = oneTriangle();
  m.indices.insert(m.indices.end(), {0, 1, 1});  // two equal corners
  const auto t = computeCornerTangents(m);
  EXPECT_EQ(t[3], t[0]);
  EXPECT_EQ(t[4], t[1]);
  EXPECT_EQ(t[5], t[1]);
}

TEST(Tangents, ZeroUvAreaStillGivesAValidFrame) {
  Mesh m = oneTriangle();
  m.uvs.assign(3, vec2(0.5f));
  const auto t = computeCornerTangents(m);
  for (const vec4& c : t) {
    EXPECT_NEAR(glm::length(vec3(c)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(vec3(c), vec3(0.0f, 0.0f, 1.0f)), 0.0f, 1e-6f);
  }
}

TEST(Tangents, MissingAttributesAreInputErrors) {
  Mesh noUv = oneTriangle();
  noUv.uvs.clear();
  Mesh noNormals = oneTriangle();
  noNormals.normals.clear();
  for (const Mesh* m : {&noUv, &noNormals}) {
    try {
      computeCornerTangents(*m);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
    }
  }
}

TEST(TangentFrame, EncodeInvertsDecodeOnSkewedFrames) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    // An interpolated frame: neither unit nor orthogonal.
    const vec3 n = vec3(u(rng), u(rng), u(rng)) * 0.5f + vec3(0.0f, 0.0f, 1.0f);
    const vec4 t(vec3(1.0f, 0.0f, 0.0f) + 0.4f * vec3(u(rng), u(rng), u(rng)), u(rng) < 0.0f ? -1.0f : 1.0f);
    const TangentFrame frame = TangentFrame::fromInterpolated(n, t);
    const vec3 v = glm::normalize(vec3(u(rng), u(rng), u(rng)) + 0.2f * n);
    const vec3 m = frame.encode(v);
    EXPECT_NEAR(glm::length(m), 1.0f, 1e-5f);
    EXPECT_LT(glm::length(frame.decode(m) - v), 2e-5f);
  }
  // Orthonormal frame: encode is the transpose.
  const TangentFrame ortho = TangentFrame::fromInterpolated({0, 0, 1}, {1, 0, 0, 1});
  const vec3 v = glm::normalize(vec3(0.3f, -0.2f, 0.9f));
  EXPECT_LT(glm::length(ortho.encode(v) - v), 1e-6f);
  // Singular frame: the normal.
  const TangentFrame singular = TangentFrame::fromInterpolated({0, 0, 1}, {0, 0, 0, 1});
  EXPECT_EQ(singular.encode(v), vec3(0.0f, 0.0f, 1.0f));
}
