// WWDC 2003 session 212's sepia without a lookup table: RGB → YIQ keeping only Y, I and Q hard-coded,
// back to RGB. With I and Q constant the round trip is rgb' = Y·(1,1,1) + c, so the pass is
// WWDC 2003 session 212's "dot product and an add" (image/post.h derives c = M⁻¹·(0, I, Q)). The offset
// is shortened to t·c where Y + c would leave [0, 1], so the luma is kept exactly.
// One texel; sepia.comp (the pass) and sepia.frag (its fragment version) call it.
#include "post/common.glsl"

uniform sampler2D uInput;
uniform vec3 uOffset;     // c
uniform vec2 uLimits;     // (1 / max(−c_k), 1 / max(c_k)): how far the offset may go at Y = 1 and Y = 0

vec4 sepiaTexel(ivec2 p) {
  vec4 color = texelFetch(uInput, p, 0);
  float y = dot(color.rgb, kLuma);                                  // the dot product
  float t = min(1.0, min(y * uLimits.x, (1.0 - y) * uLimits.y));    // stay in gamut
  return vec4(y + t * uOffset, color.a);                            // and the add
}
