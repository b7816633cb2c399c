#version 450 core
// Sepia as a compute pass (post/sepia.glsl has the arithmetic): one invocation a texel.
#include "post/sepia.glsl"
#include "post/compute_output.glsl"

void main() {
  ivec2 p;
  if (outputTexel(p)) imageStore(uTarget, p, sepiaTexel(p));
}
