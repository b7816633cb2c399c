// Unit tests for glint/raytrace: ray queries checked against analytic answers
// (a plane, a sphere whose vertices lie exactly on the sphere), the batched
// calls against the single-ray calls, and bad input against one-line errors.
#include "glint/core/error.h"
#include "glint/mesh/mesh.h"
#include "glint/raytrace/raytracer.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

using namespace glint;
using glint::raytrace::Hit;
using glint::raytrace::Ray;
using glint::raytrace::Scene;

namespace {

vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  for (;;) {
    const vec3 v(g(rng), g(rng), g(rng));
    if (glm::length(v) > 1e-3f) return glm::normalize(v);
  }
}

/// Analytic ray/sphere (centre 0): smallest t ≥ 0, or -1.
double raySphere(const glm::dvec3& o, const glm::dvec3& d, double r) {
  const double a = glm::dot(d, d), b = 2.0 * glm::dot(o, d), c = glm::dot(o, o) - r * r;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return -1.0;
  const double s = std::sqrt(disc);
  const double t0 = (-b - s) / (2.0 * a), t1 = (-b + s) / (2.0 * a);
  return t0 >= 0.0 ? t0 : (t1 >= 0.0 ? t1 : -1.0);
}

}  // namespace

TEST(Raytrace, PlaneHitIsExact) {
  const Mesh plane = makePlane(4.0f);  // XZ square of side 4, normal +Y
  const Scene scene(plane);
  EXPECT_EQ(scene.triangleCount(), 2u);
  EXPECT_EQ(scene.meshCount(), 1u);

  for (float x : {-1.5f, -0.25f, 0.3f, 1.9f}) {
    for (float z : {-1.7f, 0.1f, 1.2f}) {
      const Ray down{.origin = {x, 3.0f, z}, .direction = {0.0f, -1.0f, 0.0f}};
      const auto hit = scene.intersect(down);
      ASSERT_TRUE(hit);
      EXPECT_NEAR(hit->t, 3.0f, 1e-6f);
      EXPECT_NEAR(hit->geometricNormal.y, 1.0f, 1e-6f);  // front face seen from above
      // Barycentrics reproduce the hit point.
      const vec3 p = raytrace::interpolate(*hit, plane.positions, plane.indices);
      EXPECT_NEAR(p.x, x, 1e-5f);
      EXPECT_NEAR(p.y, 0.0f, 1e-6f);
      EXPECT_NEAR(p.z, z, 1e-5f);
      // The UVs interpolate linearly over the square: u = (x + 2) / 4.
      const vec2 uv = raytrace::interpolate(*hit, plane.uvs, plane.indices);
      EXPECT_NEAR(uv.x, (x + 2.0f) / 4.0f, 1e-5f);

      // From below: the same face, seen from its back (normal not flipped).
      const Ray up{.origin = {x, -2.0f, z}, .direction = {0.0f, 2.0f, 0.0f}};
      const auto back = scene.intersect(up);
      ASSERT_TRUE(back);
      EXPECT_NEAR(back->t, 1.0f, 1e-6f);  // t in units of |direction| = 2
      EXPECT_GT(glm::dot(back->geometricNormal, up.direction), 0.0f);
    }
  }
  // Outside the square and parallel rays miss.
  EXPECT_FALSE(scene.intersect({.origin = {2.5f, 1.0f, 0.0f}, .direction = {0.0f, -1.0f, 0.0f}}));
  EXPECT_FALSE(scene.intersect({.origin = {0.0f, 1.0f, 0.0f}, .direction = {1.0f, 0.0f, 0.0f}}));
}

TEST(Raytrace, IntervalIsRespected) {
  const Scene scene(makePlane(4.0f));
  const Ray base{.origin = {0.2f, 1.0f, 0.3f}, .direction = {0.0f, -1.0f, 0.0f}};
  Ray r = base;
  r.tfar = 0.999f;
  EXPECT_FALSE(scene.intersect(r));
  EXPECT_FALSE(scene.occluded(r));
  r.tfar = 1.001f;
  EXPECT_TRUE(scene.intersect(r));
  EXPECT_TRUE(scene.occluded(r));
  r.tnear = 1.0005f;
  EXPECT_FALSE(scene.intersect(r));
  EXPECT_FALSE(scene.occluded(r));
  // Rays only go forward: pointing away, the plane is behind.
  EXPECT_FALSE(scene.intersect({.origin = {0.2f, 1.0f, 0.3f}, .direction = {0.0f, 1.0f, 0.0f}}));
  // A zero direction never hits.
  EXPECT_FALSE(scene.intersect({.origin = {0.2f, 1.0f, 0.3f}, .direction = {0.0f, 0.0f, 0.0f}}));
}

TEST(Raytrace, SphereMatchesAnalyticIntersection) {
  // Icosphere vertices lie exactly on the sphere; a flat face sits inside it by at most
  // r - sqrt(r² - R²) ≈ R²/2r, R its circumradius (≤ e/√3 for its acute triangles, edge e).
  const float radius = 1.5f;
  const Mesh sphere = makeIcosphere(radius, 5);
  double longestEdge = 0.0;
  for (std::size_t i = 0; i < sphere.indices.size(); i += 3) {
    for (int k = 0; k < 3; ++k) {
      const vec3 a = sphere.positions[sphere.indices[i + std::size_t(k)]];
      const vec3 b = sphere.positions[sphere.indices[i + std::size_t((k + 1) % 3)]];
      longestEdge = std::max(longestEdge, double(glm::distance(a, b)));
    }
  }
  const double sagitta = longestEdge * longestEdge / (6.0 * radius) * 1.05;
  const Scene scene(sphere);

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int hits = 0, misses = 0;
  for (int i = 0; i < 2000; ++i) {
    // Origins outside at distance 3..6, directions toward a point inside the bounding box.
    const vec3 o = randomUnit(rng) * (3.0f + 3.0f * unit(rng));
    const vec3 target = (vec3(unit(rng), unit(rng), unit(rng)) * 2.0f - 1.0f) * radius;
    const vec3 d = glm::normalize(target - o);
    const double tExact = raySphere(glm::dvec3(o), glm::dvec3(d), radius);
    const auto hit = scene.intersect({.origin = o, .direction = d});
    // Near-grazing rays may legitimately miss the polyhedron; skip the ambiguous band.
    const glm::dvec3 closest = glm::dvec3(o) + glm::dot(-glm::dvec3(o), glm::dvec3(d)) * glm::dvec3(d);
    const double miss = glm::length(closest);
    if (miss > radius - 2 * sagitta && miss < radius + 1e-4) continue;
    if (tExact < 0.0) {
      EXPECT_FALSE(hit) << "ray " << i;
      ++misses;
      continue;
    }
    ASSERT_TRUE(hit) << "ray " << i;
    ++hits;
    // The mesh lies inside the sphere, within the sagitta of it: the hit point is in
    // that shell, and no earlier than the analytic hit.
    const vec3 p = o + hit->t * d;
    const vec3 nExact = glm::normalize(p);
    EXPECT_GE(hit->t, tExact - 1e-5);
    EXPECT_LE(glm::length(p), radius + 1e-5f);
    EXPECT_GE(glm::length(p), radius - sagitta);
    // Geometric normal faces outward (front face, toward the origin) and is close to radial;
    // the interpolated vertex normal is closer still.
    EXPECT_LT(glm::dot(hit->geometricNormal, d), 0.0f);
    EXPECT_GT(glm::dot(hit->geometricNormal, nExact), std::cos(glm::radians(4.0f)));
    const vec3 smooth = glm::normalize(raytrace::interpolate(*hit, sphere.normals, sphere.indices));
    EXPECT_GT(glm::dot(smooth, nExact), std::cos(glm::radians(1.0f)));
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 100);
}

TEST(Raytrace, RaysFromInsideHitBackFaces) {
  const Scene scene(makeIcosphere(1.0f, 4));
  std::mt19937 rng(3);
  for (int i = 0; i < 200; ++i) {
    const vec3 d = randomUnit(rng);
    const auto hit = scene.intersect({.origin = vec3(0.0f), .direction = d});
    ASSERT_TRUE(hit);
    EXPECT_GT(hit->t, 0.99f);
    EXPECT_LE(hit->t, 1.0f + 1e-6f);
    EXPECT_GT(glm::dot(hit->geometricNormal, d), 0.0f);
    // Occlusion: toward a light at distance 0.5 inside, nothing; at 2, the sphere.
    EXPECT_FALSE(scene.occluded({.origin = vec3(0.0f), .direction = d, .tfar = 0.5f}));
    EXPECT_TRUE(scene.occluded({.origin = vec3(0.0f), .direction = d, .tfar = 2.0f}));
  }
}

TEST(Raytrace, BatchesMatchSingleRays) {
  const Mesh torus = makeTorus(1.0f, 0.4f, 48, 24);
  const Scene scene(torus);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Ray> rays;
  for (int i = 0; i < 5000; ++i) {
    const vec3 o = randomUnit(rng) * 3.0f;
    const vec3 target(unit(rng) * 1.4f, unit(rng) * 0.4f, unit(rng) * 1.4f);
    rays.push_back({.origin = o, .direction = target - o, .tfar = i % 3 == 0 ? 0.8f : 100.0f});
  }
  const auto hits = scene.intersectBatch(rays);
  const auto blocked = scene.occludedBatch(rays);
  ASSERT_EQ(hits.size(), rays.size());
  int hitCount = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const auto single = scene.intersect(rays[i]);
    ASSERT_EQ(bool(single), bool(hits[i]));
    EXPECT_EQ(blocked[i], single ? 1 : 0);
    if (!single) continue;
    ++hitCount;
    EXPECT_EQ(single->t, hits[i]->t);
    EXPECT_EQ(single->triangle, hits[i]->triangle);
    // Hit point on the torus surface (within the tessellation error of ~0.01).
    const vec3 p = rays[i].at(single->t);
    const float ring = std::sqrt(p.x * p.x + p.z * p.z) - 1.0f;
    EXPECT_NEAR(std::sqrt(ring * ring + p.y * p.y), 0.4f, 0.01f);
  }
  EXPECT_GT(hitCount, 1000);

  // The coherent (stream) path gives the same answers, in groups of any size.
  std::vector<std::optional<Hit>> coherent(rays.size());
  scene.intersectCoherent(std::span(rays).first(100), std::span(coherent).first(100));
  scene.intersectCoherent(std::span(rays).subspan(100), std::span(coherent).subspan(100));
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(bool(coherent[i]), bool(hits[i]));
    if (hits[i]) {
      EXPECT_EQ(coherent[i]->triangle, hits[i]->triangle);
      EXPECT_NEAR(coherent[i]->t, hits[i]->t, 1e-5f * hits[i]->t);
    }
  }

  std::vector<std::optional<Hit>> tooFew(3);
  EXPECT_THROW(scene.intersectBatch(rays, tooFew), Error);
}

// shareMeshes reads positions and indices in place when the positions have room after the
// last vertex (Embree's 16-byte loads), copies them otherwise: same answers either way, and
// no Embree-owned copy of the shared buffers.
TEST(Raytrace, SharedMeshesGiveTheSameHits) {
  Mesh roomy = makeTorus(1.0f, 0.4f, 96, 48);
  roomy.positions.reserve(roomy.positions.size() + 1);
  Mesh tight = roomy;
  tight.positions.shrink_to_fit();
  ASSERT_EQ(tight.positions.capacity(), tight.positions.size());
  const Scene copied(roomy);
  const Scene shared(roomy, {.shareMeshes = true});
  const Scene fallback(tight, {.shareMeshes = true});
  // Embree no longer allocates the vertex and index buffers (its BVH is the same size).
  const std::size_t buffers = roomy.positions.size() * sizeof(vec3) + roomy.indices.size() * sizeof(std::uint32_t);
  EXPECT_LE(shared.memoryBytes() + buffers, copied.memoryBytes());
  EXPECT_LT(shared.memoryBytes(), fallback.memoryBytes());

  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int hitCount = 0;
  for (int i = 0; i < 3000; ++i) {
    const vec3 origin = randomUnit(rng) * 3.0f, target(unit(rng) * 1.4f, unit(rng) * 0.4f, unit(rng) * 1.4f);
    const Ray ray{.origin = origin, .direction = target - origin};
    const auto a = copied.intersect(ray), b = shared.intersect(ray), c = fallback.intersect(ray);
    ASSERT_EQ(bool(a), bool(b));
    ASSERT_EQ(bool(a), bool(c));
    if (!a) continue;
    ++hitCount;
    EXPECT_EQ(a->t, b->t);
    EXPECT_EQ(a->triangle, b->triangle);
    EXPECT_EQ(a->t, c->t);
    EXPECT_EQ(a->triangle, c->triangle);
  }
  EXPECT_GT(hitCount, 500);
}

TEST(Raytrace, ResultsDoNotDependOnThreadCount) {
  const Mesh sphere = makeUvSphere(1.0f, 96, 48);
  std::vector<Ray> rays;
  std::mt19937 rng(5);
  for (int i = 0; i < 4000; ++i) rays.push_back({.origin = randomUnit(rng) * 4.0f, .direction = -randomUnit(rng)});
  std::vector<std::optional<Hit>> one, many;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = Scene(sphere).intersectBatch(rays);
  }
  many = Scene(sphere).intersectBatch(rays);
  ASSERT_EQ(one.size(), many.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(bool(one[i]), bool(many[i]));
    if (!one[i]) continue;
    EXPECT_EQ(one[i]->t, many[i]->t);
    EXPECT_EQ(one[i]->triangle, many[i]->triangle);
    EXPECT_EQ(one[i]->u, many[i]->u);
  }
}

TEST(Raytrace, SeveralMeshesReportWhichOneWasHit) {
  Mesh lower = makePlane(2.0f);
  Mesh upper = makePlane(2.0f);
  upper.transform(glm::translate(mat4(1.0f), vec3(0.0f, 1.0f, 0.0f)));
  const std::vector<Mesh> meshes{lower, upper};
  Scene scene(meshes);
  EXPECT_EQ(scene.meshCount(), 2u);
  EXPECT_EQ(scene.triangleCount(), 4u);
  EXPECT_NEAR(scene.bounds().max.y, 1.0f, 1e-6f);
  const auto fromAbove = scene.intersect({.origin = {0.1f, 5.0f, 0.1f}, .direction = {0.0f, -1.0f, 0.0f}});
  ASSERT_TRUE(fromAbove);
  EXPECT_EQ(fromAbove->mesh, 1u);
  const auto fromBelow = scene.intersect({.origin = {0.1f, -5.0f, 0.1f}, .direction = {0.0f, 1.0f, 0.0f}});
  ASSERT_TRUE(fromBelow);
  EXPECT_EQ(fromBelow->mesh, 0u);
  EXPECT_GT(scene.memoryBytes(), 0u);

  Scene moved = std::move(scene);
  EXPECT_TRUE(moved.intersect({.origin = {0.1f, 5.0f, 0.1f}, .direction = {0.0f, -1.0f, 0.0f}}));
}

TEST(Raytrace, DegenerateAndNonFiniteTrianglesNeverHit) {
  Mesh mesh = makePlane(2.0f);  // triangles 0, 1
  const auto base = std::uint32_t(mesh.positions.size());
  // Triangle 2: zero area, on the ray's path. Triangle 3: a NaN corner.
  mesh.positions.push_back({0.0f, 0.5f, 0.0f});
  mesh.positions.push_back({0.0f, 0.5f, 0.0f});
  mesh.positions.push_back({0.0f, 0.5f, 0.0f});
  mesh.positions.push_back({-1.0f, 0.7f, -1.0f});
  mesh.positions.push_back({1.0f, 0.7f, -1.0f});
  mesh.positions.push_back({0.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f});
  for (std::uint32_t i = 0; i < 6; ++i) mesh.indices.push_back(base + i);
  mesh.normals.clear();
  mesh.uvs.clear();
  mesh.tangents.clear();
  const Scene scene(mesh);
  EXPECT_EQ(scene.triangleCount(), 4u);
  const auto hit = scene.intersect({.origin = {0.0f, 2.0f, 0.0f}, .direction = {0.0f, -1.0f, 0.0f}});
  ASSERT_TRUE(hit);
  EXPECT_LT(hit->triangle, 2u);
  EXPECT_NEAR(hit->t, 2.0f, 1e-6f);
}

TEST(Raytrace, BadMeshesAreInputErrors) {
  const auto expectInputError = [](auto&& build, const char* fragment) {
    try {
      build();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  expectInputError([] { Scene s{Mesh{}}; }, "no triangles");
  expectInputError([] { Scene s{std::span<const Mesh>{}}; }, "no meshes");
  expectInputError(
      [] {
        Mesh m = makePlane();
        m.indices.push_back(0);
        Scene s{m};
      },
      "multiple of 3");
  expectInputError(
      [] {
        Mesh m = makePlane();
        m.indices[4] = 99;
        Scene s{m};
      },
      "out of range");
  expectInputError(
      [] {
        const std::vector<Mesh> meshes{makePlane(), Mesh{}};
        Scene s{meshes};
      },
      "mesh 1");
}
