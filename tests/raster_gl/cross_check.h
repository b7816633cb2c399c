#pragma once
// Test support for comparing glint::raster with OpenGL:
//   GlCanvas           an offscreen GL framebuffer that draws raster::Vertex data under a
//                      raster::State (render/raster_gl.h), read back in the reference's layout
//   ReferenceRecorder  the same draw on the CPU, recording what judging GL needs per pixel
//                      (depth gradient, ambiguous depth tests, clip-created edges)
//   compareBuffers     stencil exactly, depth and colour within tolerances, with counts
#include "glint/gl/objects.h"
#include "glint/raster/raster.h"
#include "glint/render/raster_gl.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace glint::test {

/// Counts every fragment in the stencil buffer; depth GL_ALWAYS so the last fragment's
/// depth is stored; no culling.
inline raster::State countingState() {
  const raster::StencilFace count{.func = raster::CompareFunc::Always, .dppass = raster::StencilOp::IncrWrap};
  return raster::State{.depthTest = true,
                       .depthFunc = raster::CompareFunc::Always,
                       .stencilTest = true,
                       .stencilFront = count,
                       .stencilBack = count};
}

/// What OpenGL drew, bottom row first like raster::Framebuffer's spans.
struct GlBuffers {
  int width = 0, height = 0;
  std::vector<vec4> color;             ///< RGBA8 read as 0..1
  std::vector<float> depth;            ///< window z
  std::vector<std::uint8_t> stencil;
  std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width) + std::size_t(x); }
};

/// An offscreen GL framebuffer: GL_RGBA8 colour and a depth/stencil texture of
/// `depthStencilFormat` (GL_DEPTH32F_STENCIL8 or GL_DEPTH24_STENCIL8).
class GlCanvas {
public:
  GlCanvas(ivec2 size, GLenum depthStencilFormat);

  /// glClear of all buffers, unmasked and unscissored.
  void clear(const vec4& color, float depth, int stencil);
  /// Draws vertices [first, first + count) of `triangles` with `state`; with a scissor
  /// box, GL_SCISSOR_TEST is enabled to it (the reference never writes outside its viewport).
  void draw(const raster::State& state, const render::RasterTriangles& triangles, GLint first = 0, GLsizei count = -1,
            std::optional<raster::Viewport> scissor = std::nullopt);
  GlBuffers read() const;
  ivec2 size() const { return m_size; }

private:
  ivec2 m_size;
  gl::Texture m_color;
  gl::Texture m_depthStencil;
  gl::Framebuffer m_framebuffer;
};

/// Draws into a reference framebuffer like raster::drawTriangles, and records per pixel
/// what judging GL's result needs:
///   - the depth gradient |∇z| (window z per pixel) of the triangle that last wrote depth,
///     for the depth tolerance kDepthAbsolute + |∇z| · kPositionError (below);
///   - "ambiguous" pixels, where a depth test compared two depths closer than both of their
///     tolerances together (so GL may legitimately decide the other way), except exact ties
///     of the same triangle drawn twice, which both pipelines reproduce bit for bit;
///   - "clip-edge" pixels, whose centre lies within kClipEdgeSlack of an edge that clipping
///     created (an edge with a vertex that is not one of the triangle's own). llvmpipe
///     computes those intersection vertices in float, the reference in double; after the
///     perspective divide they differ by up to ~1e-3 px (measured: two pixels 0.0012 and
///     0.0023 px from such edges were covered differently), so a centre that close to a
///     clip edge may fall either way. Coverage along the triangles' own edges, which both
///     snap from the same float inputs, stays exact.
/// Triangles are identified by their clip positions, so a repeated triangle keeps its id.
class ReferenceRecorder {
public:
  explicit ReferenceRecorder(raster::Framebuffer& fb);
  raster::DrawStats draw(const raster::State& state, std::span<const raster::Vertex> vertices);

  raster::Framebuffer& framebuffer() { return m_fb; }
  /// Allowed |GL depth − reference depth| at pixel index i.
  double depthTolerance(std::size_t i) const;
  const std::vector<std::uint8_t>& ambiguous() const { return m_ambiguous; }
  const std::vector<std::uint8_t>& clipEdge() const { return m_clipEdge; }
  std::size_t ambiguousCount() const;
  std::size_t clipEdgeCount() const;

private:
  void markClipEdges(const std::array<vec4, 3>& clip, const raster::State& state);

  raster::Framebuffer& m_fb;
  std::vector<float> m_gradient;        // |∇z| of the last depth writer, per pixel
  std::vector<int> m_writer;            // its triangle id (-1: the clear value)
  std::vector<std::uint8_t> m_ambiguous;
  std::vector<std::uint8_t> m_clipEdge;
  std::map<std::array<float, 12>, int> m_ids;
};

// The depth model. Both pipelines evaluate the same window-z plane, GL (llvmpipe) in
// float from float window positions, the reference in double. A float window position
// near x = 512 is only known to 2^-14 px; a depth plane with gradient |∇z| turns that into
// |∇z| · 2^-14 of depth, and sliver triangles have |∇z| up to 10^4 per pixel. So depth
// must agree up to a sub-pixel shift of kPositionError plus kDepthAbsolute (float
// rounding of z itself, ~1e-7, and 24-bit quantization, 6e-8). Measured on every test
// here: the worst case is printed as "depth err / gradient" (see docs/raster.md).
constexpr double kDepthAbsolute = 1e-6;
constexpr double kPositionError = 1.0 / 4096.0;  // px: 4 float ulps at 512, 1 at 2048

/// Pixel centres closer than this to an edge created by clipping may be covered differently.
constexpr double kClipEdgeSlack = 1.0 / 256.0;  // px: the sub-pixel unit, 1.7× the largest difference measured

/// |∇z| of the window-space depth plane of a clip-space triangle under `state` and a
/// framebuffer of `size` (0 when the triangle is clipped away or degenerate).
double depthGradient(const std::array<vec4, 3>& clip, const raster::State& state, ivec2 size);

/// Pixel-by-pixel agreement of a reference framebuffer with GL's buffers.
struct Agreement {
  std::size_t pixels = 0;
  std::size_t stencilMismatches = 0;   ///< stencil values differing (excluded pixels skipped)
  std::size_t depthCompared = 0;       ///< pixels whose depth was compared
  std::size_t depthOutside = 0;        ///< of those, outside the tolerance
  double maxDepthError = 0.0;          ///< largest |GL depth − reference depth| compared
  double maxDepthShift = 0.0;          ///< largest (error − kDepthAbsolute) / |∇z|, in px
  std::size_t colorOutside = 0;        ///< pixels with a channel beyond the colour tolerance
  double maxColorError = 0.0;          ///< largest channel difference, 0..1
  std::size_t excluded = 0;            ///< pixels skipped: depth ties and clip edges
  std::size_t excludedDepthTies = 0;   ///< of those, ambiguous depth tests
  std::size_t excludedClipEdges = 0;   ///< of those, centres next to a clip-created edge
  std::size_t excludedMismatches = 0;  ///< stencil differences inside the excluded pixels (informative)
  std::string firstStencilMismatch;    ///< "pixel (x, y): GL s, reference t", for messages
  std::string firstDepthOutside;
};

/// Compares every pixel: stencil exactly, depth within recorder.depthTolerance where
/// compareDepth(x, y), colour within colorTolerance where compareColor(x, y). Pixels the
/// recorder marked ambiguous or clip-edge are skipped.
Agreement compareBuffers(const ReferenceRecorder& recorder, const raster::Framebuffer& ref, const GlBuffers& gl,
                         const std::function<bool(int, int)>& compareDepth, double colorTolerance,
                         const std::function<bool(int, int)>& compareColor = {});

/// True when the current context renders with Mesa's llvmpipe, whose rasterization
/// rules (8 sub-pixel bits, bottom-left tie rule, full clipping) glint::raster follows.
bool isLlvmpipe();

}  // namespace glint::test
