#version 450 core
// Kuwahara's selection as a compute pass (post/kuwahara_select.glsl): one invocation a texel.
#include "post/kuwahara_select.glsl"
#include "post/compute_output.glsl"

void main() {
  ivec2 p;
  if (outputTexel(p)) imageStore(uTarget, p, kuwaharaSelect(p));
}
