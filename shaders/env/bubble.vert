#version 450 core
// The bubble: a sphere that wobbles (two travelling waves along its normal, a few
// percent of its radius) so it reads as a soap film rather than a steel ball.
#include "common/attributes.glsl"
uniform mat4 uModel;
uniform mat4 uViewProj;
uniform float uTime;
uniform float uWobble = 0.03;
out vec3 vWorldPos;
out vec3 vNormal;

void main() {
  vec3 n = normalize(aNormal);
  float w = sin(3.1 * uTime + 4.0 * aPosition.y) * sin(2.3 * uTime + 3.0 * aPosition.x + 1.7 * aPosition.z);
  vec3 p = aPosition * (1.0 + uWobble * w);
  vec4 world = uModel * vec4(p, 1.0);
  vWorldPos = world.xyz;
  vNormal = mat3(uModel) * n;  // uModel is a uniform scale + translation
  gl_Position = uViewProj * world;
}
