#version 450 core
// Edges as a compute pass (post/edges.glsl has the arithmetic): one invocation a texel.
#include "post/edges.glsl"
#include "post/compute_output.glsl"

void main() {
  ivec2 p;
  if (outputTexel(p)) imageStore(uTarget, p, edgesTexel(p));
}
