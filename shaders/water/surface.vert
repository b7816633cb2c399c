#version 450 core
// The pool's surface: a grid in the XZ plane, lifted by the simulated height so the
// silhouette moves a little; the shading detail comes from the normal map per pixel.
#include "common/attributes.glsl"

uniform mat4 uViewProjection;
uniform float uHalfSize;
uniform float uDisplacement;            // world units per unit of height
layout(binding = 0) uniform sampler2D uWaveState;  // R = height

out vec3 vWorld;
out vec2 vUv;

void main() {
  // Bilinear by hand: the state texture is NEAREST (exact texels for the simulation).
  vec2 size = vec2(textureSize(uWaveState, 0));
  vec2 t = aUv * size - 0.5;
  ivec2 i = ivec2(floor(t));
  vec2 f = t - vec2(i);
  ivec2 hi = ivec2(size) - 1;
  float h00 = texelFetch(uWaveState, clamp(i, ivec2(0), hi), 0).r;
  float h10 = texelFetch(uWaveState, clamp(i + ivec2(1, 0), ivec2(0), hi), 0).r;
  float h01 = texelFetch(uWaveState, clamp(i + ivec2(0, 1), ivec2(0), hi), 0).r;
  float h11 = texelFetch(uWaveState, clamp(i + ivec2(1, 1), ivec2(0), hi), 0).r;
  float h = mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
  vWorld = vec3(aPosition.x * uHalfSize, h * uDisplacement, aPosition.z * uHalfSize);
  vUv = aUv;
  gl_Position = uViewProjection * vec4(vWorld, 1.0);
}
