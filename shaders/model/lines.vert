#version 450 core
// Lines over a model (wireframe, UV seams, hard edges): positions only.
#include "common/attributes.glsl"
uniform mat4 uViewProj;
void main() { gl_Position = uViewProj * vec4(aPosition, 1.0); }
