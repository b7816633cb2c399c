#version 450 core
// Normal mapping, vertex stage: world-space position, and the MikkTSpace frame made unit
// per vertex and then interpolated WITHOUT renormalizing (render/bump/normal_mapping.h) — the
// frame glint's baker inverts, texel by texel.
#include "common/attributes.glsl"

uniform mat4 uModel;
uniform mat3 uNormalMatrix;  // inverse transpose of uModel's 3×3
uniform mat4 uViewProj;

out vec3 vWorldPos;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorldPos = world.xyz;
  vNormal = normalize(uNormalMatrix * aNormal);
  // A mesh without tangents reads (0, 0, 0, 1): keep it zero rather than NaN.
  vec3 t = mat3(uModel) * aTangent.xyz;
  vTangent = vec4(dot(t, t) > 0.0 ? normalize(t) : vec3(0.0), aTangent.w);
  vUv = aUv;
  gl_Position = uViewProj * world;
}
