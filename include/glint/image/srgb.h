#pragma once
// glint/image/srgb.h — the sRGB transfer function (IEC 61966-2-1), the one implementation
// glint's CPU code uses: display encoding of linear light (image/envmap.h's displayEncode,
// `glint post` on float images) and decoding of 8- and 16-bit colour to linear
// (render/env's equirect upload). The shaders that encode on the GPU include the one GLSL
// copy, shaders/common/srgb.glsl, with the same branch point.
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

/// The transfer function extended past 0..1 (light above display white in an HDR image,
/// and negative values, mirrored): monotonic, and srgbDecodeExtended undoes it exactly up to
/// float rounding. `glint post` encodes a float image this way so it can decode the result.
inline float srgbEncodeExtended(float linear) {
  return linear < 0.0f ? -srgbEncode(-linear) : srgbEncode(linear);
}
inline float srgbDecodeExtended(float encoded) {
  return encoded < 0.0f ? -srgbDecode(-encoded) : srgbDecode(encoded);
}

/// An F32 image's colour channels (R, G, B, or gray) through `f`; alpha unchanged.
template <class F>
Image mapColour(Image image, F f) {
  const int colour = image.channels() >= 3 ? 3 : 1;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < colour; ++c) image.set(x, y, c, f(image.at(x, y, c)));
  return image;
}

/// Linear light (F32) encoded without clamping (srgbEncodeExtended): values above 1 stay
/// above 1, so decoding the result gives them back.
inline Image srgbEncodedExtended(Image image) { return mapColour(std::move(image), srgbEncodeExtended); }
/// Encoded values (any type; the result is F32) back to linear light (srgbDecodeExtended).
inline Image srgbDecoded(const Image& image) {
  return mapColour(image.type() == PixelType::F32 ? image : image.converted(PixelType::F32), srgbDecodeExtended);
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
