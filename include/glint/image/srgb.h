#pragma once
// glint/image/srgb.h — the sRGB transfer function (IEC 61966-2-1), the one implementation
// glint's CPU code uses: display encoding of linear light (image/envmap.h's displayEncode,
// `glint post` on float images) and decoding of 8- and 16-bit colour to linear
// (render/env's equirect upload). The shaders that encode on the GPU
// (shaders/env/envmap.glsl, shaders/pipedream/present.frag) write the same formula.
//
/// ```cpp
/// const float encoded = glint::srgbEncode(0.18f);  // middle gray: 0.46
/// const float linear = glint::srgbDecode(encoded);  // 0.18 again, within float rounding
/// glint::Image light(2, 2, 4, glint::PixelType::F32);
/// light.set(0, 0, 0, linear);
/// const glint::Image frame = glint::srgbEncoded(light);  // F32, encoded values, clamped to 0..1
/// ```

#include "glint/image/image.h"

#include <algorithm>
#include <cmath>

namespace glint {

/// Linear light in [0, 1] → the sRGB-encoded value (a linear segment below 0.0031308).
inline float srgbEncode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

/// An sRGB-encoded value in [0, 1] → linear light.
inline float srgbDecode(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

/// An image of linear light (F32: EXR, HDR) with its colour (R, G, B, or gray) clamped to
/// 0..1 and encoded; alpha unchanged, the type kept.
inline Image srgbEncoded(Image image) {
  const int colour = image.channels() >= 3 ? 3 : 1;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < colour; ++c) image.set(x, y, c, srgbEncode(std::clamp(image.at(x, y, c), 0.0f, 1.0f)));
  return image;
}

}  // namespace glint
