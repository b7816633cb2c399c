#version 450 core
// The scene pass of WWDC 2003 session 212's Pipe Dream method, and the naive method's passes.
//
// uPass 0  WWDC 2003 session 212's pass: lit by the lights in uMask (the cut's light mask of this piece;
//          all lights for dynamic parts), colour in linear light (an sRGB framebuffer), and
//          in alpha the dim factor 1 − w₀; the second target gets w = (light i's term) / (all
//          light), the share of this pixel's light each light gives.
// uPass 1  ambient only (the naive method's first pass)
// uPass 2  light uLight only (the naive method's additive pass, where the stencil is 0)
// uPass 3  uEmissive, unlit (the light markers)
#include "pipedream/lighting.glsl"

uniform int uPass;
uniform int uMask;
uniform int uLight;
uniform vec3 uEmissive;
// The colour buffer holds linear light × uColorScale (1 / the brightest a pixel can be:
// render/pipedream/renderer.h's colorScale()), so its 8 bits clip nothing a shadow dims.
uniform float uColorScale;

in vec3 vWorld;
in vec3 vNormal;
in vec3 vAlbedo;
layout(location = 0) out vec4 fragColor;
layout(location = 1) out vec4 fragWeights;

void main() {
  fragWeights = vec4(0.0);
  if (uPass == 3) {
    fragColor = vec4(uEmissive * uColorScale, 1.0);
    return;
  }
  if (uPass == 1) {
    fragColor = vec4(vAlbedo * uAmbient * uColorScale, 1.0);
    return;
  }
  vec3 n = normalize(vNormal);
  if (uPass == 2) {
    fragColor = vec4(vAlbedo * lightTerm(uLight, vWorld, n) * uColorScale, 1.0);
    return;
  }
  vec4 terms = vec4(0.0);
  for (int i = 0; i < uLightCount; ++i)
    if (((uMask >> i) & 1) != 0) terms[i] = lightTerm(i, vWorld, n);
  float total = uAmbient + terms.x + terms.y + terms.z + terms.w;
  fragWeights = terms / total;
  fragColor = vec4(vAlbedo * total * uColorScale, 1.0 - fragWeights.x);
}
