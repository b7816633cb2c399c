#pragma once
// glint/raster/framebuffer.h — the reference rasterizer's render target.
//
// One Framebuffer holds, per pixel: an RGBA float colour, a float depth, an 8-bit
// stencil value and an overdraw counter (how many fragments reached the
// per-fragment operations, i.e. survived the fragment shader). Pixel (x, y) uses
// OpenGL's window convention: row 0 is the BOTTOM row. The *Image functions flip
// to image convention (row 0 = top) so saved pictures look like a GL screenshot.
//
/// ```cpp
/// #include <glint/raster/pipeline.h>
/// const std::vector<glint::raster::Vertex> vertices = {
///     {{-1, -1, 0, 1}, {}}, {{1, -1, 0, 1}, {}}, {{0, 1, 0, 1}, {}}};  // white without varyings
/// const glint::raster::State state{.depthTest = true};
/// glint::raster::Framebuffer fb(500, 500);
/// fb.clear(glint::vec4(0.2f, 0.2f, 0.2f, 1.0f));  // colour, depth 1, stencil 0, overdraw 0
/// glint::raster::drawTriangles(fb, state, vertices);
/// glint::saveImage(glint::raster::colorImage(fb), "out.png");
/// ```
//
// Formats mirror the GL buffers an oracle is compared against:
//   ColorFormat::Unorm8   GL_RGBA8 (the default framebuffer): every colour written is clamped
//                         to [0, 1] and rounded to a multiple of 1/255; blending clamps its
//                         inputs to [0, 1] (GL 4.5 §17.3.6).
//   ColorFormat::Float32  GL_RGBA32F: values stored as computed, no clamping.
//   DepthFormat::Float32  GL_DEPTH_COMPONENT32F / GL_DEPTH32F_STENCIL8.
//   DepthFormat::Unorm24  GL_DEPTH24_STENCIL8: depth rounded to a multiple of 1/(2^24 - 1)
//                         before the test and the write (stored as the nearest float).

#include "glint/core/math.h"
#include "glint/image/image.h"

#include <cstdint>
#include <span>
#include <vector>

namespace glint::raster {

/// How colour values are stored (see the header comment).
enum class ColorFormat {
  Unorm8,  ///< clamp to [0, 1], quantize to k/255 (GL_RGBA8)
  Float32  ///< unclamped float (GL_RGBA32F)
};

/// How depth values are stored (see the header comment).
enum class DepthFormat {
  Float32,  ///< float as computed (GL_DEPTH_COMPONENT32F)
  Unorm24   ///< quantized to k/(2^24 - 1) (GL_DEPTH24_STENCIL8)
};

struct FramebufferFormat {
  ColorFormat color = ColorFormat::Unorm8;
  DepthFormat depth = DepthFormat::Float32;
};

/// Largest framebuffer side (GL_MAX_RENDERBUFFER_SIZE on llvmpipe).
constexpr int kMaxFramebufferSize = 16384;

class Framebuffer {
public:
  /// A framebuffer cleared to GL's initial clear values: colour (0,0,0,0), depth 1, stencil 0.
  /// Error(Usage) unless 1 <= width, height <= kMaxFramebufferSize.
  Framebuffer(int width, int height, FramebufferFormat format = {});

  int width() const { return m_width; }
  int height() const { return m_height; }
  const FramebufferFormat& format() const { return m_format; }

  // -- Clearing (glClearColor/glClearDepth/glClearStencil + glClear) ------------------
  /// Whole colour buffer; like glClear it honours a colour mask. Unorm8 clamps/quantizes.
  void clearColor(const vec4& color, const glm::bvec4& mask = glm::bvec4(true));
  /// Whole depth buffer; the value is clamped to [0, 1] like glClearDepth.
  void clearDepth(float depth = 1.0f);
  /// Whole stencil buffer; only the low 8 bits of value and the bits set in writeMask are used.
  void clearStencil(int value = 0, std::uint32_t writeMask = 0xFFu);
  /// Sets every overdraw counter to 0.
  void clearOverdraw();
  /// All four at once, unmasked.
  void clear(const vec4& color = vec4(0.0f), float depth = 1.0f, int stencil = 0);

  // -- Pixel access, (0, 0) = lower-left. Error(Usage) outside the framebuffer. -------
  vec4 color(int x, int y) const;
  float depth(int x, int y) const;
  std::uint8_t stencil(int x, int y) const;
  std::uint32_t overdraw(int x, int y) const;
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < m_width && y < m_height; }
  /// Index into the spans below: y * width + x.
  std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(m_width) + std::size_t(x); }

  // -- Whole buffers, bottom row first. Writing through them bypasses format rules. ----
  std::span<vec4> colors() { return m_color; }
  std::span<const vec4> colors() const { return m_color; }
  std::span<float> depths() { return m_depth; }
  std::span<const float> depths() const { return m_depth; }
  std::span<std::uint8_t> stencils() { return m_stencil; }
  std::span<const std::uint8_t> stencils() const { return m_stencil; }
  std::span<std::uint32_t> overdraws() { return m_overdraw; }
  std::span<const std::uint32_t> overdraws() const { return m_overdraw; }

  /// A colour as this framebuffer would store it (Unorm8: clamped and quantized).
  vec4 storedColor(const vec4& color) const;
  /// A depth as this framebuffer would store it (Unorm24: quantized).
  float storedDepth(float depth) const;

private:
  void check(int x, int y) const;

  int m_width = 0;
  int m_height = 0;
  FramebufferFormat m_format;
  std::vector<vec4> m_color;
  std::vector<float> m_depth;
  std::vector<std::uint8_t> m_stencil;
  std::vector<std::uint32_t> m_overdraw;
};

// -- Pictures of a framebuffer (row 0 = top, as image files) ----------------------------

/// RGBA F32 copy of the colour buffer.
Image colorImage(const Framebuffer& fb);
/// 1-channel F32 depth, white = 1.0 (far), black = 0.0 (near), as on the lecture's slide.
Image depthImage(const Framebuffer& fb);
/// RGB U8 false colour of the stencil values (see falseColorImage); maxValue 0 = largest present.
Image stencilImage(const Framebuffer& fb, std::uint32_t maxValue = 0);
/// RGB U8 false colour of the overdraw counts; maxValue 0 = largest present.
Image overdrawImage(const Framebuffer& fb, std::uint32_t maxValue = 0);
/// Counts as colours: 0 black, then 1..maxValue along blue → cyan → green → yellow → red,
/// anything above maxValue white. values are bottom row first (GL order); the image is flipped.
/// Error(Usage) when values.size() != width·height.
Image falseColorImage(std::span<const std::uint32_t> values, int width, int height, std::uint32_t maxValue = 0);

}  // namespace glint::raster
