#version 450 core
// Sobel as a compute pass (post/sobel.glsl has the arithmetic): one invocation a texel.
#include "post/sobel.glsl"
#include "post/compute_output.glsl"

void main() {
  ivec2 p;
  if (outputTexel(p)) imageStore(uTarget, p, sobelTexel(p));
}
