#version 450 core
// Local scenery around the bubble: plain diffuse objects, drawn both into the six faces
// of the dynamic cube map and into the frame.
#include "common/attributes.glsl"
uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProj;
out vec3 vNormal;
out vec2 vUv;

void main() {
  vNormal = uNormalMatrix * aNormal;
  vUv = aUv;
  gl_Position = uViewProj * (uModel * vec4(aPosition, 1.0));
}
