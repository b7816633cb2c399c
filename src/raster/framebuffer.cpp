// The reference rasterizer's framebuffer and its pictures (see framebuffer.h).

#include "glint/raster/framebuffer.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cmath>

namespace glint::raster {

namespace {

float clamp01(float v) {
  if (!(v > 0.0f)) return 0.0f;  // NaN becomes 0 rather than garbage
  return std::min(v, 1.0f);
}

/// GL's float → normalized fixed-point conversion (round to nearest), back to float.
float quantize(float v, double levels) {
  return static_cast<float>(std::nearbyint(double(clamp01(v)) * levels) / levels);
}

constexpr double kUnorm8Levels = 255.0;
constexpr double kUnorm24Levels = 16777215.0;  // 2^24 - 1

}  // namespace

Framebuffer::Framebuffer(int width, int height, FramebufferFormat format)
    : m_width(width), m_height(height), m_format(format) {
  if (width < 1 || height < 1 || width > kMaxFramebufferSize || height > kMaxFramebufferSize)
    fail(ErrorKind::Usage, "framebuffer size must be 1..{} per side, got {}x{}", kMaxFramebufferSize, width, height);
  const std::size_t n = std::size_t(width) * std::size_t(height);
  m_color.resize(n);
  m_depth.resize(n);
  m_stencil.resize(n);
  m_overdraw.resize(n);
  clear();
}

vec4 Framebuffer::storedColor(const vec4& color) const {
  if (m_format.color == ColorFormat::Float32) return color;
  return vec4(quantize(color.r, kUnorm8Levels), quantize(color.g, kUnorm8Levels), quantize(color.b, kUnorm8Levels),
              quantize(color.a, kUnorm8Levels));
}

float Framebuffer::storedDepth(float depth) const {
  if (m_format.depth == DepthFormat::Float32) return depth;
  return quantize(depth, kUnorm24Levels);
}

void Framebuffer::clearColor(const vec4& color, const glm::bvec4& mask) {
  const vec4 value = storedColor(color);
  for (vec4& c : m_color)
    for (int i = 0; i < 4; ++i)
      if (mask[i]) c[i] = value[i];
}

void Framebuffer::clearDepth(float depth) { std::fill(m_depth.begin(), m_depth.end(), storedDepth(clamp01(depth))); }

void Framebuffer::clearStencil(int value, std::uint32_t writeMask) {
  const auto mask = static_cast<std::uint8_t>(writeMask & 0xFFu);
  const auto v = static_cast<std::uint8_t>(value & 0xFF);
  for (std::uint8_t& s : m_stencil) s = static_cast<std::uint8_t>((s & ~mask) | (v & mask));
}

void Framebuffer::clearOverdraw() { std::fill(m_overdraw.begin(), m_overdraw.end(), 0u); }

void Framebuffer::clear(const vec4& color, float depth, int stencil) {
  clearColor(color);
  clearDepth(depth);
  clearStencil(stencil);
  clearOverdraw();
}

void Framebuffer::check(int x, int y) const {
  if (!contains(x, y)) fail(ErrorKind::Usage, "pixel ({}, {}) is outside the {}x{} framebuffer", x, y, m_width, m_height);
}

vec4 Framebuffer::color(int x, int y) const {
  check(x, y);
  return m_color[index(x, y)];
}
float Framebuffer::depth(int x, int y) const {
  check(x, y);
  return m_depth[index(x, y)];
}
std::uint8_t Framebuffer::stencil(int x, int y) const {
  check(x, y);
  return m_stencil[index(x, y)];
}
std::uint32_t Framebuffer::overdraw(int x, int y) const {
  check(x, y);
  return m_overdraw[index(x, y)];
}

// ---------------------------------------------------------------------------------
// Pictures
// ---------------------------------------------------------------------------------

Image colorImage(const Framebuffer& fb) {
  Image image(fb.width(), fb.height(), 4, PixelType::F32);
  std::span<float> out = image.pixels<float>();
  for (int y = 0; y < fb.height(); ++y) {
    const int row = fb.height() - 1 - y;  // image row 0 is the top; GL row 0 the bottom
    for (int x = 0; x < fb.width(); ++x) {
      const vec4 c = fb.colors()[fb.index(x, y)];
      for (int i = 0; i < 4; ++i) out[(std::size_t(row) * std::size_t(fb.width()) + std::size_t(x)) * 4 + std::size_t(i)] = c[i];
    }
  }
  return image;
}

Image depthImage(const Framebuffer& fb) {
  Image image(fb.width(), fb.height(), 1, PixelType::F32);
  std::span<float> out = image.pixels<float>();
  for (int y = 0; y < fb.height(); ++y) {
    const int row = fb.height() - 1 - y;
    for (int x = 0; x < fb.width(); ++x)
      out[std::size_t(row) * std::size_t(fb.width()) + std::size_t(x)] = fb.depths()[fb.index(x, y)];
  }
  return image;
}

namespace {
vec3 ramp(float t) {
  // Five stops, evenly spaced: blue, cyan, green, yellow, red.
  static const vec3 kStops[] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  constexpr int kSegments = 4;
  const float s = std::clamp(t, 0.0f, 1.0f) * kSegments;
  const int i = std::min(int(s), kSegments - 1);
  return glm::mix(kStops[i], kStops[i + 1], s - float(i));
}
}  // namespace

Image falseColorImage(std::span<const std::uint32_t> values, int width, int height, std::uint32_t maxValue) {
  if (width < 1 || height < 1 || values.size() != std::size_t(width) * std::size_t(height))
    fail(ErrorKind::Usage, "false-colour image: {} values do not make a {}x{} image", values.size(), width, height);
  if (maxValue == 0) maxValue = *std::max_element(values.begin(), values.end());
  Image image(width, height, 3, PixelType::U8);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint32_t v = values[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      vec3 c(0.0f);
      if (v > maxValue) c = vec3(1.0f);
      else if (v > 0) c = ramp(maxValue > 1 ? float(v - 1) / float(maxValue - 1) : 0.0f);
      for (int i = 0; i < 3; ++i) image.set(x, height - 1 - y, i, c[i]);
    }
  }
  return image;
}

Image stencilImage(const Framebuffer& fb, std::uint32_t maxValue) {
  const std::vector<std::uint32_t> values(fb.stencils().begin(), fb.stencils().end());
  return falseColorImage(values, fb.width(), fb.height(), maxValue);
}

Image overdrawImage(const Framebuffer& fb, std::uint32_t maxValue) {
  return falseColorImage(fb.overdraws(), fb.width(), fb.height(), maxValue);
}

}  // namespace glint::raster
