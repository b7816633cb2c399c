#include "glint/image/normalmap.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/core/text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace glint {

vec3 heightNormal(float north, float south, float east, float west, const NormalMapOptions& options) {
  if (options.formula == NormalFormula::Slide) {
    // The slide, scaled: d = vec3(e − w, s − n, 0); d.z = 1 − sqrt(d·d); normalize(d).
    vec3 d{east - west, south - north, 0.0f};
    d *= 0.5f * options.scale;
    d.z = 1.0f - std::sqrt(d.x * d.x + d.y * d.y);
    return glm::normalize(d);
  }
  // Central differences over two texels: ∂h/∂x ≈ (e − w)/2, ∂h/∂y ≈ (n − s)/2 (north = +y),
  // heights in texel units after × scale. The normal of z = h(x, y) is (−∂h/∂x, −∂h/∂y, 1).
  const vec3 d{0.5f * options.scale * (west - east), 0.5f * options.scale * (south - north), 1.0f};
  return glm::normalize(d);
}

Image heightFromImage(const Image& image, bool* usedLuminance) {
  if (image.empty()) fail(ErrorKind::Input, "the height map is empty");
  const bool colour = image.channels() >= 3;
  if (usedLuminance) *usedLuminance = colour;
  if (image.channels() == 1) return image;
  return image.withChannels(1);  // 2 channels: gray + alpha → gray; RGB(A) → Rec.709 luminance
}

NormalFormula parseNormalFormula(std::string_view name) {
  if (name == "gradient") return NormalFormula::Gradient;
  if (name == "slide") return NormalFormula::Slide;
  fail(ErrorKind::Usage, "formula must be gradient or slide, got '{}'", printable(name));
}

namespace {
/// A colour input that already decodes to unit vectors pointing out of the surface is almost
/// certainly a normal map: running it through again gives nonsense.
bool looksLikeNormalMap(const Image& image) {
  if (image.channels() < 3) return false;
  bool colourful = false;
  for (int y = 0; y < image.height() && !colourful; y += std::max(1, image.height() / 64))
    for (int x = 0; x < image.width() && !colourful; x += std::max(1, image.width() / 64))
      colourful = std::abs(image.at(x, y, 0) - image.at(x, y, 2)) > 0.1f;
  if (!colourful) return false;
  try {
    prepareNormalMap(image, "input");
    return true;
  } catch (const Error&) {
    return false;
  }
}
}  // namespace

void checkHeightMap(const Image& input, const NormalMapOptions& options, std::string_view what) {
  if (!std::isfinite(options.scale)) fail(ErrorKind::Usage, "the normal map's scale must be a finite number");
  if (input.empty()) fail(ErrorKind::Input, "the height map {} is empty", what);
  if (input.type() == PixelType::F32) {
    const auto px = input.pixels<float>();
    const int c = input.channels();
    for (std::size_t i = 0; i < px.size(); ++i)
      if (!std::isfinite(px[i]))
        fail(ErrorKind::Input, "the height map {} has a value that is not a number at texel ({}, {}) channel {}: {}", what,
             i / std::size_t(c) % std::size_t(input.width()), i / std::size_t(c) / std::size_t(input.width()), i % std::size_t(c),
             px[i]);
  }
  if (input.channels() >= 3) {
    log::warn("{} has {} channels; using its luminance (0.2126 R + 0.7152 G + 0.0722 B) as the height", what, input.channels());
    if (looksLikeNormalMap(input))
      log::warn("{} already looks like a normal map (its colours decode to unit vectors pointing out); the result "
                "will not mean much", what);
  } else if (input.channels() == 2) {
    log::info("{} has gray + alpha; using the gray channel as the height", what);
  }
}

Image heightToNormalMap(const Image& input, const NormalMapOptions& options) {
  if (!std::isfinite(options.scale)) fail(ErrorKind::Usage, "normal map scale must be finite");
  const Image height = heightFromImage(input).converted(PixelType::F32);
  const int w = height.width(), h = height.height();
  const auto px = height.pixels<float>();
  auto fetch = [&](int x, int y) {
    if (options.wrap) {
      x = ((x % w) + w) % w;
      y = ((y % h) + h) % h;
    } else {
      x = std::clamp(x, 0, w - 1);
      y = std::clamp(y, 0, h - 1);
    }
    return px[std::size_t(y) * std::size_t(w) + std::size_t(x)];
  };
  Image out(w, h, 4, PixelType::U8);
  auto dst = out.pixels<std::uint8_t>();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // Row 0 is the top of the picture: north is y − 1.
      const vec3 c = encodeNormal(heightNormal(fetch(x, y - 1), fetch(x, y + 1), fetch(x + 1, y), fetch(x - 1, y), options));
      std::uint8_t* p = &dst[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
      for (int k = 0; k < 3; ++k) p[k] = std::uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
      p[3] = 255;
    }
  }
  return out;
}

Image prepareNormalMap(const Image& image, std::string_view name, NormalSpace space, NormalMapReport* report) {
  if (image.empty()) fail(ErrorKind::Input, "{}: the normal map is empty", name);
  if (image.channels() == 1) {
    fail(ErrorKind::Input,
         "{}: one channel — this looks like a height map, not a normal map (make one with `glint normalmap {} -o "
         "normal.png`)",
         name, name);
  }
  NormalMapReport r;
  const int w = image.width(), h = image.height();
  // Signed float maps store n itself; everything else stores (n + 1) / 2.
  bool isSigned = false;
  if (image.type() == PixelType::F32) {
    for (float v : image.pixels<float>())
      if (v < -1.0f / 512.0f) isSigned = true;
  }
  Image out(w, h, 4, PixelType::U8);
  double lengthSum = 0;
  std::size_t outward = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      vec3 n;
      if (image.channels() == 2) {
        const vec2 xy = isSigned ? vec2(image.at(x, y, 0), image.at(x, y, 1))
                                 : vec2(image.at(x, y, 0), image.at(x, y, 1)) * 2.0f - 1.0f;
        n = vec3(xy, std::sqrt(std::max(0.0f, 1.0f - glm::dot(xy, xy))));
      } else {
        n = vec3(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
        if (!isSigned) n = decodeNormal(n);
      }
      lengthSum += double(glm::length(n));
      if (n.z > 0.0f) ++outward;
      const vec3 c = encodeNormal(glm::clamp(n, -1.0f, 1.0f));
      for (int k = 0; k < 3; ++k) out.set(x, y, k, c[k]);
      out.set(x, y, 3, 1.0f);
    }
  }
  const double count = double(image.pixelCount());
  r.meanLength = lengthSum / count;
  r.outwardFraction = double(outward) / count;
  if (image.channels() == 2) r.conversion = "two channels (x, y): z reconstructed as sqrt(1 − x² − y²)";
  else if (isSigned) r.conversion = "signed float encoding (n itself): re-encoded as (n + 1) / 2";
  else if (image.type() != PixelType::U8) r.conversion = fmt::format("{} → 8-bit", pixelTypeName(image.type()));
  if (std::abs(r.meanLength - 1.0) > 0.15) {
    fail(ErrorKind::Input,
         "{}: decoded normals have mean length {:.2f}, expected 1 — not a (n + 1) / 2 encoded normal map (a colour "
         "texture? a height map saved as RGB? an sRGB-converted map?)",
         name, r.meanLength);
  }
  if (space == NormalSpace::Tangent && r.outwardFraction < 0.9) {
    fail(ErrorKind::Input,
         "{}: only {:.0f}% of the normals point out of the surface (blue ≥ 0.5) — not a tangent-space normal map "
         "(an object-space map? channels in another order?)",
         name, 100.0 * r.outwardFraction);
  }
  if (report) *report = r;
  return out;
}

Image withHeightAlpha(const Image& normals, const Image& height) {
  // RGB, the three components of the normal; RGBA carrying the input's alpha when it has one.
  const bool alpha = height.channels() == 2 || height.channels() == 4;
  Image written = normals.withChannels(alpha ? 4 : 3);
  if (alpha) {
    for (int y = 0; y < height.height(); ++y)
      for (int x = 0; x < height.width(); ++x) written.set(x, y, 3, height.at(x, y, height.channels() - 1));
  }
  return written;
}

}  // namespace glint
