// What every post pass's compute shader shares (issue 37): 16×16 invocations a group, one
// per output texel, and the output image, RGBA8 or (FLOAT_OUTPUT) RGBA32F as the chain's
// targets are. An RGBA8 store clamps to 0..1 and rounds as the fragment pass's colour
// output does, so both give the same bytes.
layout(local_size_x = 16, local_size_y = 16) in;
#ifdef FLOAT_OUTPUT
layout(rgba32f, binding = 0) writeonly uniform image2D uTarget;
#else
layout(rgba8, binding = 0) writeonly uniform image2D uTarget;
#endif

// This invocation's texel, or false past the image's edge (the last groups overhang it).
bool outputTexel(out ivec2 p) {
  p = ivec2(gl_GlobalInvocationID.xy);
  return all(lessThan(p, imageSize(uTarget)));
}
