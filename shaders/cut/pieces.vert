#version 450 core
// The cutter's pieces: world positions, one colour per piece (vertices are not shared
// between pieces, so the colour is flat).
#include "common/attributes.glsl"

uniform mat4 uViewProjection;
out vec4 vColor;
out vec3 vWorld;
out vec3 vNormal;

void main() {
  vColor = aColor;
  vWorld = aPosition;
  vNormal = aNormal;  // the piece's face normal (counter-clockwise front)
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
