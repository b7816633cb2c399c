#version 450 core
// The real-input transform's columns (issue 37, render/post/fft.h's RealFft2d): a workgroup
// per column u = 0..w/2 of a channel's half spectrum (fft_real_rows.comp wrote it), in place.
// The column's forward FFT (post/fft_line.glsl), then:
//
// SPECTRUM: the centred view of log(1 + |F|) / log(1 + w·h) (image/fourier.h), written
// straight into the output image: pixel ((u + ⌊w/2⌋) mod w, (v + ⌊h/2⌋) mod h), and for
// 0 < u < w/2 also its mirror, frequency (w − u, −v), which has the same magnitude (the
// input is real). No spectrum buffer is written.
//
// COLUMNS_ONLY: written back, so the planes hold the half spectrum (tests read it).
//
// FILTER: × H(u, v) (binding 3, column-major: u·h + v), the inverse FFT, written back: the
// forward transform, the multiply and the inverse in one read and one write of the column.
//
// The twiddle table (binding 2) is the column's, h entries.
layout(local_size_x = 256) in;
#include "post/fft_line.glsl"

#if !defined(SPECTRUM) && !defined(FILTER) && !defined(COLUMNS_ONLY)
#define FILTER 1  // the default lets the file compile on its own (the glslang check)
#endif

layout(std430, binding = 0) buffer Data { vec2 data[]; };  // planes of h rows of w/2 + 1
uniform ivec2 uSize;                                       // (w, h)

#ifdef SPECTRUM
#ifdef FLOAT_OUTPUT
layout(rgba32f, binding = 0) writeonly uniform image2D uOutput;
#else
layout(rgba8, binding = 0) writeonly uniform image2D uOutput;
#endif
#elif defined(FILTER)
layout(std430, binding = 3) readonly buffer Transfer { vec2 transfer[]; };
#endif

void main() {
  const int u = int(gl_WorkGroupID.x), channel = int(gl_WorkGroupID.y), thread = int(gl_LocalInvocationID.x);
  const int w = uSize.x, h = uSize.y, n = w / 2;
  const int base = channel * (n + 1) * h + u;
  for (int v = thread; v < h; v += kThreads) sLine[v] = data[base + v * (n + 1)];
  fftLine(h, 1, -1.0);
#ifdef SPECTRUM
  const float scale = 1.0 / log(1.0 + float(w) * float(h));
  for (int v = thread; v < h; v += kThreads) {
    const vec4 value = vec4(vec3(log(1.0 + length(sLine[v])) * scale), 1.0);
    imageStore(uOutput, ivec2((u + w / 2) % w, (v + h / 2) % h), value);
    if (u > 0 && u < n) imageStore(uOutput, ivec2((w - u + w / 2) % w, ((h - v) % h + h / 2) % h), value);
  }
#else
#ifdef FILTER
  for (int v = thread; v < h; v += kThreads) sLine[v] = cmul(sLine[v], transfer[u * h + v]);
  fftLine(h, 1, 1.0);
#endif
  for (int v = thread; v < h; v += kThreads) data[base + v * (n + 1)] = sLine[v];
#endif
}
