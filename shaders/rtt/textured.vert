#version 450 core
// A cube wearing the rendered texture on every face.
#include "common/attributes.glsl"
uniform mat4 uModel;
uniform mat4 uViewProj;
out vec2 vUv;
out vec3 vNormal;

void main() {
  vUv = aUv;
  vNormal = mat3(uModel) * aNormal;
  gl_Position = uViewProj * (uModel * vec4(aPosition, 1.0));
}
