#include "glint/image/image.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace glint {

std::size_t pixelTypeSize(PixelType type) {
  switch (type) {
    case PixelType::U8: return 1;
    case PixelType::U16: return 2;
    case PixelType::F32: return 4;
  }
  return 1;
}

const char* pixelTypeName(PixelType type) {
  switch (type) {
    case PixelType::U8: return "8-bit";
    case PixelType::U16: return "16-bit";
    case PixelType::F32: return "float";
  }
  return "?";
}

Image::Image(int width, int height, int channels, PixelType type)
    : m_width(width), m_height(height), m_channels(channels), m_type(type) {
  if (width <= 0 || height <= 0) fail(ErrorKind::Usage, "image size must be positive, got {}x{}", width, height);
  if (channels < 1 || channels > 4) fail(ErrorKind::Usage, "images have 1 to 4 channels, got {}", channels);
  m_data.resize(pixelCount() * bytesPerPixel());
}

namespace {
template <typename T> constexpr PixelType typeOf();
template <> constexpr PixelType typeOf<std::uint8_t>() { return PixelType::U8; }
template <> constexpr PixelType typeOf<std::uint16_t>() { return PixelType::U16; }
template <> constexpr PixelType typeOf<float>() { return PixelType::F32; }
}  // namespace

template <typename T> std::span<T> Image::pixels() {
  if (typeOf<T>() != m_type) fail(ErrorKind::Internal, "image pixel type mismatch");
  return {reinterpret_cast<T*>(m_data.data()), m_data.size() / sizeof(T)};
}
template <typename T> std::span<const T> Image::pixels() const {
  if (typeOf<T>() != m_type) fail(ErrorKind::Internal, "image pixel type mismatch");
  return {reinterpret_cast<const T*>(m_data.data()), m_data.size() / sizeof(T)};
}
template std::span<std::uint8_t> Image::pixels();
template std::span<std::uint16_t> Image::pixels();
template std::span<float> Image::pixels();
template std::span<const std::uint8_t> Image::pixels() const;
template std::span<const std::uint16_t> Image::pixels() const;
template std::span<const float> Image::pixels() const;

float Image::at(int x, int y, int c) const {
  const std::size_t i = (std::size_t(y) * std::size_t(m_width) + std::size_t(x)) * std::size_t(m_channels) + std::size_t(c);
  const std::byte* p = m_data.data() + i * pixelTypeSize(m_type);
  switch (m_type) {
    case PixelType::U8: return float(std::to_integer<std::uint8_t>(*p)) / 255.0f;
    case PixelType::U16: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return float(v) / 65535.0f;
    }
    case PixelType::F32: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
  return 0;
}

void Image::set(int x, int y, int c, float value) {
  const std::size_t i = (std::size_t(y) * std::size_t(m_width) + std::size_t(x)) * std::size_t(m_channels) + std::size_t(c);
  std::byte* p = m_data.data() + i * pixelTypeSize(m_type);
  // NaN must not turn into an arbitrary integer: it maps to 0.
  const float clamped = std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f);
  switch (m_type) {
    case PixelType::U8: *p = std::byte(std::uint8_t(std::lround(clamped * 255.0f))); break;
    case PixelType::U16: {
      const auto v = std::uint16_t(std::lround(clamped * 65535.0f));
      std::memcpy(p, &v, 2);
      break;
    }
    case PixelType::F32: std::memcpy(p, &value, 4); break;
  }
}

namespace {
/// In one tight loop: through at()/set() a 1024² RGB map took 30 ms.
template <typename T>
void quantizeInto(std::span<const float> in, std::span<T> out, float scale) {
  if (in.size() != out.size()) fail(ErrorKind::Internal, "quantize: {} values into room for {}", in.size(), out.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    const float v = in[i];
    const float clamped = v >= 0.0f ? (v <= 1.0f ? v : 1.0f) : 0.0f;  // NaN fails both tests: 0
    // scaled + 0.5 is exact in double (scaled < 2^16), so truncating rounds half up like lround.
    out[i] = T(double(clamped * scale) + 0.5);
  }
}
}  // namespace

void quantize(std::span<const float> in, std::span<std::uint8_t> out) { quantizeInto(in, out, 255.0f); }
void quantize(std::span<const float> in, std::span<std::uint16_t> out) { quantizeInto(in, out, 65535.0f); }

Image Image::converted(PixelType type) const {
  if (type == m_type) return *this;
  Image out(m_width, m_height, m_channels, type);
  if (m_type == PixelType::F32 && type == PixelType::U8) {
    quantize(pixels<float>(), out.pixels<std::uint8_t>());
    return out;
  }
  if (m_type == PixelType::F32 && type == PixelType::U16) {
    quantize(pixels<float>(), out.pixels<std::uint16_t>());
    return out;
  }
  for (int y = 0; y < m_height; ++y)
    for (int x = 0; x < m_width; ++x)
      for (int c = 0; c < m_channels; ++c) out.set(x, y, c, at(x, y, c));
  return out;
}

Image Image::withChannels(int channels) const {
  if (channels == m_channels) return *this;
  Image out(m_width, m_height, channels, m_type);
  for (int y = 0; y < m_height; ++y) {
    for (int x = 0; x < m_width; ++x) {
      float rgba[4] = {0, 0, 0, 1};
      if (m_channels <= 2) {
        rgba[0] = rgba[1] = rgba[2] = at(x, y, 0);
        if (m_channels == 2) rgba[3] = at(x, y, 1);
      } else {
        for (int c = 0; c < m_channels; ++c) rgba[c] = at(x, y, c);
      }
      if (channels == 1) {
        out.set(x, y, 0, m_channels <= 2 ? rgba[0] : 0.2126f * rgba[0] + 0.7152f * rgba[1] + 0.0722f * rgba[2]);
      } else if (channels == 2) {
        out.set(x, y, 0, m_channels <= 2 ? rgba[0] : 0.2126f * rgba[0] + 0.7152f * rgba[1] + 0.0722f * rgba[2]);
        out.set(x, y, 1, rgba[3]);
      } else {
        for (int c = 0; c < channels; ++c) out.set(x, y, c, rgba[c]);
      }
    }
  }
  return out;
}

void Image::flipVertical() {
  const std::size_t row = rowBytes();
  std::vector<std::byte> tmp(row);
  for (int y = 0; y < m_height / 2; ++y) {
    std::byte* a = m_data.data() + std::size_t(y) * row;
    std::byte* b = m_data.data() + std::size_t(m_height - 1 - y) * row;
    std::memcpy(tmp.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, tmp.data(), row);
  }
}

ImageDifference compareImages(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height()) {
    fail(ErrorKind::Usage, "cannot compare a {}x{} image with a {}x{} one", a.width(), a.height(), b.width(),
         b.height());
  }
  const int channels = std::min(a.channels(), b.channels());
  ImageDifference d;
  d.visual = Image(a.width(), a.height(), 3, PixelType::U8);
  double sum = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      double pixelMax = 0;
      for (int c = 0; c < channels; ++c) {
        const double diff = std::abs(double(a.at(x, y, c)) - double(b.at(x, y, c)));
        sum += diff;
        pixelMax = std::max(pixelMax, diff);
        if (c < 3) d.visual.set(x, y, c, float(diff * 8.0));
      }
      if (channels < 3)
        for (int c = channels; c < 3; ++c) d.visual.set(x, y, c, float(pixelMax * 8.0));
      d.maxAbs = std::max(d.maxAbs, pixelMax);
      if (pixelMax > 1.0 / 255.0 + 1e-6) ++d.differingPixels;
    }
  }
  d.meanAbs = sum / double(a.pixelCount() * std::size_t(channels));
  return d;
}

}  // namespace glint
