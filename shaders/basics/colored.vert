#version 450 core
// The lecture's simple triangle: positions are already in normalized device
// coordinates (no transforms), colours interpolated smoothly (GL_SMOOTH).
#include "common/attributes.glsl"

out vec4 vColor;

void main() {
  vColor = aColor;
  gl_Position = vec4(aPosition, 1.0);
}
