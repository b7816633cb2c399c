#version 450 core
// Kuwahara's statistics as a fragment pass (post/kuwahara_stats.glsl has the arithmetic).
#include "post/kuwahara_stats.glsl"

out vec4 fragColor;

void main() { fragColor = kuwaharaStats(ivec2(gl_FragCoord.xy)); }
