#version 450 core
// A sphere map shown as an image, centred in the viewport. Wasted texels (alpha 0) are
// black, as in the WWDC 2001 talk's picture. With HEMISPHERES the front half of the environment
// (the disk of radius 1/√2) is tinted green, the back half (the ring) red and the wasted
// corners hatched, to show the ≈40 / 40 / 20 split.
#include "env/envmap.glsl"

in vec2 vUv;
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform sampler2D uSphereMap;
uniform float uAspect;
uniform vec3 uBackground = vec3(0.12, 0.13, 0.15);

void main() {
  vec2 p = vUv;
  if (uAspect > 1.0) p.x = (p.x - 0.5) * uAspect + 0.5;
  else p.y = (p.y - 0.5) / uAspect + 0.5;
  if (any(lessThan(p, vec2(0.0))) || any(greaterThan(p, vec2(1.0)))) {
    fragColor = vec4(uBackground, 1.0);
    return;
  }
  vec4 texel = textureLod(uSphereMap, p, 0.0);
  vec3 c = texel.rgb;
#ifdef HEMISPHERES
  bool inside;
  vec3 r = sphereMapDirection(p, inside);
  if (texel.a < 0.5) {
    float stripe = step(0.5, fract((gl_FragCoord.x + gl_FragCoord.y) / 12.0));
    c = mix(vec3(0.25, 0.05, 0.3), vec3(0.6, 0.2, 0.7), stripe);
  } else {
    c = mix(c, r.z >= 0.0 ? vec3(0.2, 0.9, 0.3) : vec3(0.95, 0.25, 0.2), 0.45);
  }
#endif
  fragColor = vec4(c, 1.0);
}
