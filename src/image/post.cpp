#include "glint/image/post.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cmath>

namespace glint {

namespace {
using Matrix3 = std::array<std::array<double, 3>, 3>;

Matrix3 invert(const Matrix3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  Matrix3 r{};
  r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}

// 8-bit value of channel c at (x, y), edges repeated.
int texel(const Image& image, int x, int y, int c) {
  x = std::clamp(x, 0, image.width() - 1);
  y = std::clamp(y, 0, image.height() - 1);
  const auto p = image.pixels<std::uint8_t>();
  return p[(std::size_t(y) * std::size_t(image.width()) + std::size_t(x)) * 4 + std::size_t(c)];
}

float lumaAt(const Image& image, int x, int y) {
  // In float, in this order: the shader computes dot(rgb, weights) in float too, and the
  // test tolerance (one 8-bit step) dwarfs the difference of any evaluation order.
  return postLuma(vec3(float(texel(image, x, y, 0)), float(texel(image, x, y, 1)), float(texel(image, x, y, 2))) /
                  255.0f);
}

Image outputLike(const Image& input) { return Image(input.width(), input.height(), 4, PixelType::F32); }
}  // namespace

Image postInput(const Image& image) {
  if (image.type() != PixelType::U8) {
    fail(ErrorKind::Usage, "post effects take 8-bit images, got {} (convert first)", pixelTypeName(image.type()));
  }
  if (image.channels() == 4) return image;
  if (image.channels() == 3) return image.withChannels(4);
  fail(ErrorKind::Usage, "post effects take RGB or RGBA images, got {} channel(s)", image.channels());
}

Image quantizeToU8(const Image& reference) { return reference.converted(PixelType::U8); }

// ---------------------------------------------------------------------------
// Sepia

std::array<std::array<double, 3>, 3> yiqFromRgb() {
  return {{{0.299, 0.587, 0.114}, {0.5959, -0.2746, -0.3213}, {0.2115, -0.5227, 0.3112}}};
}

std::array<std::array<double, 3>, 3> rgbFromYiq() {
  static const Matrix3 inverse = invert(yiqFromRgb());
  return inverse;
}

dvec3 sepiaOffset(const SepiaOptions& options) {
  const Matrix3 m = rgbFromYiq();
  dvec3 c;
  for (int row = 0; row < 3; ++row) c[row] = m[std::size_t(row)][1] * options.i + m[std::size_t(row)][2] * options.q;
  return c;
}

dvec3 sepiaPixel(dvec3 rgb, const SepiaOptions& options) {
  // The full round trip, as WWDC 2003 session 212 describes it: RGB → YIQ (only Y is needed), replace I
  // and Q, YIQ → RGB. Written as matrices, not as the shader's dot-and-add, so the test
  // compares two different evaluations.
  const Matrix3 forward = yiqFromRgb();
  const double y = forward[0][0] * rgb.r + forward[0][1] * rgb.g + forward[0][2] * rgb.b;
  const Matrix3 inverse = rgbFromYiq();
  const double yiq[3] = {y, options.i, options.q};
  dvec3 out, gray;
  for (int row = 0; row < 3; ++row) {
    out[row] = 0.0;
    for (int col = 0; col < 3; ++col) out[row] += inverse[std::size_t(row)][std::size_t(col)] * yiq[col];
    gray[row] = inverse[std::size_t(row)][0] * y;  // = y: the first column is (1, 1, 1)
  }
  // Shorten the chroma offset so every channel stays in [0, 1]: luma unchanged.
  double t = 1.0;
  for (int row = 0; row < 3; ++row) {
    const double c = out[row] - gray[row];
    if (c > 0.0) t = std::min(t, (1.0 - gray[row]) / c);
    if (c < 0.0) t = std::min(t, gray[row] / -c);
  }
  t = std::max(t, 0.0);
  return gray + t * (out - gray);
}

Image sepiaReference(const Image& rgba, const SepiaOptions& options) {
  const Image in = postInput(rgba);
  Image out = outputLike(in);
  for (int y = 0; y < in.height(); ++y) {
    for (int x = 0; x < in.width(); ++x) {
      const dvec3 rgb(texel(in, x, y, 0) / 255.0, texel(in, x, y, 1) / 255.0, texel(in, x, y, 2) / 255.0);
      const dvec3 s = sepiaPixel(rgb, options);
      for (int c = 0; c < 3; ++c) out.set(x, y, c, float(s[c]));
      out.set(x, y, 3, in.at(x, y, 3));
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// Sobel and edges

vec2 sobelGradient(const Image& rgba, int x, int y) {
  float l[3][3];
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) l[dy + 1][dx + 1] = lumaAt(rgba, x + dx, y + dy);
  const float gx = (l[0][2] + 2.0f * l[1][2] + l[2][2]) - (l[0][0] + 2.0f * l[1][0] + l[2][0]);
  const float gy = (l[2][0] + 2.0f * l[2][1] + l[2][2]) - (l[0][0] + 2.0f * l[0][1] + l[0][2]);
  return {gx, gy};
}

Image sobelReference(const Image& rgba, const SobelOptions& options) {
  const Image in = postInput(rgba);
  Image out = outputLike(in);
  const float s = options.scale;
  for (int y = 0; y < in.height(); ++y) {
    for (int x = 0; x < in.width(); ++x) {
      const vec2 g = sobelGradient(in, x, y);
      float v = 0.0f;
      switch (options.output) {
        case SobelOutput::Horizontal: v = std::min(1.0f, s * std::abs(g.y)); break;
        case SobelOutput::Vertical: v = std::min(1.0f, s * std::abs(g.x)); break;
        case SobelOutput::Magnitude: v = std::min(1.0f, s * std::sqrt(g.x * g.x + g.y * g.y)); break;
        case SobelOutput::SignedX: v = std::clamp(0.5f + 0.5f * s * g.x, 0.0f, 1.0f); break;
        case SobelOutput::SignedY: v = std::clamp(0.5f + 0.5f * s * g.y, 0.0f, 1.0f); break;
      }
      for (int c = 0; c < 3; ++c) out.set(x, y, c, v);
      out.set(x, y, 3, in.at(x, y, 3));
    }
  }
  return out;
}

Image edgesReference(const Image& rgba, const EdgesOptions& options) {
  const Image in = postInput(rgba);
  Image out = outputLike(in);
  for (int y = 0; y < in.height(); ++y) {
    for (int x = 0; x < in.width(); ++x) {
      const vec2 g = sobelGradient(in, x, y);
      const float e = std::clamp(options.scale * (std::sqrt(g.x * g.x + g.y * g.y) - options.threshold), 0.0f, 1.0f);
      for (int c = 0; c < 3; ++c) out.set(x, y, c, in.at(x, y, c) * (1.0f - e));
      out.set(x, y, 3, in.at(x, y, 3));
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// Kuwahara

KuwaharaReference kuwaharaReference(const Image& rgba, const KuwaharaOptions& options) {
  const int s = options.size;
  if (s < 2 || s > 8) fail(ErrorKind::Usage, "kuwahara: quadrant size must be 2..8, got {}", s);
  const Image in = postInput(rgba);
  const int w = in.width(), h = in.height();
  KuwaharaReference r{outputLike(in), std::vector<std::uint8_t>(in.pixelCount()),
                      std::vector<std::uint8_t>(in.pixelCount())};
  const std::int64_t n = std::int64_t(s) * s;
  // Quadrant q's top-left corner relative to p (x, y): see the header's table.
  const ivec2 corner[4] = {{-(s - 1), -(s - 1)}, {0, -(s - 1)}, {-(s - 1), 0}, {0, 0}};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::int64_t sums[4][3] = {}, d[4] = {};
      for (int q = 0; q < 4; ++q) {
        std::int64_t squares[3] = {};
        for (int j = 0; j < s; ++j) {
          for (int i = 0; i < s; ++i) {
            for (int c = 0; c < 3; ++c) {
              const std::int64_t k = texel(in, x + corner[q].x + i, y + corner[q].y + j, c);
              sums[q][c] += k;
              squares[c] += k * k;
            }
          }
        }
        for (int c = 0; c < 3; ++c) d[q] += n * squares[c] - sums[q][c] * sums[q][c];
      }
      const std::int64_t best = *std::min_element(d, d + 4);
      int chosen = -1;
      std::uint8_t tied = 0;
      for (int q = 0; q < 4; ++q) {
        if (d[q] != best) continue;
        tied |= std::uint8_t(1u << q);
        if (chosen < 0) chosen = q;
      }
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      r.chosen[i] = std::uint8_t(chosen);
      r.tied[i] = tied;
      for (int c = 0; c < 3; ++c) r.image.set(x, y, c, float(double(sums[chosen][c]) / double(n * 255)));
      r.image.set(x, y, 3, in.at(x, y, 3));
    }
  }
  return r;
}

}  // namespace glint
