// drawTriangles: the reference triangle pipeline (see pipeline.h for the stages).

#include "glint/raster/pipeline.h"

#include "glint/core/error.h"
#include "glint/raster/fragment_ops.h"
#include "glint/raster/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace glint::raster {

namespace {

/// A clipped polygon vertex after the viewport transform.
struct WindowVertex {
  dvec2 xy;          ///< window x, y as computed (interpolation uses these)
  FixedPoint fixed;  ///< snapped window x, y (coverage uses these)
  double z = 0.0;    ///< window z (after glDepthRange)
  double invW = 0.0; ///< 1 / clip w, linear in screen space
  dvec3 weights;     ///< clip-space weights of the original three vertices
};

/// Pixels a draw may touch: the viewport rectangle intersected with the framebuffer.
/// Clipping already keeps primitives inside the viewport; the rectangle makes that hold
/// for samples on its very edge too (and for any guard band kGuardBand might be set to).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< half-open [x0, x1) × [y0, y1)
};

bool isFinite(const vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

/// Everything the per-triangle loop needs that does not change within a draw.
struct DrawContext {
  Framebuffer& fb;
  const State& state;
  const FragmentShader& shader;
  PixelRect rect;
  std::size_t varyingCount = 0;
  DrawStats& stats;
};

/// Values interpolated at one sample.
struct Interpolated {
  double z = 0.0;     ///< window z
  double invW = 0.0;  ///< 1/w_clip (gl_FragCoord.w)
  dvec3 weights;      ///< perspective-correct weights of the original three vertices
};

/// Window z is linear in screen space (the lecture's z plane equation), and so is 1/w;
/// attributes divided by w are too, which gives the perspective-correct weights
/// (Σ λi·attr_i/w_i) / (Σ λi/w_i), GL 4.5 eq. 14.9.
Interpolated interpolate(const std::array<const WindowVertex*, 3>& wv, const dvec3& lambda) {
  Interpolated result;
  dvec3 weightsOverW(0.0);
  for (int i = 0; i < 3; ++i) {
    result.z += lambda[i] * wv[i]->z;
    result.invW += lambda[i] * wv[i]->invW;
    weightsOverW += lambda[i] * wv[i]->invW * wv[i]->weights;
  }
  result.weights = weightsOverW / result.invW;
  return result;
}

/// Rasterizes and shades one (sub-)triangle of a clipped polygon.
void rasterizeTriangle(DrawContext& ctx, const TriangleSetup& tri, const std::array<const WindowVertex*, 3>& wv,
                       const std::array<const Vertex*, 3>& original, bool frontFacing) {
  // Pixels whose centre (256·p + 128 in fixed point) can lie inside the triangle's box.
  std::int64_t minX = tri.v[0].x, maxX = minX, minY = tri.v[0].y, maxY = minY;
  for (const FixedPoint& p : tri.v) {
    minX = std::min(minX, p.x), maxX = std::max(maxX, p.x);
    minY = std::min(minY, p.y), maxY = std::max(maxY, p.y);
  }
  const std::int64_t half = kSubpixelOne / 2;
  const int x0 = int(std::max<std::int64_t>(ctx.rect.x0, -floorDiv(-(minX - half), kSubpixelOne)));
  const int x1 = int(std::min<std::int64_t>(ctx.rect.x1 - 1, floorDiv(maxX - half, kSubpixelOne)));
  const int y0 = int(std::max<std::int64_t>(ctx.rect.y0, -floorDiv(-(minY - half), kSubpixelOne)));
  const int y1 = int(std::min<std::int64_t>(ctx.rect.y1 - 1, floorDiv(maxY - half, kSubpixelOne)));

  std::array<vec4, kMaxVaryings> varyings{};
  for (int py = y0; py <= y1; ++py) {
    for (int px = x0; px <= x1; ++px) {
      if (!coversSample(tri, px, py)) continue;
      ++ctx.stats.fragments;

      // Screen-space barycentrics, as area ratios of the unsnapped window triangle (as
      // llvmpipe and most GPUs set up attribute planes from float positions; snapping only
      // decides coverage). The fixed-point weights are the fallback for a triangle that is
      // flat before snapping but not after.
      const std::optional<dvec3> bary = barycentric(wv[0]->xy, wv[1]->xy, wv[2]->xy, dvec2(px + 0.5, py + 0.5));
      Interpolated at = interpolate(wv, bary ? *bary : sampleBarycentric(tri, px, py));
      // Unsnapped weights extrapolate slightly at snapped edges; next to a vertex with
      // w ≈ 0 that could make 1/w non-positive. The exact weights are never negative.
      if (!(at.invW > 0.0) || !std::isfinite(at.invW)) at = interpolate(wv, sampleBarycentric(tri, px, py));
      // Clipping keeps the exact polygon within the depth range, but a pixel centre that
      // snapping lets in (at most 1/512 px outside) extrapolates the z plane slightly past
      // it. GL clamps only to [0, 1] there (to the depth range only with GL_DEPTH_CLAMP),
      // and so does llvmpipe: measured 0.900036 with glDepthRange(0.1, 0.9).
      const double z = std::clamp(at.z, 0.0, 1.0);
      const double invW = at.invW;
      const dvec3 weights = at.weights;

      for (std::size_t k = 0; k < ctx.varyingCount; ++k) {
        dvec4 v(0.0);
        for (int i = 0; i < 3; ++i) v += weights[i] * dvec4(original[i]->varyings[k]);
        varyings[k] = vec4(v);
      }

      const Fragment fragment{
          .pixel = ivec2(px, py),
          .fragCoord = vec4(float(px) + 0.5f, float(py) + 0.5f, float(z), float(invW)),
          .frontFacing = frontFacing,
          .varyings = std::span<const vec4>(varyings.data(), ctx.varyingCount),
      };
      std::optional<vec4> color;
      if (ctx.shader) color = ctx.shader(fragment);
      else color = ctx.varyingCount > 0 ? varyings[0] : vec4(1.0f);
      if (!color) {
        ++ctx.stats.discarded;
        continue;
      }

      switch (processFragment(ctx.fb, ctx.state, px, py, float(z), *color, frontFacing)) {
        case FragmentFate::StencilFailed: ++ctx.stats.stencilFailed; break;
        case FragmentFate::DepthFailed: ++ctx.stats.depthFailed; break;
        case FragmentFate::Written: ++ctx.stats.written; break;
      }
    }
  }
}

/// Twice the signed area of a (convex) window polygon, exact.
std::int64_t polygonArea2(const std::vector<WindowVertex>& polygon) {
  std::int64_t area2 = 0;
  const FixedPoint& o = polygon[0].fixed;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const FixedPoint& a = polygon[i].fixed;
    const FixedPoint& b = polygon[i + 1].fixed;
    area2 += (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  }
  return area2;
}

bool isCulled(const State& state, bool frontFacing) {
  if (!state.cull) return false;
  switch (state.cullFace) {
    case Face::Front: return frontFacing;
    case Face::Back: return !frontFacing;
    case Face::FrontAndBack: return true;
  }
  return false;
}

/// The varyings every vertex of a draw has: Error(Usage) for an index out of range, more
/// than kMaxVaryings, or vertices that differ in their count.
std::size_t checkedVaryingCount(std::span<const Vertex> vertices, std::span<const std::uint32_t> indices,
                                std::size_t triangleCount) {
  auto vertexIndex = [&](std::size_t k) -> std::size_t { return indices.empty() ? k : std::size_t(indices[k]); };
  const std::size_t varyingCount = triangleCount > 0 ? vertices[vertexIndex(0)].varyings.size() : 0;
  if (varyingCount > kMaxVaryings)
    fail(ErrorKind::Usage, "a vertex has {} varyings; the rasterizer takes at most {}", varyingCount, kMaxVaryings);
  for (std::size_t k = 0; k < triangleCount * 3; ++k) {
    const std::size_t index = vertexIndex(k);
    if (index >= vertices.size())
      fail(ErrorKind::Usage, "index {} (element {}) is out of range for {} vertices", index, k, vertices.size());
    if (vertices[index].varyings.size() != varyingCount)
      fail(ErrorKind::Usage, "vertex {} has {} varyings but vertex {} has {}; a draw needs the same count everywhere",
           index, vertices[index].varyings.size(), vertexIndex(0), varyingCount);
  }
  return varyingCount;
}

}  // namespace

DrawStats drawTriangles(Framebuffer& fb, const State& state, std::span<const Vertex> vertices,
                        std::span<const std::uint32_t> indices, const FragmentShader& shader) {
  // -- Primitive assembly and validation (before anything is drawn) ------------------
  const std::size_t triangleCount = (indices.empty() ? vertices.size() : indices.size()) / 3;
  auto vertexIndex = [&](std::size_t k) -> std::size_t { return indices.empty() ? k : std::size_t(indices[k]); };
  const std::size_t varyingCount = checkedVaryingCount(vertices, indices, triangleCount);

  const Viewport viewport = effectiveViewport(state, fb.width(), fb.height());
  const DepthRange range = clampDepthRange(state.depthRange);
  DrawStats stats;
  DrawContext ctx{
      .fb = fb,
      .state = state,
      .shader = shader,
      .rect = PixelRect{std::max(viewport.x, 0), std::max(viewport.y, 0), std::min(viewport.x + viewport.width, fb.width()),
                        std::min(viewport.y + viewport.height, fb.height())},
      .varyingCount = varyingCount,
      .stats = stats,
  };

  for (std::size_t t = 0; t < triangleCount; ++t) {
    ++stats.triangles;
    const std::array<const Vertex*, 3> tri = {&vertices[vertexIndex(3 * t)], &vertices[vertexIndex(3 * t + 1)],
                                              &vertices[vertexIndex(3 * t + 2)]};
    if (!isFinite(tri[0]->position) || !isFinite(tri[1]->position) || !isFinite(tri[2]->position)) {
      ++stats.rejected;
      continue;
    }

    // -- Clipping in homogeneous clip space -------------------------------------------
    const std::vector<ClipVertex> clipped =
        clipTriangle({dvec4(tri[0]->position), dvec4(tri[1]->position), dvec4(tri[2]->position)});
    if (clipped.empty()) {
      ++stats.clippedAway;
      continue;
    }
    const bool wasClipped = clipped.size() != 3 || clipped[0].weights != dvec3(1, 0, 0) ||
                            clipped[1].weights != dvec3(0, 1, 0) || clipped[2].weights != dvec3(0, 0, 1);
    if (wasClipped) ++stats.clipped;

    // -- Perspective divide, viewport transform, snapping ------------------------------
    std::vector<WindowVertex> polygon;
    for (const ClipVertex& cv : clipped) {
      const dvec3 window = clipToWindow(cv.position, viewport, range);
      polygon.push_back(WindowVertex{dvec2(window), snapToSubpixel(dvec2(window)), window.z, 1.0 / cv.position.w, cv.weights});
    }

    // -- Facing and culling from the window-space area (GL 4.5 eq. 14.8) ---------------
    const std::int64_t area2 = polygonArea2(polygon);
    if (area2 == 0) {
      ++stats.degenerate;
      continue;
    }
    const bool counterClockwise = area2 > 0;
    const bool frontFacing = counterClockwise == (state.frontFace == Winding::Ccw);
    if (isCulled(state, frontFacing)) {
      ++stats.culled;
      continue;
    }

    // -- Rasterize the polygon as a fan; its inner edges are shared, so the tie rule
    //    draws every pixel of the polygon exactly once. -------------------------------
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      const std::array<const WindowVertex*, 3> fan = {&polygon[0], &polygon[i], &polygon[i + 1]};
      const std::optional<TriangleSetup> setup = setupTriangle({fan[0]->fixed, fan[1]->fixed, fan[2]->fixed});
      // Snapping can flatten or (for slivers) flip a fan triangle of a clipped polygon;
      // such a triangle covers no area of the polygon and is skipped.
      if (!setup || setup->counterClockwise() != counterClockwise) continue;
      rasterizeTriangle(ctx, *setup, fan, tri, frontFacing);
    }
  }
  return stats;
}

}  // namespace glint::raster
