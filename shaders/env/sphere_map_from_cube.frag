#version 450 core
// Cube map → sphere map (the WWDC 2001 talk: "sphere maps are usually generated from cube maps").
// Each texel shows the reflection off a mirror ball at its position, seen along −Z of
// the map's frame. Texels whose centre lies outside the ball are wasted: written black
// with alpha 0 (alpha = 1 marks used texels, so the wasted fraction can be counted).
// A texel near the rim covers a large solid angle, so it averages uSamples² lookups
// (those that hit the ball).
#include "env/envmap.glsl"

in vec2 vUv;
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform samplerCube uCube;
uniform mat3 uFrameToWorld;
uniform int uSize;
uniform int uSamples = 4;

void main() {
  bool centreInside;
  sphereMapDirection(vUv, centreInside);
  if (!centreInside) {
    fragColor = vec4(0.0);
    return;
  }
  vec3 sum = vec3(0.0);
  int hits = 0;
  for (int j = 0; j < uSamples; ++j) {
    for (int i = 0; i < uSamples; ++i) {
      vec2 st = vUv + ((vec2(i, j) + 0.5) / float(uSamples) - 0.5) / float(uSize);
      bool inside;
      vec3 r = sphereMapDirection(st, inside);
      if (inside) {
        sum += textureLod(uCube, uFrameToWorld * r, 0.0).rgb;
        ++hits;
      }
    }
  }
  fragColor = vec4(sum / float(max(hits, 1)), 1.0);
}
