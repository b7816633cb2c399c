#version 450 core
#include "common/srgb.glsl"
// The renderer's colour buffer (sRGB: texel fetches decode to linear) into the frame's
// target, encoded to sRGB by hand (the target is a plain RGBA8 buffer or the window),
// alpha 1. uView 1: WWDC 2003 session 212's destination-alpha view — the dim factor for every light,
// 1 − Σ w: white where no light reaches, darker where more light would be taken away.
layout(binding = 0) uniform sampler2D uColor;
layout(binding = 1) uniform sampler2D uWeights;
uniform ivec2 uOrigin;
uniform int uView;
uniform float uColorScale;  // the colour buffer holds linear light × this (scene.frag)
in vec2 vUv;
layout(location = 0) out vec4 fragColor;


void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - uOrigin;
  if (uView == 1) {
    vec4 w = texelFetch(uWeights, p, 0);
    fragColor = vec4(srgbEncode(vec3(1.0 - (w.x + w.y + w.z + w.w))), 1.0);
  } else {
    fragColor = vec4(srgbEncode(texelFetch(uColor, p, 0).rgb / uColorScale), 1.0);
  }
}
