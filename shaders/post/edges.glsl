// Sobel edges composited over the image: strong edges become dark lines, weak ones
// (below the threshold) leave the pixel alone. After kuwahara this is WWDC 2003 session 212's posterize.
// One texel; edges.comp (the pass) and edges.frag (its fragment version) call it.
#include "post/common.glsl"

uniform sampler2D uInput;
uniform float uScale;
uniform float uThreshold;

vec4 edgesTexel(ivec2 p) {
  float e = clamp(uScale * (length(sobel(uInput, p)) - uThreshold), 0.0, 1.0);
  vec4 color = texelFetch(uInput, p, 0);
  return vec4(color.rgb * (1.0 - e), color.a);
}
