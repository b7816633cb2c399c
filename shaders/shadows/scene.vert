#version 450 core
// The lit scene of every shadow technique: world-space position and normal for
// per-pixel lighting by one point light (shaders/shadows/scene.frag).
#include "common/attributes.glsl"

uniform mat4 uModel;
uniform mat3 uNormalMatrix;  // inverse transpose of uModel's upper 3×3
uniform mat4 uViewProj;

out vec3 vWorldPos;
out vec3 vNormal;

// The multi-pass method redraws the scene with GL_EQUAL depth: `invariant` promises
// the same gl_Position bits from the same inputs in every pass.
invariant gl_Position;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorldPos = world.xyz;
  vNormal = uNormalMatrix * aNormal;
  gl_Position = uViewProj * world;
}
