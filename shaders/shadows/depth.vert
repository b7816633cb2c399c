#version 450 core
// Depth only, from the light (shadow maps) — positions are all a depth pass needs.
#include "common/attributes.glsl"

uniform mat4 uModel;
uniform mat4 uViewProj;

void main() { gl_Position = uViewProj * (uModel * vec4(aPosition, 1.0)); }
