#version 450 core
// A model file as glint view shows it (scenes/model.h): world-space attributes (the loader
// applied the node transforms), passed on for per-pixel lighting.
#include "common/attributes.glsl"
uniform mat4 uViewProj;
out vec3 vWorld;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv;
out vec4 vColor;

void main() {
  vWorld = aPosition;
  vNormal = aNormal;
  vTangent = aTangent;
  vUv = aUv;
  vColor = aColor;
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
