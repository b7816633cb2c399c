#version 450 core
// The spectrum view (image/fourier.h): log(1 + |F|) / log(1 + w·h) of the luma's DFT,
// centred — output (x, y) shows index ((x − ⌊w/2⌋) mod w, (y − ⌊h/2⌋) mod h), the DC term
// in the middle, u to the right, v down.
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Source { vec2 src[]; };
#ifdef FLOAT_OUTPUT
layout(rgba32f, binding = 0) writeonly uniform image2D uOutput;
#else
layout(rgba8, binding = 0) writeonly uniform image2D uOutput;
#endif

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uOutput);
  if (p.x >= size.x || p.y >= size.y) return;
  ivec2 f = (p - size / 2 + size) % size;
  float s = log(1.0 + length(src[f.y * size.x + f.x])) / log(1.0 + float(size.x) * float(size.y));
  imageStore(uOutput, p, vec4(vec3(s), 1.0));
}
