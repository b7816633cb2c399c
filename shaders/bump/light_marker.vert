#version 450 core
// One point sprite at the light's position (no vertex buffer).
uniform mat4 uViewProjection;
uniform vec3 uPosition;
uniform float uPixels;

void main() {
  gl_Position = uViewProjection * vec4(uPosition, 1.0);
  gl_PointSize = uPixels;
}
