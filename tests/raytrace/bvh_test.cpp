// The GPU's hierarchy (raytrace/bvh.h) against Embree's own queries: the same triangle is
// hit for at least 99.99 % of rays (the rest at edges, where two triangles meet and either
// is right), at the same distance.
#include "glint/mesh/mesh.h"
#include "glint/raytrace/bvh.h"
#include "glint/raytrace/raytracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace glint;
using namespace glint::raytrace;

namespace {

/// Every node's box holds its children's boxes or its triangles; every triangle is in one leaf.
void expectWellFormed(const Bvh& bvh, std::size_t triangles) {
  ASSERT_FALSE(bvh.nodes.empty());
  std::vector<int> seen(triangles, 0);
  for (const BvhNode& n : bvh.nodes) {
    if (n.count == 0) {
      ASSERT_LT(n.first + 1, bvh.nodes.size());
      for (std::uint32_t c = n.first; c <= n.first + 1; ++c) {
        EXPECT_TRUE(glm::all(glm::lessThanEqual(n.lower, bvh.nodes[c].lower)));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(n.upper, bvh.nodes[c].upper)));
      }
      continue;
    }
    for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
      ++seen[bvh.ids[k]];
      for (const vec4& p : {bvh.triangles[k].a, bvh.triangles[k].b, bvh.triangles[k].c}) {
        EXPECT_TRUE(glm::all(glm::lessThanEqual(n.lower, vec3(p))));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(n.upper, vec3(p))));
      }
    }
  }
  for (std::size_t t = 0; t < triangles; ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t;
}

}  // namespace

TEST(Bvh, IsWellFormedAndHitsWhatEmbreeHits) {
  const Mesh mesh = makeTorus(1.0f, 0.35f, 96, 48);
  const Bvh bvh = buildBvh(mesh);
  expectWellFormed(bvh, mesh.triangleCount());
  EXPECT_LE(bvh.depth, 48);
  EXPECT_EQ(bvh.bytes(), bvh.nodes.size() * 32 + bvh.triangles.size() * 52);
  const Scene scene(mesh);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int rays = 0, same = 0, bothMiss = 0, differ = 0;
  for (int i = 0; i < 20000; ++i) {
    const vec3 origin = 2.5f * vec3(u(rng), u(rng), u(rng));
    const vec3 target = 0.8f * vec3(u(rng), u(rng) * 0.3f, u(rng));
    const Ray ray{.origin = origin, .direction = target - origin};
    const auto ours = traverse(bvh, ray), theirs = scene.intersect(ray);
    ++rays;
    if (!ours && !theirs) {
      ++bothMiss;
      continue;
    }
    if (ours && theirs && ours->triangle == theirs->triangle) {
      ++same;
      EXPECT_NEAR(ours->t, theirs->t, 1e-5f * std::max(1.0f, theirs->t));
      // Barycentrics of a grazing ray are ill-conditioned: Embree's differ by up to 1e-4.
      EXPECT_NEAR(ours->u, theirs->u, 1e-3f);
      EXPECT_NEAR(ours->v, theirs->v, 1e-3f);
      continue;
    }
    ++differ;  // at an edge: the same distance
    ASSERT_TRUE(ours && theirs) << "ray " << i << ": one hit and one miss";
    EXPECT_NEAR(ours->t, theirs->t, 1e-5f * std::max(1.0f, theirs->t)) << "ray " << i;
  }
  EXPECT_GE(double(same + bothMiss) / double(rays), 0.9999) << differ << " rays hit another triangle";
  EXPECT_GT(same, rays / 3);
  // Any hit: a hit whenever the closest query hits, none otherwise.
  for (int i = 0; i < 2000; ++i) {
    const Ray ray{.origin = 2.5f * vec3(u(rng), u(rng), u(rng)), .direction = vec3(u(rng), u(rng), u(rng))};
    EXPECT_EQ(traverse(bvh, ray, true).has_value(), traverse(bvh, ray).has_value()) << "ray " << i;
  }
}

TEST(Bvh, RaysThroughSharedVerticesAndEdgesNeverSlipThrough) {
  // A flat grid hit exactly at its vertices and along its edges, from above and at angles:
  // the watertight test hits one of the triangles that meet there, every time.
  const Mesh grid = makeGrid(8, 8, 4.0f);
  const Bvh bvh = buildBvh(grid);
  int misses = 0, rays = 0;
  for (int i = 1; i < 8; ++i)  // the inner vertices (a ray at the grid's rim may round to just outside it)
    for (int j = 1; j < 8; ++j)
      for (const vec3& d : {vec3(0, -1, 0), vec3(0.3f, -1, 0.1f), vec3(-0.7f, -1, 0.7f)}) {
        const vec3 p(-2.0f + 0.5f * float(i), 0.0f, -2.0f + 0.5f * float(j));
        const Ray ray{.origin = p - 3.0f * d, .direction = d};
        ++rays;
        misses += traverse(bvh, ray) ? 0 : 1;
      }
  EXPECT_EQ(misses, 0) << "of " << rays;
}

TEST(Bvh, EmptyAndDegenerateMeshesHitNothing) {
  const Mesh empty;
  EXPECT_FALSE(traverse(buildBvh(empty), {.origin = {0, 0, 1}, .direction = {0, 0, -1}}));
  Mesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.indices = {0, 1, 2};
  EXPECT_TRUE(buildBvh(flat).nodes.empty());
}
