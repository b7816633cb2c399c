#version 450 core
// Sobel as a fragment pass (post/sobel.glsl has the arithmetic): kept beside sobel.comp for
// `glint bench post`'s comparison of the two.
#include "post/sobel.glsl"

out vec4 fragColor;

void main() { fragColor = sobelTexel(ivec2(gl_FragCoord.xy)); }
