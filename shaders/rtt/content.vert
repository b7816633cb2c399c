#version 450 core
// The render-to-texture content: plain transformed geometry.
#include "common/attributes.glsl"
uniform mat4 uModel;
uniform mat4 uViewProj;
out vec3 vNormal;
out vec3 vWorld;

void main() {
  vNormal = mat3(uModel) * aNormal;  // rotations only
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  gl_Position = uViewProj * world;
}
