// The GPU bake's tracer (scenes/bake_tracer.h) on a headless context: the same hits as
// raytrace::traverse(), the same arithmetic on the CPU, and as Embree's own queries for at
// least 99.99 % of rays (the rest at edges, at the same distance).
#include "glint/bake/baker.h"
#include "glint/bake/samples.h"
#include "glint/core/log.h"
#include "glint/mesh/mesh.h"
#include "glint/raytrace/bvh.h"
#include "glint/raytrace/raytracer.h"
#include "glint/scenes/bake_tracer.h"

#include "support/gl_test.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

using namespace glint;
using glint::testing::GlTest;

TEST_F(GlTest, BakeTracerHitsWhatTheCpuTraversalAndEmbreeHit) {
  const Mesh mesh = makeTorus(1.0f, 0.35f, 96, 48);
  const raytrace::Bvh bvh = raytrace::buildBvh(mesh);
  const raytrace::Scene scene(mesh);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<raytrace::Ray> rays;
  for (int i = 0; i < 20000; ++i) {
    const vec3 origin = 2.5f * vec3(u(rng), u(rng), u(rng));
    rays.push_back({.origin = origin, .direction = 0.8f * vec3(u(rng), 0.3f * u(rng), u(rng)) - origin,
                    .tnear = 0.0f, .tfar = i % 3 == 0 ? 2.0f : std::numeric_limits<float>::infinity()});
  }
  scenes::BakeTracer tracer(bvh, {}, 4096);  // several batches
  for (const bool anyHit : {false, true}) {
    const std::vector<scenes::BakeHit> gpu = tracer.trace(rays, anyHit);
    ASSERT_EQ(gpu.size(), rays.size());
    int sameAsCpu = 0, sameAsEmbree = 0, hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const auto cpu = raytrace::traverse(bvh, rays[i], anyHit);
      ASSERT_EQ(gpu[i].hit(), cpu.has_value()) << "ray " << i;
      if (!cpu) continue;
      ++hits;
      if (gpu[i].triangle == cpu->triangle) ++sameAsCpu;
      EXPECT_NEAR(gpu[i].t, cpu->t, 1e-6f * std::max(1.0f, cpu->t)) << "ray " << i;
      if (anyHit) continue;
      const auto embree = scene.intersect(rays[i]);
      ASSERT_TRUE(embree) << "ray " << i;
      sameAsEmbree += embree->triangle == gpu[i].triangle ? 1 : 0;
    }
    EXPECT_GT(hits, 3000);
    if (!anyHit) {  // as Scene gives hits: the geometric normal too
      const auto adapted = tracer.intersect(rays);
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const auto embree = scene.intersect(rays[i]);
        ASSERT_EQ(adapted[i].has_value(), embree.has_value()) << "ray " << i;
        if (embree && embree->triangle == adapted[i]->triangle) {
          EXPECT_LT(glm::length(adapted[i]->geometricNormal - embree->geometricNormal), 1e-5f) << "ray " << i;
        }
      }
    }
    if (!anyHit) {
      EXPECT_EQ(sameAsCpu, hits) << "the GPU and the CPU traversal differ";
      EXPECT_GE(double(sameAsEmbree) / double(hits), 0.9999);
      std::printf("[figure] %zu rays, %d hits: %d the CPU traversal's triangle, %d Embree's\n", rays.size(), hits,
                  sameAsCpu, sameAsEmbree);
    }
  }
}

// The bake's own rays (a CPU bake's ray log: sweeps along the low poly's normals, and the
// short rays back from P), traced on the GPU and by Embree: the same triangle for ≥ 99.99 %
// of them, the rest (a ray through an edge or a vertex) at the same distance within 1e-5, or
// a hit at the very end of a ray's range that one of the two rounds past it.
TEST_F(GlTest, BakeTracerHitsWhatEmbreeHitsForTheBakesRays) {
  log::setLevel(log::Level::Error);
  const Mesh low = makeTorus(1.0f, 0.35f, 48, 12);
  const Mesh high = bake::makeStuddedTorus({.segments = 128, .sides = 64});
  bake::BakeOptions options;
  options.width = options.height = 192;
  options.samples = 4;
  options.progress = false;
  std::vector<raytrace::Ray> rays;
  options.rayLog = &rays;
  bake::bake(low, high, options);
  ASSERT_GT(rays.size(), 100000u);
  const raytrace::Scene scene(high);
  scenes::BakeTracer tracer(raytrace::buildBvh(high));
  const auto gpu = tracer.intersect(rays);
  std::size_t hits = 0, same = 0, onlyGpu = 0, onlyEmbree = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const auto embree = scene.intersect(rays[i]);
    if (gpu[i] && !embree) ++onlyGpu;  // slipped through an edge of Embree's (the bake retries those)
    if (!embree) continue;
    ++hits;
    if (!gpu[i]) {
      // Only at the ray's very end: the short ray back from P ends where the sweep hit, and the
      // two tests round that distance differently (the bake keeps the sweep's hit then).
      ++onlyEmbree;
      EXPECT_NEAR(embree->t, rays[i].tfar, 1e-5f * std::max(1e-3f, rays[i].tfar)) << "ray " << i << " missed inside its range";
    } else if (embree->triangle == gpu[i]->triangle) {
      ++same;
    } else {
      EXPECT_NEAR(embree->t, gpu[i]->t, 1e-5f * std::max(1.0f, embree->t)) << "ray " << i;
    }
  }
  std::printf("[figure] %zu rays of a 192² bake, %zu Embree hits: %zu the same triangle on the GPU, %zu missed by the "
              "GPU (at the ray's end); %zu rays that slipped through Embree's edges hit on the GPU\n",
              rays.size(), hits, same, onlyEmbree, onlyGpu);
  EXPECT_GE(double(same) / double(hits), 0.9999);
  EXPECT_LT(onlyEmbree, hits / 10000);
}
