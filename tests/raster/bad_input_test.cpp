// Bad input: degenerate, NaN/inf, behind-the-eye and enormous coordinates, misuse.
// Nothing may crash and nothing may be drawn except the correct clipped result.

#include "raster_test_util.h"

#include "glint/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using namespace glint;
using namespace glint::raster;
using namespace glint::raster::test;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kMax = std::numeric_limits<float>::max();

const vec4 kClear(0.25f, 0.5f, 0.75f, 1.0f);

Framebuffer freshFramebuffer(int w = 32, int h = 32) {
  Framebuffer fb(w, h, {.color = ColorFormat::Float32});
  fb.clear(kClear);
  return fb;
}

/// The framebuffer is exactly as freshFramebuffer left it.
void expectUntouched(const Framebuffer& fb) {
  for (int y = 0; y < fb.height(); ++y)
    for (int x = 0; x < fb.width(); ++x) {
      ASSERT_EQ(fb.overdraw(x, y), 0u) << x << ", " << y;
      ASSERT_EQ(fb.color(x, y), kClear) << x << ", " << y;
      ASSERT_EQ(fb.depth(x, y), 1.0f);
    }
}

bool sameBuffers(const Framebuffer& a, const Framebuffer& b) {
  return std::equal(a.colors().begin(), a.colors().end(), b.colors().begin()) &&
         std::equal(a.depths().begin(), a.depths().end(), b.depths().begin()) &&
         std::equal(a.overdraws().begin(), a.overdraws().end(), b.overdraws().begin());
}

}  // namespace

TEST(RasterBadInput, ZeroAreaTrianglesDrawNothing) {
  const std::vector<std::vector<Vertex>> cases = {
      {ndc(-0.5f, -0.5f), ndc(0.0f, 0.0f), ndc(0.5f, 0.5f)},     // collinear
      {ndc(-0.5f, -0.5f), ndc(-0.5f, -0.5f), ndc(0.5f, 0.2f)},   // repeated vertex
      {ndc(0.3f, 0.3f), ndc(0.3f, 0.3f), ndc(0.3f, 0.3f)},       // a point
      // A sliver 0.001 pixels high: snapped to 1/256 pixel it has exactly zero area.
      {ndc(-0.5f, 0.0f), ndc(0.0f, 0.001f / 16.0f), ndc(0.5f, 0.0f)},
  };
  for (const std::vector<Vertex>& tri : cases) {
    Framebuffer fb = freshFramebuffer();
    const DrawStats stats = drawTriangles(fb, State{.depthTest = true}, tri);
    EXPECT_EQ(stats.degenerate, 1u);
    EXPECT_EQ(stats.fragments, 0u);
    expectUntouched(fb);
  }
  // Through indices too.
  Framebuffer fb = freshFramebuffer();
  const std::vector<Vertex> v = {ndc(-1, -1), ndc(1, -1), ndc(0, 1)};
  const std::vector<std::uint32_t> indices = {0, 0, 1, 2, 2, 2};
  EXPECT_EQ(drawTriangles(fb, State{}, v, indices).degenerate, 2u);
  expectUntouched(fb);
}

TEST(RasterBadInput, NanAndInfinitePositionsAreDroppedWhole) {
  const std::vector<Vertex> good = {ndc(-0.8f, -0.8f, 0.1f), ndc(0.8f, -0.6f, 0.2f), ndc(0.1f, 0.9f, 0.3f)};
  Framebuffer reference = freshFramebuffer();
  drawTriangles(reference, State{.depthTest = true}, good);
  for (float bad : {kNaN, kInf, -kInf}) {
    for (int vertex = 0; vertex < 3; ++vertex) {
      for (int component = 0; component < 4; ++component) {
        std::vector<Vertex> v = good;
        v[std::size_t(vertex)].position[component] = bad;
        // Alone: nothing is drawn.
        Framebuffer fb = freshFramebuffer();
        const DrawStats stats = drawTriangles(fb, State{.depthTest = true}, v);
        EXPECT_EQ(stats.rejected, 1u);
        expectUntouched(fb);
        // Next to a good triangle: the good one is drawn exactly as if alone.
        v.insert(v.end(), good.begin(), good.end());
        Framebuffer mixed = freshFramebuffer();
        EXPECT_EQ(drawTriangles(mixed, State{.depthTest = true}, v).rejected, 1u);
        EXPECT_TRUE(sameBuffers(mixed, reference)) << "bad " << bad << " at vertex " << vertex << " component " << component;
      }
    }
  }
}

TEST(RasterBadInput, AllVerticesBehindTheEyeDrawNothing) {
  const std::vector<std::vector<Vertex>> cases = {
      // The visible triangle (x, y, z, 1) negated: the same projective points, but w < 0
      // puts them outside GL's clip volume -w <= x, y, z <= w.
      {vtx(vec4(0.8f, 0.8f, -0.1f, -1.0f)), vtx(vec4(-0.8f, 0.8f, -0.1f, -1.0f)), vtx(vec4(0.0f, -0.8f, -0.1f, -1.0f))},
      {vtx(vec4(1, 0, 0, 0)), vtx(vec4(0, 1, 0, 0)), vtx(vec4(-1, -1, 0, 0))},            // w = 0
      {vtx(vec4(0, 0, 0, 0)), vtx(vec4(0, 0, 0, 0)), vtx(vec4(0, 0, 0, 0))},              // all zero
      {vtx(vec4(0.1f, 0.2f, 0, -0.0f)), vtx(vec4(3, 1, -2, -5)), vtx(vec4(-7, 2, 1, -1e-20f))},  // mixed w <= 0
  };
  for (const std::vector<Vertex>& tri : cases) {
    Framebuffer fb = freshFramebuffer();
    const DrawStats stats = drawTriangles(fb, State{}, tri);
    EXPECT_EQ(stats.clippedAway, 1u);
    expectUntouched(fb);
  }
}

TEST(RasterBadInput, OneVertexAtWZeroIsClippedNotGarbage) {
  // A vertex at w = 0 is a point at infinity; the triangle's visible part is finite.
  const std::vector<Vertex> tri = {ndc(-0.5f, -0.5f), ndc(0.5f, -0.5f), vtx(vec4(0.0f, 1.0f, 0.0f, 0.0f))};
  Framebuffer fb = freshFramebuffer();
  const DrawStats stats = drawTriangles(fb, State{}, tri);
  EXPECT_EQ(stats.clipped, 1u);
  // The triangle runs from y = -0.5 upward to the point at infinity in direction +y:
  // every column with |x| < 0.5 is covered from row 8 (y_ndc = -0.5) to the top.
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const double cx = (x + 0.5) / 16 - 1, cy = (y + 0.5) / 16 - 1;
      const bool in = std::abs(cx) < 0.5 && cy > -0.5;
      ASSERT_EQ(fb.overdraw(x, y), in ? 1u : 0u) << x << ", " << y;
    }
}

TEST(RasterBadInput, EnormousCoordinatesAreClippedCorrectly) {
  const int S = 64;
  const float big = 1e30f;
  // Two triangles split along the diagonal y = x through (-1, -1) and (big, big): the upper
  // one owns pixels above the diagonal, the lower one the diagonal itself (it is the lower
  // triangle's left edge), so together every pixel is drawn exactly once.
  const std::vector<Vertex> upper = {ndc(-1, -1, 0.5f), ndc(big, big, 0.5f), ndc(-1, big, 0.5f)};
  const std::vector<Vertex> lower = {ndc(-1, -1, 0.5f), ndc(big, -1, 0.5f), ndc(big, big, 0.5f)};
  Framebuffer fb = freshFramebuffer(S, S);
  const DrawStats upperStats = drawTriangles(fb, State{.depthTest = true}, upper);
  EXPECT_EQ(upperStats.clipped, 1u);
  for (int y = 0; y < S; ++y)
    for (int x = 0; x < S; ++x) {
      ASSERT_EQ(fb.overdraw(x, y), y > x ? 1u : 0u) << x << ", " << y;
      if (y > x) { ASSERT_FLOAT_EQ(fb.depth(x, y), 0.75f); }
    }
  EXPECT_EQ(upperStats.fragments, std::size_t(S * (S - 1) / 2));
  drawTriangles(fb, State{.depthTest = true}, lower);
  EXPECT_EQ(countOverdraw(fb, 1), std::size_t(S * S));

  // Triangles around the whole viewport, up to FLT_MAX: everything covered once.
  for (float m : {1e30f, kMax}) {
    Framebuffer all = freshFramebuffer(S, S);
    drawTriangles(all, State{}, std::vector<Vertex>{ndc(-m, -m), ndc(m, -m), ndc(0, m)});
    EXPECT_EQ(countOverdraw(all, 1), std::size_t(S * S)) << m;
  }

  // Enormous z is beyond the far plane; enormous w shrinks the triangle to the centre.
  Framebuffer far = freshFramebuffer(S, S);
  EXPECT_EQ(drawTriangles(far, State{}, std::vector<Vertex>{ndc(-1, -1, big), ndc(1, -1, big), ndc(0, 1, big)}).clippedAway, 1u);
  expectUntouched(far);
  Framebuffer tiny = freshFramebuffer(S, S);
  const std::vector<Vertex> shrunk = {vtx(vec4(-1, -1, 0, big)), vtx(vec4(1, -1, 0, big)), vtx(vec4(0, 1, 0, big))};
  EXPECT_EQ(drawTriangles(tiny, State{}, shrunk).degenerate, 1u);
  expectUntouched(tiny);
}

TEST(RasterBadInput, MisuseThrowsBeforeDrawing) {
  const std::vector<Vertex> v = {ndc(-1, -1), ndc(1, -1), ndc(0, 1)};
  Framebuffer fb = freshFramebuffer();
  // Index out of range in the second triangle: the first one must not be drawn either.
  EXPECT_THROW(drawTriangles(fb, State{}, v, std::vector<std::uint32_t>{0, 1, 2, 0, 1, 3}), Error);
  // Different varying counts.
  std::vector<Vertex> mixed = v;
  mixed[2].varyings.push_back(vec4(1.0f));
  EXPECT_THROW(drawTriangles(fb, State{}, mixed), Error);
  // Too many varyings.
  std::vector<Vertex> many = v;
  for (Vertex& x : many) x.varyings.assign(kMaxVaryings + 1, vec4(0.5f));
  EXPECT_THROW(drawTriangles(fb, State{}, many), Error);
  expectUntouched(fb);
  // Nothing to draw is fine.
  EXPECT_EQ(drawTriangles(fb, State{}, std::vector<Vertex>{}).triangles, 0u);
  EXPECT_EQ(drawTriangles(fb, State{}, std::vector<Vertex>{ndc(0, 0), ndc(1, 0)}).triangles, 0u);
  expectUntouched(fb);
}
