#version 450 core
// Blinn-Phong lighting by one point light, split into the terms shadow techniques
// need: ambient is what a shadowed pixel keeps; diffuse + specular ("direct") is what
// a shadow takes away. The WWDC 2001 talk's multi-pass method draws ambient everywhere, then
// adds direct only where the stencil says lit (the WWDC 2001 talk).
//
// SHADOW_MAP      visibility from a depth map seen from the light (shadows/map)
// PROJECTED_MAP   with SHADOW_MAP: show the map's depth projected from the light instead
// PLANAR_SHADOW   visibility from a planar shadow texture on the ground (shadows/planar)
#include "shadows/lighting.glsl"

in vec3 vWorldPos;
in vec3 vNormal;
layout(location = 0) out vec4 fragColor;

#ifdef SHADOW_MAP
#include "shadows/shadow_map.glsl"
#endif
#ifdef PLANAR_SHADOW
// The ground's shadow picture, rendered from above (white lit, dark shadowed).
layout(binding = 1) uniform sampler2D uPlanarShadow;
uniform mat4 uPlanarTexMatrix;  // world → shadow texture coordinates (xy) on the ground
#endif

void main() {
  float visibility = 1.0;
#ifdef SHADOW_MAP
  visibility = shadowMapVisibility(vWorldPos);
#endif
#ifdef PLANAR_SHADOW
  if (uGround) visibility = texture(uPlanarShadow, (uPlanarTexMatrix * vec4(vWorldPos, 1.0)).xy).r;
#endif
#if defined(SHADOW_MAP) && defined(PROJECTED_MAP)
  fragColor = vec4(projectedMapColor(vWorldPos), 1.0);
  return;
#endif
  fragColor = shade(vWorldPos, vNormal, visibility);
}
