#version 450 core
// DOT3 bump mapping with the texture-combiner arithmetic of the OpenGL spec, so this path
// and the fixed-function GL_COMBINE path render the same image (tests/bump/dot3_gl_test).
//   STAGE_LIGHT_VECTORS: the primary colour alone (the encoded light vectors)
//   STAGE_DOT_PRODUCT:   combiner stage 1, GL_DOT3_RGB(primary colour, normal map in unit 0)
//   (neither):           stage 1, then stage 2 GL_MODULATE(previous, base texture in unit 1)
// NORMALIZE_PER_PIXEL: the fix for interpolated light vectors being shorter than 1.

smooth in vec3 vLightColor;
in vec2 vUv;
layout(location = 0) out vec4 fragColor;

layout(binding = 0) uniform sampler2D uNormalMap;  // texture unit 0, as in the WWDC 2001 talk
layout(binding = 1) uniform sampler2D uBase;       // texture unit 1

// GL_DOT3_RGB: 4·Σ(a − ½)(b − ½), clamped to [0, 1] (OpenGL 1.3, table 3.20).
float combineDot3(vec3 a, vec3 b) {
  vec3 p = (a - 0.5) * (b - 0.5);
  return clamp(4.0 * (p.x + p.y + p.z), 0.0, 1.0);
}

void main() {
  vec3 primary = clamp(vLightColor, 0.0, 1.0);  // fixed function clamps colours too
#ifdef NORMALIZE_PER_PIXEL
  // Decode the interpolated colour back to a vector, restore unit length, encode again.
  // (2001 hardware did this with a "normalization cube map" looked up by the vector.)
  vec3 l = primary * 2.0 - 1.0;
  float len = length(l);
  primary = len > 0.0 ? l / len * 0.5 + 0.5 : vec3(0.5, 0.5, 1.0);
#endif
#if defined(STAGE_LIGHT_VECTORS)
  fragColor = vec4(primary, 1.0);
#elif defined(STAGE_DOT_PRODUCT)
  fragColor = vec4(vec3(combineDot3(primary, texture(uNormalMap, vUv).rgb)), 1.0);
#else
  float nDotL = combineDot3(primary, texture(uNormalMap, vUv).rgb);
  fragColor = vec4(vec3(nDotL) * texture(uBase, vUv).rgb, 1.0);
#endif
}
