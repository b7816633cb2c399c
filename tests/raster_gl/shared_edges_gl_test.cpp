// Shared edges and vertices against OpenGL: meshes whose triangles share edges must
// cover every pixel of their union exactly once, in both pipelines — including edges
// through pixel centres (ties), a vertex exactly on a pixel centre shared by a fan,
// and a perspective ground plane that reaches behind the eye, so that clipping cuts
// shared edges. The stencil buffer counts fragments (GL_INCR_WRAP on every fragment),
// so a hole is a 0 and a doubly drawn pixel a 2.
#include "cross_check.h"

#include "glint/core/camera.h"
#include "support/gl_test.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

using namespace glint;
using glint::testing::GlTest;
using glm::dvec2;

namespace {

constexpr int kWidth = 256, kHeight = 192;

// Depth: see cross_check.h. Colour: see coverage_gl_test.cpp.
constexpr double kColorTolerance = 2.0 / 255.0;


vec4 windowToClip(dvec2 window, double z, double w) {
  const dvec2 ndc{window.x / (kWidth / 2.0) - 1.0, window.y / (kHeight / 2.0) - 1.0};
  return vec4(float(ndc.x * w), float(ndc.y * w), float(z * w), float(w));
}

/// A grid of (n+1)² vertices over a region larger than the viewport, jittered: half the
/// vertices on the half-pixel lattice (edges through pixel centres), half anywhere;
/// random diagonals and windings; per-vertex w (same window position, other 1/w).
std::vector<raster::Vertex> jitteredGrid(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double x0 = -20, y0 = -20, x1 = kWidth + 20, y1 = kHeight + 20;
  std::vector<raster::Vertex> grid;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      dvec2 p{x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n};
      const bool inner = i > 0 && j > 0 && i < n && j < n;  // the border stays straight
      if (inner) p += dvec2(u(rng) - 0.5, u(rng) - 0.5) * ((x1 - x0) / n * 0.6);
      if (u(rng) < 0.5) p = glm::round(p * 2.0) / 2.0;
      const double w = u(rng) < 0.5 ? 1.0 : 0.5 + 1.5 * u(rng);
      grid.push_back({windowToClip(p, u(rng) * 1.8 - 0.9, w), {vec4(float(u(rng)), float(u(rng)), float(u(rng)), 1)}});
    }
  }
  std::vector<raster::Vertex> out;
  auto at = [&](int i, int j) { return grid[std::size_t(j * (n + 1) + i)]; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const bool flipDiagonal = u(rng) < 0.5, flipWinding = u(rng) < 0.5;
      std::array<raster::Vertex, 6> q = flipDiagonal
                                            ? std::array{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)}
                                            : std::array{at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      if (flipWinding) std::swap(q[1], q[2]), std::swap(q[4], q[5]);
      out.insert(out.end(), q.begin(), q.end());
    }
  }
  return out;
}

/// A fan of `spokes` triangles around a centre vertex exactly on a pixel centre.
std::vector<raster::Vertex> fan(dvec2 centre, double radius, int spokes) {
  std::vector<raster::Vertex> out;
  auto rim = [&](int k) {
    const double a = 6.283185307179586 * k / spokes;
    return raster::Vertex{windowToClip(centre + radius * dvec2(std::cos(a), std::sin(a)), 0.2, 1.0), {vec4(1, 0.5, 0, 1)}};
  };
  for (int k = 0; k < spokes; ++k)
    out.insert(out.end(), {raster::Vertex{windowToClip(centre, -0.3, 1.0), {vec4(0, 0, 1, 1)}}, rim(k), rim(k + 1)});
  return out;
}

/// A 20×20 ground grid on y = 0 seen by a low camera standing on it: the grid runs
/// behind the eye, so triangles are cut by the near plane (and w < 0 vertices occur).
std::vector<raster::Vertex> groundThroughTheEye() {
  const auto camera = glint::Camera::lookAt({0.3f, 0.4f, 0.0f}, {0.0f, 0.0f, -3.0f}, {0, 1, 0}, 70.0f,
                                             float(kWidth) / float(kHeight), 0.1f, 30.0f);
  const mat4 viewProj = camera.viewProjection();
  constexpr int n = 20;
  auto vertex = [&](int i, int j) {
    const vec3 p{-10.0f + 20.0f * float(i) / n, 0.0f, -10.0f + 20.0f * float(j) / n};
    return raster::Vertex{viewProj * vec4(p, 1.0f), {vec4(float(i) / n, float(j) / n, 0.5f, 1.0f)}};
  };
  std::vector<raster::Vertex> out;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      out.insert(out.end(), {vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1), vertex(i, j), vertex(i + 1, j + 1),
                             vertex(i + 1, j)});
  return out;
}

struct Drawn {
  raster::Framebuffer ref{kWidth, kHeight};
  test::ReferenceRecorder recorder{ref};
  test::GlBuffers gl;
  raster::DrawStats stats;
};

void drawBoth(Drawn& d, const std::vector<raster::Vertex>& vertices) {
  test::GlCanvas canvas({kWidth, kHeight}, GL_DEPTH32F_STENCIL8);
  canvas.clear(vec4(0.0f), 1.0f, 0);
  const render::RasterTriangles gpu(vertices, "shared-edges");
  canvas.draw(test::countingState(), gpu);
  d.gl = canvas.read();
  d.stats = d.recorder.draw(test::countingState(), vertices);
}

std::size_t count(std::span<const std::uint8_t> values, std::uint8_t v) {
  return std::size_t(std::count(values.begin(), values.end(), v));
}

void expectAgreement(const Drawn& d, const char* what) {
  const auto a = test::compareBuffers(
      d.recorder, d.ref, d.gl, [&](int x, int y) { return d.ref.stencil(x, y) > 0 && d.gl.stencil[d.gl.index(x, y)] > 0; },
      kColorTolerance);
  const std::size_t allowed = test::isLlvmpipe() ? 0 : a.pixels / 1000;  // see coverage_gl_test.cpp
  EXPECT_LE(a.stencilMismatches, allowed) << what << ": first difference at " << a.firstStencilMismatch;
  EXPECT_EQ(a.depthOutside, 0u) << what << ": first at " << a.firstDepthOutside;
  EXPECT_EQ(a.colorOutside, 0u) << what;
  EXPECT_LE(a.excluded, a.pixels / 100) << what;
  std::printf("[ raster ] %-28s %zu triangles, %zu px covered, %zu coverage mismatches (%zu clip-edge px excluded, %zu "
              "of them differ), depth err %.3g (%.2g px of gradient), colour err %.0f/255\n",
              what, d.stats.triangles, a.pixels - count(d.ref.stencils(), 0), a.stencilMismatches, a.excludedClipEdges,
              a.excludedMismatches, a.maxDepthError, a.maxDepthShift, a.maxColorError * 255);
}

}  // namespace

TEST_F(GlTest, JitteredGridCoversEveryPixelExactlyOnceInBoth) {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    Drawn d;
    drawBoth(d, jitteredGrid(rng, 12 + int(seed) * 4));
    // The grid extends past the viewport on every side: every pixel exactly once.
    EXPECT_EQ(count(d.ref.stencils(), 1), d.ref.stencils().size()) << "reference: hole or double hit, seed " << seed;
    EXPECT_EQ(count(d.gl.stencil, 1), d.gl.stencil.size()) << "OpenGL: hole or double hit, seed " << seed;
    EXPECT_GT(d.stats.clipped, 0u);  // the border triangles cross the viewport edges
    expectAgreement(d, "jittered grid");
  }
}

TEST_F(GlTest, FanAroundAPixelCentreDrawsTheCentreOnce) {
  const dvec2 centre{100.5, 80.5};  // exactly a sample position: every spoke passes through it
  Drawn d;
  drawBoth(d, fan(centre, 60.0, 12));
  EXPECT_EQ(d.ref.stencil(100, 80), 1);
  EXPECT_EQ(d.gl.stencil[d.gl.index(100, 80)], 1);
  EXPECT_EQ(count(d.ref.stencils(), 2), 0u);
  EXPECT_EQ(count(d.gl.stencil, 2), 0u);
  expectAgreement(d, "fan on a pixel centre");
}

TEST_F(GlTest, GroundPlaneCutByTheNearPlaneStaysWatertight) {
  Drawn d;
  drawBoth(d, groundThroughTheEye());
  EXPECT_GT(d.stats.clipped, 10u);
  EXPECT_EQ(count(d.ref.stencils(), 2), 0u) << "clipped shared edges drawn twice (reference)";
  EXPECT_EQ(count(d.gl.stencil, 2), 0u) << "clipped shared edges drawn twice (OpenGL)";
  // The ground fills the lower part of the view, below the horizon, without holes:
  // the bottom row is entirely covered.
  for (int x = 0; x < kWidth; ++x) EXPECT_EQ(d.ref.stencil(x, 0), 1) << x;
  expectAgreement(d, "ground through the eye");
}
