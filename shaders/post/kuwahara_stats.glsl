// Kuwahara pass 1 (WWDC 2003 session 212): the mean and variance of every s×s block, into a float
// texture. Texel q describes the block whose top-left pixel is q − (s − 1), so blocks
// hanging over the image's edges are there too (their pixels repeat the edge).
//
// Stored as integers (image/post.h): RGB = Σk per channel with k = 255·value, and
// A = D = Σ_c (n·Σk_c² − (Σk_c)²) = n²·255²·(total variance), n = s². The sums are taken in
// 32-bit integers (D < 2³¹ for s ≤ 8), so they are exact; the float texture holds D exactly
// while it is below 2²⁴ (s ≤ 4) and rounded once above — rounding keeps the order, so pass 2
// can only see a tie where two variances agree to 7 digits.
// One texel; kuwahara_stats.frag calls it (the fragment version: the compute pass,
// kuwahara.comp, sums its blocks in shared memory).
#include "post/common.glsl"

uniform sampler2D uInput;
uniform int uSize;

vec4 kuwaharaStats(ivec2 q) {
  ivec2 corner = q - ivec2(uSize - 1);
  ivec3 sum = ivec3(0), squares = ivec3(0);
  for (int j = 0; j < uSize; ++j) {
    for (int i = 0; i < uSize; ++i) {
      ivec3 k = ivec3(round(fetchClamped(uInput, corner + ivec2(i, j)).rgb * 255.0));
      sum += k;
      squares += k * k;
    }
  }
  int n = uSize * uSize;
  ivec3 d = n * squares - sum * sum;
  return vec4(vec3(sum), float(d.r + d.g + d.b));
}
