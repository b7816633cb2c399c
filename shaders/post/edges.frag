#version 450 core
// Edges as a fragment pass (post/edges.glsl has the arithmetic): kept beside edges.comp for
// `glint bench post`'s comparison of the two.
#include "post/edges.glsl"

out vec4 fragColor;

void main() { fragColor = edgesTexel(ivec2(gl_FragCoord.xy)); }
