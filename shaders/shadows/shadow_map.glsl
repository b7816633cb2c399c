// Shadow-map lookup (the OpenGL III lecture: "shadow maps from the light's view depth").
//
// The light's depth texture is sampled through a sampler2DShadow: the hardware
// compares the reference depth with the stored one (GL_TEXTURE_COMPARE_MODE) and,
// with GL_LINEAR filtering, blends the results of the 2×2 nearest texels, so one tap
// is already a small percentage-closer filter. PCF widens it to (2r+1)² taps.
//
// Bias. Acne is fought where it starts, when the map is drawn: slope-scaled polygon
// offset pushes each stored depth back in proportion to how steeply the surface is
// seen from the light (render/shadows/shadow_map.h). That covers the texels one tap
// reads (the hardware's 2×2, at most a texel away), not a wider footprint: a PCF tap k
// texels away reads the same surface k texels further along, which on a surface tilted
// to the light is nearer the light by k × the depth slope — k = 2 taps of a 5×5 kernel
// shadowed the lit floor in moiré bands. So each tap compares against the receiver's
// own plane at the tap: "receiver plane depth bias" (Isidoro, "Shadow Mapping: GPU-based
// Tips and Techniques", GDC 2006). Light-space depth is affine in the map's (u, v) over
// a plane, so the plane's depth gradient d(depth)/d(u, v), solved from the screen-space
// derivatives of the light-space coordinate, gives every tap's reference depth exactly;
// the polygon offset is then left with one tap's worth, whatever the radius.
layout(binding = 0) uniform sampler2DShadow uShadowMap;
uniform mat4 uLightViewProj;  // world → the light's clip space
uniform int uPcfRadius;       // 0: one (hardware 2×2) tap; r: (2r+1)² taps
uniform bool uReceiverPlane;  // false: every tap compares the pixel's own depth (acne, for the lesson)

// d(depth)/d(u, v) of the receiver's plane from the screen derivatives of (u, v, depth):
// the 2×2 system [dx.xy; dy.xy] · g = (dx.z, dy.z). Zero where the plane is seen edge-on
// (from the light or the camera) and the system has no stable answer.
vec2 receiverPlaneDepthGradient(vec3 dx, vec3 dy) {
  float det = dx.x * dy.y - dx.y * dy.x;
  if (abs(det) < 1e-12) return vec2(0.0);
  return vec2(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det;
}

float shadowMapVisibility(vec3 p) {
  vec4 clip = uLightViewProj * vec4(p, 1.0);
  vec3 coord = clip.xyz / clip.w * 0.5 + 0.5;
  // Derivatives first: they need all four pixels of the 2×2 quad in the same flow.
  vec2 gradient = receiverPlaneDepthGradient(dFdx(coord), dFdy(coord));
  if (!uReceiverPlane) gradient = vec2(0.0);
  // Behind the light or outside its frustum: the map knows nothing there; call it lit.
  if (clip.w <= 0.0) return 1.0;
  if (any(lessThan(coord, vec3(0.0))) || any(greaterThan(coord, vec3(1.0)))) return 1.0;
  vec2 texel = 1.0 / vec2(textureSize(uShadowMap, 0));
  float sum = 0.0;
  for (int y = -uPcfRadius; y <= uPcfRadius; ++y)
    for (int x = -uPcfRadius; x <= uPcfRadius; ++x) {
      vec2 offset = vec2(x, y) * texel;
      sum += texture(uShadowMap, vec3(coord.xy + offset, coord.z + dot(gradient, offset)));
    }
  float side = float(2 * uPcfRadius + 1);
  return sum / (side * side);
}

// The lecture's "projected shadow map": the stored depth (linearised between the
// light's near and far planes) cast onto the scene like a slide; blue outside the map.
layout(binding = 2) uniform sampler2D uShadowDepth;  // the same texture, no comparison
uniform vec2 uLightNearFar;

vec3 projectedMapColor(vec3 p) {
  vec4 clip = uLightViewProj * vec4(p, 1.0);
  vec3 coord = clip.xyz / clip.w * 0.5 + 0.5;
  if (clip.w <= 0.0 || any(lessThan(coord.xy, vec2(0.0))) || any(greaterThan(coord.xy, vec2(1.0))))
    return vec3(0.1, 0.15, 0.35);
  float ndc = 2.0 * texture(uShadowDepth, coord.xy).r - 1.0;
  float n = uLightNearFar.x, f = uLightNearFar.y;
  float eye = 2.0 * n * f / (f + n - ndc * (f - n));
  return vec3((eye - n) / (f - n));
}
