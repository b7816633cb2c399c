#version 450 core
// A whole axis of the 2D FFT in one dispatch (issue 37, render/post/fft.h): a workgroup per
// line loads the line into shared memory, runs every radix pass there (post/fft_line.glsl)
// and writes it back — read from the data buffer once and written once, where fft.comp
// reads and writes it once a pass. Fft2d runs fft.comp for axes fft_line.glsl cannot take.
// Defines: LANES (1: vec2 elements; 2: vec4, two transforms, one after the other).
layout(local_size_x = 256) in;
#include "post/fft_line.glsl"

#if !defined(LANES)
#define LANES 1  // the default lets the file compile on its own (the glslang check)
#endif
#if LANES == 1
#define T vec2
#else
#define T vec4
#endif

layout(std430, binding = 0) readonly buffer Source { T src[]; };
layout(std430, binding = 1) writeonly buffer Destination { T dst[]; };

uniform int uAxis;     // 0: along rows (x), 1: along columns (y)
uniform int uLength;   // N, the axis length
uniform ivec2 uSize;   // (w, h)
uniform float uSign;   // −1 forward, +1 inverse
uniform float uScale;  // 1, or 1/(w·h) on the inverse's last axis

int address(int line, int position) { return uAxis == 0 ? line * uSize.x + position : position * uSize.x + line; }

void main() {
  const int line = int(gl_WorkGroupID.x), thread = int(gl_LocalInvocationID.x), n = uLength;
  for (int lane = 0; lane < LANES; ++lane) {
    for (int j = thread; j < n; j += kThreads) {
#if LANES == 1
      sLine[j] = src[address(line, j)];
#else
      vec4 v = src[address(line, j)];
      sLine[j] = lane == 0 ? v.xy : v.zw;
#endif
    }
    fftLine(n, 1, uSign);
    for (int j = thread; j < n; j += kThreads) {
#if LANES == 1
      dst[address(line, j)] = sLine[j] * uScale;
#else
      if (lane == 0) dst[address(line, j)].xy = sLine[j] * uScale;
      else dst[address(line, j)].zw = sLine[j] * uScale;
#endif
    }
    barrier();  // the next lane refills the line
  }
}
