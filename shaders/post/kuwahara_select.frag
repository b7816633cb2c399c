#version 450 core
// Kuwahara's selection as a fragment pass (post/kuwahara_select.glsl has the arithmetic).
#include "post/kuwahara_select.glsl"

out vec4 fragColor;

void main() { fragColor = kuwaharaSelect(ivec2(gl_FragCoord.xy)); }
