// The sRGB transfer function (IEC 61966-2-1), the one GLSL copy: every shader that encodes
// includes this file. The CPU's is image/srgb.h (srgbEncode), with the same branch point
// (linear ≤ 0.0031308 takes the linear segment), so both write the same values. Include it
// once per shader (directly, or through env/envmap.glsl).
// Linear light in [0, 1] → sRGB-encoded values (clamped first).
vec3 srgbEncode(vec3 linear) {
  vec3 c = clamp(linear, 0.0, 1.0);
  return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, lessThanEqual(c, vec3(0.0031308)));
}
