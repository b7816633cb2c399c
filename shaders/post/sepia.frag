#version 450 core
// Sepia as a fragment pass (post/sepia.glsl has the arithmetic): kept beside sepia.comp for
// `glint bench post`'s comparison of the two.
#include "post/sepia.glsl"

out vec4 fragColor;

void main() { fragColor = sepiaTexel(ivec2(gl_FragCoord.xy)); }
