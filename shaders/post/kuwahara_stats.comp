#version 450 core
// Kuwahara's statistics as a compute pass (post/kuwahara_stats.glsl): one invocation a
// block, into the RGBA32F statistics texture.
#include "post/kuwahara_stats.glsl"
#include "post/compute_output.glsl"

void main() {
  ivec2 q;
  if (outputTexel(q)) imageStore(uTarget, q, kuwaharaStats(q));
}
