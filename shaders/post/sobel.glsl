// Sobel edge detection (WWDC 2003 session 212): the horizontal and vertical kernels on the luma, from
// the eight texels around the pixel. image/post.h's sobelReference is the same arithmetic.
// One texel; sobel.comp (the pass) and sobel.frag (its fragment version) call it.
#include "post/common.glsl"

uniform sampler2D uInput;
uniform int uOutput;   // SobelOutput: 0 horizontal |Gy|, 1 vertical |Gx|, 2 magnitude, 3 signed Gx, 4 signed Gy
uniform float uScale;

vec4 sobelTexel(ivec2 p) {
  vec2 g = sobel(uInput, p);
  float v;
  if (uOutput == 0) v = min(1.0, uScale * abs(g.y));
  else if (uOutput == 1) v = min(1.0, uScale * abs(g.x));
  else if (uOutput == 2) v = min(1.0, uScale * length(g));
  else if (uOutput == 3) v = clamp(0.5 + 0.5 * uScale * g.x, 0.0, 1.0);
  else v = clamp(0.5 + 0.5 * uScale * g.y, 0.0, 1.0);
  return vec4(vec3(v), texelFetch(uInput, p, 0).a);
}
