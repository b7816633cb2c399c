#version 450 core
// DOT3 bump mapping, programmable path: pass the encoded light vector (the vertex colour,
// unsigned bytes normalized to 0..1 exactly as glColor3ub) and one texture coordinate set
// (the WWDC 2001 talk issues the same coordinates for units 0 and 1).
#include "common/attributes.glsl"

uniform mat4 uModelViewProjection;

// `smooth` (the default), as glShadeModel(GL_SMOOTH): perspective-correct interpolation,
// which is what fixed-function colour interpolation does on every current implementation.
smooth out vec3 vLightColor;
out vec2 vUv;

void main() {
  vLightColor = aColor.rgb;
  vUv = aUv;
  gl_Position = uModelViewProjection * vec4(aPosition, 1.0);
}
