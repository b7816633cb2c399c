#version 450 core
// Equirect → one cube face, drawn through a framebuffer object whose colour attachment
// is that face (level 0). Each texel averages uSamples × uSamples HDR lookups spread
// over its footprint before display encoding: one lookup per texel would alias where
// the lat-long image is denser than the face (towards the poles).
#include "env/envmap.glsl"

in vec2 vUv;  // (s, t) of this texel's centre: window row 0 is face row 0 (t ≈ 0)
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform sampler2D uEquirect;
uniform int uFace;
uniform int uSize;
uniform int uSamples = 2;
uniform float uExposure = 1.0;

void main() {
  vec3 sum = vec3(0.0);
  for (int j = 0; j < uSamples; ++j) {
    for (int i = 0; i < uSamples; ++i) {
      vec2 offset = (vec2(i, j) + 0.5) / float(uSamples) - 0.5;
      vec2 st = vUv + offset / float(uSize);
      // Level 0 explicitly: implicit derivatives jump at the u = 0/1 seam.
      sum += textureLod(uEquirect, equirectUv(cubeFaceDirection(uFace, st)), 0.0).rgb;
    }
  }
  fragColor = vec4(displayEncode(sum / float(uSamples * uSamples), uExposure), 1.0);
}
