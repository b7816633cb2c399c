#version 450 core
// The instrument machine: world position, normal and albedo for per-pixel lighting
// (shaders/pipedream/scene.frag). The naive method adds each light in a pass of its own
// over the same triangles with GL_EQUAL depth: `invariant` keeps gl_Position bit-identical.
#include "common/attributes.glsl"

uniform mat4 uModel;
uniform mat3 uNormalMatrix;  // inverse transpose of uModel's upper 3×3
uniform mat4 uViewProj;
uniform bool uVertexAlbedo;  // albedo from the colour attribute (static scene) or uAlbedo (dynamic parts)
uniform vec3 uAlbedo;

out vec3 vWorld;
out vec3 vNormal;
out vec3 vAlbedo;
invariant gl_Position;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  vNormal = uNormalMatrix * aNormal;
  vAlbedo = uVertexAlbedo ? aColor.rgb : uAlbedo;
  gl_Position = uViewProj * world;
}
