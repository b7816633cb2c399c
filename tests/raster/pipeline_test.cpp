// drawTriangles end to end: the lecture's triangle, watertight meshes, clipping,
// perspective-correct interpolation, culling, stencil counting, depth scenes.

#include "raster_test_util.h"

#include "glint/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

using namespace glint;
using namespace glint::raster;
using namespace glint::raster::test;

namespace {

/// Pixel-centre NDC coordinate of pixel i in a viewport of `size` pixels starting at 0.
double centreNdc(int i, int size) { return (i + 0.5) / size * 2.0 - 1.0; }

/// Where the eye ray through a pixel centre meets the plane y = planeY (camera at the
/// origin looking down -z, symmetric perspective with tan(fovy/2) = tanHalf).
std::optional<dvec3> floorHit(int px, int py, int w, int h, double tanHalf, double planeY) {
  const double aspect = double(w) / h;
  const dvec3 dir(centreNdc(px, w) * tanHalf * aspect, centreNdc(py, h) * tanHalf, -1.0);
  if (dir.y * planeY <= 0.0) return std::nullopt;  // ray never reaches the plane
  return dir * (planeY / dir.y);
}

/// Is p strictly inside the convex CCW polygon by more than margin (in its own units)?
/// Returns +1 inside, -1 outside by more than margin, 0 when too close to decide.
int classify(const std::vector<dvec2>& polygon, dvec2 p, double margin) {
  bool inside = true;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const dvec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const double distance = signedArea2(a, b, p) / glm::length(b - a);  // > 0 on the inner side
    if (distance < -margin) return -1;
    if (distance <= margin) inside = false;
  }
  return inside ? 1 : 0;
}

}  // namespace

// ---------------------------------------------------------------------------------
// The simple triangle of the lecture, end to end
// ---------------------------------------------------------------------------------

TEST(RasterPipeline, LectureTriangleCoverageDepthAndColour) {
  const vec4 red(1, 0, 0, 1), green(0, 1, 0, 1), blue(0, 0, 1, 1);
  const std::vector<Vertex> tri = {ndc(-0.8f, 0.8f, 0.3f, red), ndc(0.8f, 0.8f, -0.2f, green), ndc(0.0f, -0.8f, -0.2f, blue)};
  Framebuffer fb(500, 500, {.color = ColorFormat::Float32});
  const DrawStats stats = drawTriangles(fb, State{.depthTest = true}, tri);
  EXPECT_EQ(stats.triangles, 1u);
  EXPECT_EQ(stats.clipped, 0u);
  EXPECT_EQ(stats.written, stats.fragments);

  // Independent check in window space: vertices (50,450) red, (450,450) green, (250,50) blue.
  const dvec2 L(50, 450), M(450, 450), N(250, 50);
  const PlaneEquation z = *planeEquation(dvec3(50, 450, 0.65), dvec3(250, 50, 0.4), dvec3(450, 450, 0.4));
  std::size_t inside = 0;
  for (int y = 0; y < 500; ++y) {
    for (int x = 0; x < 500; ++x) {
      const dvec2 p(x + 0.5, y + 0.5);
      const dvec3 bary = *barycentric(L, M, N, p);
      // No pixel centre lies exactly on an edge of this triangle, so inside is strict.
      const bool in = bary.x > 0 && bary.y > 0 && bary.z > 0;
      inside += in;
      ASSERT_EQ(fb.overdraw(x, y), in ? 1u : 0u) << x << ", " << y;
      if (!in) continue;
      EXPECT_NEAR(fb.depth(x, y), z(p.x, p.y), 1e-6);
      const vec4 c = fb.color(x, y);
      EXPECT_NEAR(c.r, bary.x, 1e-5);
      EXPECT_NEAR(c.g, bary.y, 1e-5);
      EXPECT_NEAR(c.b, bary.z, 1e-5);
    }
  }
  EXPECT_EQ(stats.fragments, inside);
  // The slide's sample: (250, 250) is in, and its depth is the z plane at the pixel centre.
  EXPECT_EQ(fb.overdraw(250, 250), 1u);
  EXPECT_NEAR(fb.depth(250, 250), -0.000625 * 250.5 + 0.0003125 * 250.5 + 0.540625, 1e-6);
}

// ---------------------------------------------------------------------------------
// Viewport, depth range, near/far clipping of z
// ---------------------------------------------------------------------------------

TEST(RasterPipeline, ViewportSelectsThePixels) {
  struct Case {
    Viewport viewport;
    int x0, y0, x1, y1;  // expected covered pixels [x0, x1) × [y0, y1)
  };
  const Case cases[] = {{{10, 20, 30, 40}, 10, 20, 40, 60}, {{-10, -10, 30, 30}, 0, 0, 20, 20}, {{50, 50, 100, 100}, 50, 50, 64, 64},
                        {{5, 5, 0, 0}, 0, 0, 0, 0}};
  for (const Case& c : cases) {
    Framebuffer fb(64, 64);
    drawTriangles(fb, State{.viewport = c.viewport}, quad(-1, -1, 1, 1));
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const bool in = x >= c.x0 && x < c.x1 && y >= c.y0 && y < c.y1;
        ASSERT_EQ(fb.overdraw(x, y), in ? 1u : 0u) << x << ", " << y;
      }
  }
  // Unset viewport = the whole framebuffer.
  Framebuffer fb(17, 9);
  drawTriangles(fb, State{}, quad(-1, -1, 1, 1));
  EXPECT_EQ(countOverdraw(fb, 1), 17u * 9u);
  EXPECT_THROW(drawTriangles(fb, State{.viewport = Viewport{0, 0, -5, 5}}, quad(-1, -1, 1, 1)), Error);
}

TEST(RasterPipeline, DepthRangeMapsWindowZ) {
  Framebuffer fb(8, 8);
  const State state{.depthRange = {0.2, 0.6}, .depthTest = true, .depthFunc = CompareFunc::Always};
  drawTriangles(fb, state, quad(-1, -1, 1, 1, 0.0f));
  EXPECT_FLOAT_EQ(fb.depth(3, 3), 0.4f);
  drawTriangles(fb, State{.depthRange = {1.0, 0.0}, .depthTest = true, .depthFunc = CompareFunc::Always}, quad(-1, -1, 1, 1, 0.5f));
  EXPECT_FLOAT_EQ(fb.depth(3, 3), 0.25f);
}

TEST(RasterPipeline, FarPlaneClipsDepth) {
  Framebuffer fb(64, 8);
  // z goes from 0 at the left edge to 2 at the right: only x_ndc <= 0 survives the far plane.
  const std::vector<Vertex> tilted = {ndc(-1, -1, 0), ndc(1, -1, 2), ndc(1, 1, 2), ndc(-1, -1, 0), ndc(1, 1, 2), ndc(-1, 1, 0)};
  const DrawStats stats = drawTriangles(fb, State{.depthTest = true, .depthFunc = CompareFunc::Always}, tilted);
  EXPECT_EQ(stats.clipped, 2u);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 64; ++x) {
      ASSERT_EQ(fb.overdraw(x, y), x < 32 ? 1u : 0u) << x;
      if (x < 32) { EXPECT_NEAR(fb.depth(x, y), 0.5 + 0.5 * (1.0 + centreNdc(x, 64)), 1e-6); }
    }
  // Entirely beyond the far plane: nothing.
  Framebuffer empty(8, 8);
  EXPECT_EQ(drawTriangles(empty, State{}, quad(-1, -1, 1, 1, 1.5f)).clippedAway, 2u);
  EXPECT_EQ(countOverdraw(empty, 0), 64u);
}

// ---------------------------------------------------------------------------------
// Watertight meshes: shared edges drawn exactly once
// ---------------------------------------------------------------------------------

namespace {

/// Clip-space vertex for NDC (x, y) with a random positive w (same window position).
Vertex perspectiveVertex(double x, double y, double w) { return vtx(vec4(float(x * w), float(y * w), 0.0f, float(w))); }

void expectEveryPixelOnce(const Framebuffer& fb, const std::string& what) {
  for (int y = 0; y < fb.height(); ++y)
    for (int x = 0; x < fb.width(); ++x) ASSERT_EQ(fb.overdraw(x, y), 1u) << what << " at pixel " << x << ", " << y;
}

}  // namespace

TEST(RasterWatertight, FanTilingTheViewportDrawsEveryPixelOnce) {
  const int W = 97, H = 61;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> inner(-0.9, 0.9), along(-1.0, 1.0), wDist(0.5, 3.0);
    const bool onCentres = seed % 2 == 0;  // even seeds: every vertex on a pixel centre (ties everywhere)
    auto place = [&](double x, double y) {
      if (onCentres) {  // snap to the nearest pixel centre, keeping the boundary on ±1
        if (std::abs(x) != 1.0) x = centreNdc(std::clamp(int(std::floor((x + 1) / 2 * W)), 0, W - 1), W);
        if (std::abs(y) != 1.0) y = centreNdc(std::clamp(int(std::floor((y + 1) / 2 * H)), 0, H - 1), H);
      }
      return dvec2(x, y);
    };
    // Rim: points along the square's boundary in counter-clockwise order, corners included.
    std::vector<dvec2> rim;
    const dvec2 corners[] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int side = 0; side < 4; ++side) {
      const dvec2 a = corners[side], b = corners[(side + 1) % 4];
      std::vector<double> ts = {0.0};
      for (int k = 0; k < 5; ++k) ts.push_back((along(rng) + 1) / 2);
      std::sort(ts.begin(), ts.end());
      for (double t : ts) rim.push_back(place(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)));
    }
    const dvec2 centre = place(inner(rng), inner(rng));
    std::vector<Vertex> vertices = {perspectiveVertex(centre.x, centre.y, wDist(rng))};
    for (const dvec2& p : rim) vertices.push_back(perspectiveVertex(p.x, p.y, wDist(rng)));
    std::vector<std::uint32_t> indices;
    for (std::uint32_t i = 0; i < rim.size(); ++i) {
      const std::uint32_t a = 1 + i, b = 1 + (i + 1) % std::uint32_t(rim.size());
      if (rng() % 2) indices.insert(indices.end(), {0, a, b});
      else indices.insert(indices.end(), {0, b, a});  // some clockwise: winding must not matter
    }
    Framebuffer fb(W, H);
    const DrawStats stats = drawTriangles(fb, State{}, vertices, indices);
    EXPECT_EQ(stats.fragments, std::size_t(W * H));
    expectEveryPixelOnce(fb, "fan seed " + std::to_string(seed));
  }
}

TEST(RasterWatertight, PerturbedGridTilingTheViewportDrawsEveryPixelOnce) {
  const int W = 128, H = 96, cellsX = 13, cellsY = 9;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed * 7919u);
    // ±0.2 of a cell keeps every cell convex, so either diagonal splits it into two triangles.
    std::uniform_real_distribution<double> jitter(-0.2, 0.2), wDist(0.25, 4.0);
    const bool onCentres = seed % 2 == 0;
    std::vector<Vertex> vertices;
    for (int j = 0; j <= cellsY; ++j) {
      for (int i = 0; i <= cellsX; ++i) {
        // Interior vertices move within their cell; boundary ones slide along the boundary.
        double x = -1.0 + 2.0 * (i + (i > 0 && i < cellsX ? jitter(rng) : 0.0)) / cellsX;
        double y = -1.0 + 2.0 * (j + (j > 0 && j < cellsY ? jitter(rng) : 0.0)) / cellsY;
        if (onCentres) {
          if (i > 0 && i < cellsX) x = centreNdc(int(std::floor((x + 1) / 2 * W)), W);
          if (j > 0 && j < cellsY) y = centreNdc(int(std::floor((y + 1) / 2 * H)), H);
        }
        vertices.push_back(perspectiveVertex(x, y, wDist(rng)));
      }
    }
    std::vector<std::uint32_t> indices;
    auto at = [&](int i, int j) { return std::uint32_t(j * (cellsX + 1) + i); };
    for (int j = 0; j < cellsY; ++j)
      for (int i = 0; i < cellsX; ++i) {
        const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
        if (rng() % 2) indices.insert(indices.end(), {a, b, c, a, c, d});
        else indices.insert(indices.end(), {a, b, d, b, c, d});
      }
    // Draw the triangles in a random order.
    std::vector<std::size_t> order(indices.size() / 3);
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<std::uint32_t> shuffled;
    for (std::size_t k : order) shuffled.insert(shuffled.end(), indices.begin() + std::ptrdiff_t(3 * k), indices.begin() + std::ptrdiff_t(3 * k + 3));
    Framebuffer fb(W, H);
    drawTriangles(fb, State{}, vertices, shuffled);
    expectEveryPixelOnce(fb, "grid seed " + std::to_string(seed));
  }
}

TEST(RasterWatertight, GroundGridCrossingTheNearPlane) {
  // A 20×20 grid on the floor y = -1 from z = +40 (behind the eye) to z = -40.
  const int W = 160, H = 120, cells = 20;
  const double extent = 40.0, tanHalf = std::tan(glm::radians(30.0));
  const mat4 projection = glm::perspective(glm::radians(60.0f), float(W) / H, 0.1f, 100.0f);
  std::vector<Vertex> vertices;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const vec4 eye(float(-extent + 2 * extent * i / cells), -1.0f, float(extent - 2 * extent * j / cells), 1.0f);
      vertices.push_back(vtx(projection * eye));
    }
  std::vector<std::uint32_t> indices;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const auto a = std::uint32_t(j * (cells + 1) + i), b = a + 1, c = a + cells + 2, d = a + cells + 1;
      indices.insert(indices.end(), {a, b, c, a, c, d});
    }
  Framebuffer fb(W, H);
  const DrawStats stats = drawTriangles(fb, State{}, vertices, indices);
  EXPECT_GT(stats.clipped, 0u);
  EXPECT_GT(stats.clippedAway, 0u);
  std::size_t checked = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      ASSERT_LE(fb.overdraw(x, y), 1u) << x << ", " << y;
      const std::optional<dvec3> hit = floorHit(x, y, W, H, tanHalf, -1.0);
      const bool clearlyIn = hit && std::abs(hit->x) < extent - 0.5 && hit->z > -extent + 0.5;
      const bool clearlyOut = !hit || std::abs(hit->x) > extent + 0.5 || hit->z < -extent - 0.5;
      if (clearlyIn) { ASSERT_EQ(fb.overdraw(x, y), 1u) << "gap at " << x << ", " << y; }
      if (clearlyOut) { ASSERT_EQ(fb.overdraw(x, y), 0u) << "spill at " << x << ", " << y; }
      checked += clearlyIn || clearlyOut;
    }
  EXPECT_GT(checked, std::size_t(W * H * 9 / 10));
}

// ---------------------------------------------------------------------------------
// Perspective-correct interpolation and near-plane clipping against analytic answers
// ---------------------------------------------------------------------------------

TEST(RasterInterpolation, PerspectiveCorrectVaryingsDepthAndFragCoordW) {
  const int W = 256, H = 256;
  const double n = 0.5, f = 50.0, tanHalf = std::tan(glm::radians(30.0));
  const mat4 projection = glm::perspective(glm::radians(60.0f), 1.0f, float(n), float(f));
  // Floor quad y = -1, x in [-1, 1], z in [-2, -6]; varying 0 = (x, z) of the surface point.
  const dvec2 corners[] = {{-1, -2}, {1, -2}, {1, -6}, {-1, -6}};
  std::vector<Vertex> vertices;
  for (const dvec2& c : corners)
    vertices.push_back(vtx(projection * vec4(float(c.x), -1.0f, float(c.y), 1.0f), vec4(float(c.x), float(c.y), 0, 1)));
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  Framebuffer fb(W, H, {.color = ColorFormat::Float32});
  const FragmentShader shader = [](const Fragment& frag) {
    return std::optional<vec4>(vec4(frag.varyings[0].x, frag.varyings[0].y, frag.fragCoord.w, 1.0f));
  };
  drawTriangles(fb, State{.depthTest = true}, vertices, indices, shader);

  // Screen-linear (affine) interpolation over the window-space triangles, for contrast.
  std::vector<dvec3> window;
  for (const Vertex& v : vertices) window.push_back(clipToWindow(dvec4(v.position), Viewport{0, 0, W, H}));
  double maxError = 0.0, maxAffineError = 0.0;
  std::size_t checked = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::optional<dvec3> hit = floorHit(x, y, W, H, tanHalf, -1.0);
      if (!hit || std::abs(hit->x) > 0.95 || hit->z > -2.05 || hit->z < -5.95) continue;  // clearly inside only
      ++checked;
      ASSERT_EQ(fb.overdraw(x, y), 1u);
      const vec4 c = fb.color(x, y);
      maxError = std::max({maxError, std::abs(c.r - hit->x), std::abs(c.g - hit->z)});
      EXPECT_NEAR(c.b, 1.0 / -hit->z, 1e-4);  // gl_FragCoord.w = 1 / w_clip = 1 / -z_eye
      // Window z: NDC z = (f + n)/(f - n) + 2fn / ((f - n) z_eye), then z/2 + 1/2.
      const double zNdc = (f + n) / (f - n) + 2 * f * n / ((f - n) * hit->z);
      EXPECT_NEAR(fb.depth(x, y), 0.5 * zNdc + 0.5, 1e-5);
      // Which triangle holds the pixel: try both and keep the one with non-negative weights.
      const dvec2 p(x + 0.5, y + 0.5);
      for (const auto& t : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
        const dvec3 b = *barycentric(dvec2(window[std::size_t(t[0])]), dvec2(window[std::size_t(t[1])]), dvec2(window[std::size_t(t[2])]), p);
        if (b.x < 0 || b.y < 0 || b.z < 0) continue;
        double affineZ = 0;
        for (int i = 0; i < 3; ++i) affineZ += b[i] * corners[t[std::size_t(i)]].y;
        maxAffineError = std::max(maxAffineError, std::abs(affineZ - hit->z));
      }
    }
  EXPECT_GT(checked, 5000u);
  EXPECT_LT(maxError, 2e-3);
  EXPECT_GT(maxAffineError, 0.5);  // the test would catch missing perspective correction
}

TEST(RasterClipping, TriangleCrossingTheNearPlaneMatchesTheAnalyticCoverage) {
  const int W = 128, H = 128;
  const mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, 0.5f, 100.0f);
  // Floor triangle with its apex behind the eye (z_eye = +2, so clip w = -2).
  const vec4 A(-1, -1, -3, 1), B(1, -1, -3, 1), C(0, -1, 2, 1);
  const std::vector<Vertex> tri = {vtx(projection * A), vtx(projection * B), vtx(projection * C)};
  ASSERT_LT(tri[2].position.w, 0.0f);
  Framebuffer fb(W, H);
  const DrawStats stats = drawTriangles(fb, State{.depthTest = true}, tri);
  EXPECT_EQ(stats.clipped, 1u);

  // By hand, in eye space: AC and BC cross z = -0.5 at s = 0.5: (-0.5, -1, -0.5) and (0.5, -1, -0.5).
  // Project with x_win = (x / -z + 1)·64 (tan 45° = 1), same for y.
  auto project = [&](dvec3 e) { return dvec2((e.x / -e.z + 1) * W / 2, (e.y / -e.z + 1) * H / 2); };
  // Counter-clockwise in window space: A, Ac, Bc, B.
  const std::vector<dvec2> visible = {project({-1, -1, -3}), project({-0.5, -1, -0.5}), project({0.5, -1, -0.5}), project({1, -1, -3})};
  EXPECT_NEAR(visible[0].x, 128.0 / 3, 1e-12);
  EXPECT_NEAR(visible[2].y, -64.0, 1e-12);
  std::size_t inside = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const int side = classify(visible, dvec2(x + 0.5, y + 0.5), 0.01);
      if (side > 0) { ASSERT_EQ(fb.overdraw(x, y), 1u) << x << ", " << y; }
      if (side < 0) { ASSERT_EQ(fb.overdraw(x, y), 0u) << x << ", " << y; }
      inside += side > 0;
    }
  EXPECT_GT(inside, 2000u);
}

// ---------------------------------------------------------------------------------
// Facing and culling
// ---------------------------------------------------------------------------------

TEST(RasterCulling, FacingFollowsWindowWindingAndFrontFace) {
  const std::vector<Vertex> ccw = quad(-1, -1, 0, 1), cw = quadCw(0, -1, 1, 1);
  std::vector<Vertex> both = ccw;
  both.insert(both.end(), cw.begin(), cw.end());
  struct Case {
    State state;
    bool leftDrawn, rightDrawn;
  };
  const Case cases[] = {
      {State{}, true, true},
      {State{.cull = true}, true, false},  // cull back faces (CW)
      {State{.cull = true, .cullFace = Face::Front}, false, true},
      {State{.cull = true, .frontFace = Winding::Cw}, false, true},
      {State{.cull = true, .cullFace = Face::FrontAndBack}, false, false},
      {State{.cull = false, .cullFace = Face::FrontAndBack}, true, true},
  };
  for (const Case& c : cases) {
    Framebuffer fb(8, 4);
    const DrawStats stats = drawTriangles(fb, c.state, both);
    EXPECT_EQ(fb.overdraw(1, 1), c.leftDrawn ? 1u : 0u);
    EXPECT_EQ(fb.overdraw(6, 1), c.rightDrawn ? 1u : 0u);
    EXPECT_EQ(stats.culled, std::size_t(2 * (!c.leftDrawn + !c.rightDrawn)));
  }
  // gl_FrontFacing reaches the shader.
  Framebuffer fb(8, 4, {.color = ColorFormat::Float32});
  drawTriangles(fb, State{}, both, {}, [](const Fragment& frag) { return std::optional<vec4>(vec4(frag.frontFacing ? 1.0f : 0.5f)); });
  EXPECT_EQ(fb.color(1, 1).r, 1.0f);
  EXPECT_EQ(fb.color(6, 1).r, 0.5f);
}

// ---------------------------------------------------------------------------------
// Stencil counting as in shadow volumes, and the (ZERO, DST_ALPHA) shadow pass
// ---------------------------------------------------------------------------------

TEST(RasterStencilScene, TwoSidedCountingMatchesHandCounts) {
  const int S = 64;
  std::vector<Vertex> v = quad(-1, -1, 0.5f, 0.5f);  // front, +1
  for (const Vertex& x : quad(-0.5f, -0.5f, 1, 1)) v.push_back(x);  // front, +1
  for (const Vertex& x : quadCw(-0.25f, -0.25f, 0.25f, 0.25f)) v.push_back(x);  // back, -1
  for (const Vertex& x : quadCw(0.75f, 0.75f, 1, 1)) v.push_back(x);  // back, -1
  const State state{
      .stencilTest = true,
      .stencilFront = {.dppass = StencilOp::IncrWrap},
      .stencilBack = {.dppass = StencilOp::DecrWrap},
      .colorMask = glm::bvec4(false),
  };
  Framebuffer fb(S, S);
  fb.clear(vec4(0.25f));
  drawTriangles(fb, state, v);
  auto inRect = [&](int x, int y, double x0, double y0, double x1, double y1) {
    const double cx = centreNdc(x, S), cy = centreNdc(y, S);
    return cx > x0 && cx < x1 && cy > y0 && cy < y1;
  };
  for (int y = 0; y < S; ++y)
    for (int x = 0; x < S; ++x) {
      const int count = int(inRect(x, y, -1, -1, 0.5, 0.5)) + int(inRect(x, y, -0.5, -0.5, 1, 1)) -
                        int(inRect(x, y, -0.25, -0.25, 0.25, 0.25)) - int(inRect(x, y, 0.75, 0.75, 1, 1));
      ASSERT_EQ(fb.stencil(x, y), std::uint8_t(count & 0xFF)) << x << ", " << y;  // -1 wraps to 255
      ASSERT_FLOAT_EQ(fb.color(x, y).r, 64.0f / 255.0f);  // colour writes masked off
    }
}

TEST(RasterStencilScene, DepthFailCountingAndDestinationAlphaShadow) {
  const int S = 32;
  Framebuffer fb(S, S);
  fb.clear(vec4(0.8f, 0.6f, 0.4f, 1.0f));
  // Occluder on the left half at z = 0 (window depth 0.5), writing alpha 0.5 (its "dim factor").
  drawTriangles(fb, State{.depthTest = true}, quad(-1, -1, 0, 1, 0.0f, vec4(1.0f, 1.0f, 1.0f, 0.5f)));
  // A back-facing volume side behind it (z = 0.5) counts where the depth test FAILS
  // (z-fail / "Carmack's reverse"), with depth and colour writes off.
  const State volume{
      .depthTest = true,
      .depthMask = false,
      .stencilTest = true,
      .stencilBack = {.dpfail = StencilOp::IncrWrap},
      .colorMask = glm::bvec4(false),
  };
  const DrawStats stats = drawTriangles(fb, volume, quadCw(-0.5f, -1, 0.5f, 1, 0.5f));
  EXPECT_EQ(stats.depthFailed, std::size_t(8 * S));
  EXPECT_EQ(stats.written, std::size_t(8 * S));
  // The shadow pass: a full-screen quad blended with (ZERO, DST_ALPHA) where stencil != 0.
  const State shadow{
      .stencilTest = true,
      .stencilFront = {.func = CompareFunc::NotEqual, .ref = 0},
      .blend = BlendState::func(BlendFactor::Zero, BlendFactor::DstAlpha),
  };
  drawTriangles(fb, shadow, quad(-1, -1, 1, 1));
  for (int y = 0; y < S; ++y)
    for (int x = 0; x < S; ++x) {
      const bool occluder = x < 16, counted = x >= 8 && x < 16;
      ASSERT_EQ(fb.stencil(x, y), counted ? 1 : 0) << x;
      ASSERT_FLOAT_EQ(fb.depth(x, y), occluder ? 0.5f : 1.0f);
      const vec4 c = fb.color(x, y);
      // Lit occluder white, shadowed occluder white × 0.5 = 128/255 (alpha 0.25 → 64/255),
      // background untouched.
      if (counted) { ASSERT_FLOAT_EQ(c.r, 128.0f / 255.0f); }
      else if (occluder) { ASSERT_FLOAT_EQ(c.r, 1.0f); }
      else { ASSERT_FLOAT_EQ(c.r, 204.0f / 255.0f); }
    }
}

// ---------------------------------------------------------------------------------
// Depth scenes, overdraw, discard, indices, default shader
// ---------------------------------------------------------------------------------

TEST(RasterDepthScene, NearestWinsInEitherOrder) {
  const vec4 red(1, 0, 0, 1), blue(0, 0, 1, 1);
  const std::vector<Vertex> nearQuad = quad(-1, -1, 0.5f, 0.5f, -0.5f, red), farQuad = quad(-0.5f, -0.5f, 1, 1, 0.5f, blue);
  for (bool nearFirst : {true, false}) {
    Framebuffer fb(16, 16);
    const State state{.depthTest = true};
    drawTriangles(fb, state, nearFirst ? nearQuad : farQuad);
    drawTriangles(fb, state, nearFirst ? farQuad : nearQuad);
    EXPECT_EQ(fb.color(7, 7), red);   // overlap: the nearer quad
    EXPECT_EQ(fb.color(14, 14), blue);
    EXPECT_FLOAT_EQ(fb.depth(7, 7), 0.25f);
    EXPECT_EQ(fb.overdraw(7, 7), 2u);
  }
  // GREATER with depth cleared to 0: the farther one wins.
  Framebuffer fb(16, 16);
  fb.clearDepth(0.0f);
  drawTriangles(fb, State{.depthTest = true, .depthFunc = CompareFunc::Greater}, nearQuad);
  drawTriangles(fb, State{.depthTest = true, .depthFunc = CompareFunc::Greater}, farQuad);
  EXPECT_EQ(fb.color(7, 7), blue);
}

TEST(RasterPipeline, DiscardedFragmentsNeverReachTheFragmentOperations) {
  Framebuffer fb(16, 4);
  const State state{.stencilTest = true, .stencilFront = {.dppass = StencilOp::Incr}};
  const DrawStats stats = drawTriangles(fb, state, quad(-1, -1, 1, 1), {}, [](const Fragment& frag) {
    return frag.pixel.x < 8 ? std::nullopt : std::optional<vec4>(vec4(1.0f));
  });
  EXPECT_EQ(stats.fragments, 64u);
  EXPECT_EQ(stats.discarded, 32u);
  EXPECT_EQ(fb.overdraw(3, 1), 0u);
  EXPECT_EQ(fb.stencil(3, 1), 0);
  EXPECT_EQ(fb.overdraw(12, 1), 1u);
  EXPECT_EQ(fb.stencil(12, 1), 1);
}

TEST(RasterPipeline, IndexedAndNonIndexedDrawTheSame) {
  const std::vector<Vertex> corners = {ndc(-0.7f, -0.9f, 0, vec4(1, 0, 0, 1)), ndc(0.8f, -0.6f, 0, vec4(0, 1, 0, 1)),
                                       ndc(0.6f, 0.9f, 0, vec4(0, 0, 1, 1)), ndc(-0.9f, 0.5f, 0, vec4(1, 1, 0, 1))};
  // A trailing incomplete triangle is ignored, as in GL: its index is never read.
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3, 7};
  std::vector<Vertex> expanded;
  for (std::size_t k = 0; k < 6; ++k) expanded.push_back(corners[indices[k]]);
  Framebuffer a(40, 30, {.color = ColorFormat::Float32}), b(40, 30, {.color = ColorFormat::Float32});
  EXPECT_EQ(drawTriangles(a, State{}, corners, indices).triangles, 2u);
  drawTriangles(b, State{}, expanded);
  EXPECT_TRUE(std::equal(a.colors().begin(), a.colors().end(), b.colors().begin()));
  EXPECT_TRUE(std::equal(a.overdraws().begin(), a.overdraws().end(), b.overdraws().begin()));
  // Without varyings the default shader writes opaque white.
  Framebuffer c(4, 4);
  const std::vector<Vertex> plain = {Vertex{vec4(-1, -1, 0, 1), {}}, Vertex{vec4(3, -1, 0, 1), {}}, Vertex{vec4(-1, 3, 0, 1), {}}};
  drawTriangles(c, State{}, plain);
  EXPECT_EQ(c.color(2, 2), vec4(1.0f));
}
