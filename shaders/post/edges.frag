#version 450 core
// Sobel edges composited over the image: strong edges become dark lines, weak ones
// (below the threshold) leave the pixel alone. After kuwahara this is the seed's posterize.
#include "post/common.glsl"

uniform sampler2D uInput;
uniform float uScale;
uniform float uThreshold;
out vec4 fragColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float e = clamp(uScale * (length(sobel(uInput, p)) - uThreshold), 0.0, 1.0);
  vec4 color = texelFetch(uInput, p, 0);
  fragColor = vec4(color.rgb * (1.0 - e), color.a);
}
