// glint::raster against OpenGL (headless llvmpipe): which pixels a triangle covers, how
// often, and the depth it writes there.
//
// Method. Both pipelines draw the same clip-space vertices under the same raster::State
// (render/raster_gl.h) with the stencil test on and GL_INCR_WRAP on depth pass, so the
// stencil buffer counts the fragments of every pixel: coverage, double coverage and
// holes all show up as stencil values, and depth (GL_ALWAYS, writes on) is the depth
// of the last fragment. Random triangles are drawn one per 32×32 tile of a 512×512
// canvas, each tile its own viewport (so viewport offsets are exercised too) and
// scissor (so tiles are independent whatever a GL implementation does outside its
// viewport), 256 triangles per readback.
//
// What must agree, and why it can:
//   coverage  exactly, pixel for pixel, on llvmpipe: glint::raster uses its rules
//             (1/256-pixel snapping with round-to-nearest-even, the bottom-left tie rule,
//             clipping against all six planes). GL itself leaves sub-pixel precision and
//             the tie rule to the implementation (GL 4.5 §14.6.1 only requires that
//             shared edges be covered once), so on another driver edge pixels may differ;
//             there the tests allow kOtherDriverCoverageSlack of the pixels and say so.
//             Not compared: pixel centres within 1/256 px of an edge that clipping
//             created (llvmpipe computes those vertices in float; cross_check.h).
//   depth     within a tolerance that scales with the triangle's depth gradient
//             (cross_check.h), because both evaluate the same plane from slightly
//             different floating-point inputs.
//   colour    within kColorTolerance, except on slivers: their colour gradients reach
//             thousands of codes per pixel, so the same 2^-14 px of position rounding
//             that moves depth moves colour by several codes and proves nothing.
#include "cross_check.h"

#include "support/gl_test.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

using namespace glint;
using glint::testing::GlTest;
using glm::dvec2;

namespace {

constexpr int kTile = 32;
constexpr int kTilesPerSide = 16;  // 256 triangles per batch on a 512×512 canvas
constexpr int kCanvas = kTile * kTilesPerSide;

// Depth: within kDepthAbsolute + |∇z| · kPositionError per pixel (cross_check.h explains
// the model; |∇z| is the depth gradient of the triangle at that pixel).
// Colour: varyings are perspective-correct in both; llvmpipe interpolates in float and
// both round to 8 bits, so a channel may land one code apart, two on steep gradients.
constexpr double kColorTolerance = 2.0 / 255.0;

// Other drivers: different sub-pixel precision or tie rule moves pixels whose centre lies
// within a fraction of a pixel of an edge; 1 in 1,000 covers that and still fails on a
// wrong edge (a whole row or column of a tile is 1 in 32).
constexpr double kOtherDriverCoverageSlack = 1e-3;

enum class Category { HalfPixelTies, SubpixelGrid, RandomFloat, Slivers, Tiny, Huge, BehindTheEye, NearFarPlanes, OffScreen };

const char* name(Category c) {
  switch (c) {
    case Category::HalfPixelTies: return "half-pixel ties";
    case Category::SubpixelGrid: return "1/256 grid, partly off-screen";
    case Category::RandomFloat: return "random float";
    case Category::Slivers: return "slivers";
    case Category::Tiny: return "tiny";
    case Category::Huge: return "huge";
    case Category::BehindTheEye: return "behind the eye (w < 0)";
    case Category::NearFarPlanes: return "crossing near/far";
    case Category::OffScreen: return "off-screen";
  }
  return "?";
}

std::string categoryId(const ::testing::TestParamInfo<Category>& info) {
  static const char* const kIds[] = {"HalfPixelTies", "SubpixelGrid", "RandomFloat", "Slivers",  "Tiny",
                                     "Huge",          "BehindTheEye", "NearFarPlanes", "OffScreen"};
  return kIds[int(info.param)];
}

class TriangleMaker {
public:
  explicit TriangleMaker(unsigned seed) : m_rng(seed) {}

  /// Three clip-space positions for a kTile×kTile viewport.
  std::array<vec4, 3> make(Category category) {
    std::array<dvec2, 3> win{};  // window position inside the tile's viewport
    double w = uniform(0.0, 1.0) < 0.5 ? 1.0 : uniform(0.5, 4.0);
    switch (category) {
      case Category::HalfPixelTies:  // vertices and edges through pixel centres: ties
        for (auto& p : win) p = {double(m_rng() % (2 * kTile + 1)) * 0.5, double(m_rng() % (2 * kTile + 1)) * 0.5};
        w = 1.0;  // x/w exact: every tie is a real tie
        break;
      case Category::SubpixelGrid:
        for (auto& p : win) p = {double(m_rng() % (kTile * 256 * 3)) / 256.0 - kTile, double(m_rng() % (kTile * 256 * 3)) / 256.0 - kTile};
        break;
      case Category::RandomFloat:
        for (auto& p : win) p = {uniform(-4, kTile + 4), uniform(-4, kTile + 4)};
        break;
      case Category::Slivers: {  // nearly collinear: the third vertex 1e-4..0.3 px off the line
        win[0] = {uniform(-4, kTile + 4), uniform(-4, kTile + 4)};
        win[1] = {uniform(-4, kTile + 4), uniform(-4, kTile + 4)};
        const dvec2 d = win[1] - win[0];
        const dvec2 n = glm::length(d) > 0 ? dvec2(-d.y, d.x) / glm::length(d) : dvec2(0, 1);
        win[2] = win[0] + uniform(0.1, 0.9) * d + n * std::pow(10.0, uniform(-4, -0.5)) * (uniform(0, 1) < 0.5 ? -1.0 : 1.0);
        break;
      }
      case Category::Tiny: {  // sub-pixel triangles, often around a pixel centre
        const dvec2 c{double(m_rng() % kTile) + 0.5, double(m_rng() % kTile) + 0.5};
        for (auto& p : win) p = c + dvec2(uniform(-0.75, 0.75), uniform(-0.75, 0.75));
        break;
      }
      case Category::Huge: {  // one vertex in the tile, two up to 10^7 tiles away
        win[0] = {uniform(0, kTile), uniform(0, kTile)};
        for (int i = 1; i < 3; ++i) {
          const double angle = uniform(0, 6.283185307179586), r = kTile * std::pow(10.0, uniform(1, 7));
          win[std::size_t(i)] = win[0] + r * dvec2(std::cos(angle), std::sin(angle));
        }
        break;
      }
      case Category::BehindTheEye: {  // raw clip space, w in [-1, 3]: some vertices behind the eye
        std::array<vec4, 3> clip{};
        for (auto& p : clip) p = vec4(float(uniform(-2, 2)), float(uniform(-2, 2)), float(uniform(-3, 3)), float(uniform(-1, 3)));
        return clip;
      }
      case Category::NearFarPlanes: {  // in x/y, but NDC z in [-2.5, 2.5]: cut by the near and far planes
        std::array<vec4, 3> clip{};
        for (auto& p : clip) {
          const double ww = uniform(0.5, 4.0);
          p = vec4(float(uniform(-1.2, 1.2) * ww), float(uniform(-1.2, 1.2) * ww), float(uniform(-2.5, 2.5) * ww), float(ww));
        }
        return clip;
      }
      case Category::OffScreen: {  // entirely beyond one side of the view volume
        const int side = int(m_rng() % 4);
        for (auto& p : win) {
          p = {uniform(-2 * kTile, 3 * kTile), uniform(-2 * kTile, 3 * kTile)};
          if (side == 0) p.x = uniform(-3 * kTile, -0.01);
          if (side == 1) p.x = uniform(kTile + 0.01, 3 * kTile);
          if (side == 2) p.y = uniform(-3 * kTile, -0.01);
          if (side == 3) p.y = uniform(kTile + 0.01, 3 * kTile);
        }
        break;
      }
    }
    std::array<vec4, 3> clip{};
    for (std::size_t i = 0; i < 3; ++i) {
      const double z = uniform(-0.9, 0.9);
      const dvec2 ndc = win[i] / (kTile / 2.0) - 1.0;
      clip[i] = vec4(float(ndc.x * w), float(ndc.y * w), float(z * w), float(w));
    }
    return clip;
  }

  vec4 color() { return vec4(float(uniform(0, 1)), float(uniform(0, 1)), float(uniform(0, 1)), 1.0f); }

private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(m_rng); }
  std::mt19937 m_rng;
};


std::size_t allowedCoverageMismatches(std::size_t pixels) {
  static const bool llvmpipe = test::isLlvmpipe();
  return llvmpipe ? 0 : std::size_t(double(pixels) * kOtherDriverCoverageSlack);
}

std::size_t countStencil(std::span<const std::uint8_t> values, std::uint8_t v) {
  return std::size_t(std::count(values.begin(), values.end(), v));
}

}  // namespace

class RasterCoverage : public GlTest, public ::testing::WithParamInterface<Category> {};

TEST_P(RasterCoverage, MatchesOpenGLPixelForPixel) {
  const Category category = GetParam();
  TriangleMaker maker(1000u + unsigned(category));
  test::GlCanvas canvas({kCanvas, kCanvas}, GL_DEPTH32F_STENCIL8);
  raster::Framebuffer ref(kCanvas, kCanvas);
  const bool compareColor = category != Category::Slivers;

  constexpr int kBatches = 2;  // 512 triangles per category
  std::size_t covered = 0, clipped = 0, triangles = 0, pixels = 0, mismatches = 0, clipEdge = 0,
              clipEdgeDiffering = 0;
  double maxDepthError = 0, maxDepthShift = 0, maxColorError = 0;
  for (int batch = 0; batch < kBatches; ++batch) {
    std::vector<raster::Vertex> vertices;
    for (int t = 0; t < kTilesPerSide * kTilesPerSide; ++t)
      for (const vec4& p : maker.make(category)) vertices.push_back({p, {maker.color()}});
    const render::RasterTriangles gpu(vertices, "coverage-triangles");

    canvas.clear(vec4(0.0f), 1.0f, 0);
    ref.clear(vec4(0.0f), 1.0f, 0);
    test::ReferenceRecorder recorder(ref);
    for (int t = 0; t < kTilesPerSide * kTilesPerSide; ++t) {
      raster::State state = test::countingState();
      state.viewport = raster::Viewport{(t % kTilesPerSide) * kTile, (t / kTilesPerSide) * kTile, kTile, kTile};
      const auto stats = recorder.draw(state, std::span(vertices).subspan(std::size_t(t) * 3, 3));
      clipped += stats.clipped;
      ++triangles;
      canvas.draw(state, gpu, t * 3, 3, state.viewport);
    }
    const test::GlBuffers gl = canvas.read();
    const auto agreement = test::compareBuffers(
        recorder, ref, gl,
        [&](int x, int y) { return ref.stencil(x, y) > 0 && gl.stencil[gl.index(x, y)] > 0; },  // where both drew
        kColorTolerance, [&](int, int) { return compareColor; });
    EXPECT_EQ(recorder.ambiguousCount(), 0u);  // GL_ALWAYS decides nothing by value
    EXPECT_LE(agreement.stencilMismatches, allowedCoverageMismatches(agreement.pixels))
        << name(category) << ", batch " << batch << ": first difference at " << agreement.firstStencilMismatch;
    EXPECT_EQ(agreement.depthOutside, 0u) << name(category) << ": first at " << agreement.firstDepthOutside;
    EXPECT_EQ(agreement.colorOutside, 0u) << name(category);
    mismatches += agreement.stencilMismatches;
    clipEdge += agreement.excludedClipEdges;
    clipEdgeDiffering += agreement.excludedMismatches;
    pixels += agreement.pixels;
    covered += agreement.pixels - countStencil(ref.stencils(), 0);
    maxDepthError = std::max(maxDepthError, agreement.maxDepthError);
    maxDepthShift = std::max(maxDepthShift, agreement.maxDepthShift);
    maxColorError = std::max(maxColorError, agreement.maxColorError);
    // One triangle per tile and no overlap: every count is 0 or 1.
    EXPECT_EQ(countStencil(ref.stencils(), 0) + countStencil(ref.stencils(), 1), ref.stencils().size());
  }

  // Not vacuous: each category draws what it is meant to draw.
  if (category == Category::OffScreen) {
    EXPECT_EQ(covered, 0u);
  } else {
    EXPECT_GT(covered, category == Category::Tiny || category == Category::Slivers ? 20u : 2000u);
  }
  if (category == Category::Huge || category == Category::BehindTheEye || category == Category::NearFarPlanes) {
    EXPECT_GT(clipped, triangles / 3) << "these triangles are meant to be clipped";
  }

  RecordProperty("triangles", int(triangles));
  RecordProperty("pixels", int(pixels));
  RecordProperty("covered", int(covered));
  RecordProperty("coverage_mismatches", int(mismatches));
  RecordProperty("clip_edge_pixels_excluded", int(clipEdge));
  EXPECT_LE(clipEdge, pixels / 200) << "clip-edge exclusions must stay rare";
  RecordProperty("max_depth_error", std::to_string(maxDepthError));
  RecordProperty("max_depth_shift_px", std::to_string(maxDepthShift));
  RecordProperty("max_color_error_255", std::to_string(maxColorError * 255));
  std::printf("[ raster ] %-30s %zu triangles (%zu clipped), %zu px covered, %zu coverage mismatches (%zu clip-edge px "
              "excluded, %zu of them differ), depth err %.3g (%.2g px of gradient), colour err %.0f/255%s\n",
              name(category), triangles, clipped, covered, mismatches, clipEdge, clipEdgeDiffering, maxDepthError,
              maxDepthShift, maxColorError * 255, compareColor ? "" : " (not compared)");
}

INSTANTIATE_TEST_SUITE_P(Categories, RasterCoverage,
                         ::testing::Values(Category::HalfPixelTies, Category::SubpixelGrid, Category::RandomFloat,
                                           Category::Slivers, Category::Tiny, Category::Huge, Category::BehindTheEye,
                                           Category::NearFarPlanes, Category::OffScreen),
                         categoryId);
