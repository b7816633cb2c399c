#include "glint/image/metrics.h"

#include "glint/core/error.h"

#include <cmath>
#include <cstdint>

namespace glint {
namespace {
Region resolve(const Image& image, Region r) {
  if (r.empty()) return {0, 0, image.width(), image.height()};
  if (r.x0 < 0 || r.y0 < 0 || r.x1 > image.width() || r.y1 > image.height()) {
    fail(ErrorKind::Usage, "region [{},{})x[{},{}) lies outside the {}x{} image", r.x0, r.x1, r.y0, r.y1,
         image.width(), image.height());
  }
  return r;
}

void requireSameSize(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height()) {
    fail(ErrorKind::Usage, "images differ in size: {}x{} vs {}x{}", a.width(), a.height(), b.width(), b.height());
  }
}
}  // namespace

float luminance(const Image& image, int x, int y) {
  if (image.channels() < 3) return image.at(x, y, 0);
  return 0.2126f * image.at(x, y, 0) + 0.7152f * image.at(x, y, 1) + 0.0722f * image.at(x, y, 2);
}

Image boxDownsample(const Image& image, int factor) {
  if (factor <= 0 || image.width() % factor || image.height() % factor) {
    fail(ErrorKind::Usage, "cannot downsample {}x{} by {}", image.width(), image.height(), factor);
  }
  Image out(image.width() / factor, image.height() / factor, image.channels(), PixelType::F32);
  const float norm = 1.0f / float(factor * factor);
  if (image.type() == PixelType::U8) {
    // Fast path for readbacks (a 16×16-supersampled truth is millions of pixels).
    const auto src = image.pixels<std::uint8_t>();
    auto dst = out.pixels<float>();
    const std::size_t ch = std::size_t(image.channels()), w = std::size_t(image.width());
    for (std::size_t y = 0; y < std::size_t(image.height()); ++y)
      for (std::size_t x = 0; x < w; ++x)
        for (std::size_t c = 0; c < ch; ++c)
          dst[((y / std::size_t(factor)) * std::size_t(out.width()) + x / std::size_t(factor)) * ch + c] +=
              float(src[(y * w + x) * ch + c]) * (norm / 255.0f);
    return out;
  }
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      for (int c = 0; c < image.channels(); ++c) {
        float sum = 0.0f;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i) sum += image.at(x * factor + i, y * factor + j, c);
        out.set(x, y, c, sum * norm);
      }
    }
  }
  return out;
}

double rmsError(const Image& a, const Image& b, Region region) {
  requireSameSize(a, b);
  const Region r = resolve(a, region);
  double sum = 0.0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const double d = double(luminance(a, x, y)) - double(luminance(b, x, y));
      sum += d * d;
    }
  return std::sqrt(sum / (double(r.x1 - r.x0) * double(r.y1 - r.y0)));
}

double sharpness(const Image& image, Region region) {
  const Region r = resolve(image, region);
  double sum = 0.0;
  std::size_t n = 0;
  for (int y = r.y0; y < r.y1 - 1; ++y)
    for (int x = r.x0; x < r.x1 - 1; ++x) {
      const double l = luminance(image, x, y);
      const double dx = luminance(image, x + 1, y) - l;
      const double dy = luminance(image, x, y + 1) - l;
      sum += std::sqrt(dx * dx + dy * dy);
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}

double temporalFlicker(std::span<const Image> frames, std::span<const Image> truth, Region region) {
  if (frames.size() < 2 || frames.size() != truth.size()) {
    fail(ErrorKind::Usage, "flicker needs two or more frames and as many reference frames ({} vs {})", frames.size(),
         truth.size());
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    requireSameSize(frames[i], frames[0]);
    requireSameSize(truth[i], frames[0]);
  }
  const Region r = resolve(frames[0], region);
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i + 1 < frames.size(); ++i)
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const double df = double(luminance(frames[i + 1], x, y)) - luminance(frames[i], x, y);
        const double dt = double(luminance(truth[i + 1], x, y)) - luminance(truth[i], x, y);
        sum += (df - dt) * (df - dt);
        ++n;
      }
  return std::sqrt(sum / double(n));
}

}  // namespace glint
