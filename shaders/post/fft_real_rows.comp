#version 450 core
// The real-input transform's rows (issue 37, render/post/fft.h's RealFft2d): a workgroup
// per image row, each channel in turn.
//
// FORWARD: the row's w real values (the luma, CHANNELS 1; or R, G, B, CHANNELS 3) straight
// from the input texture, paired as n = w/2 complex values z[j] = x[2j] + i·x[2j+1]; their
// n-point FFT Z (post/fft_line.glsl); then the row's real DFT at the n + 1 frequencies
// k = 0..n, the other half being their conjugates:
//   E[k] = (Z[k] + conj Z[n−k]) / 2,  O[k] = (Z[k] − conj Z[n−k]) / 2i,  X[k] = E[k] + W^k·O[k],
// W = e^(−2πi/w). Written to channel c's plane: c·(n+1)·h + row·(n+1) + k.
//
// INVERSE (CHANNELS 3): the way back from a plane of n + 1 frequencies a row (after the
// columns' inverse): E[k] = (X[k] + conj X[n−k]) / 2, O[k] = (X[k] − conj X[n−k])·W^−k / 2,
// Z[k] = E[k] + i·O[k], its inverse n-point FFT gives x[2j] + i·x[2j+1], times uScale
// (1/(n·h): neither inverse is normalized). The three channels plus the filter's offset go
// into the output image, clamped for RGBA8, alpha from the input texel.
//
// The twiddle table (binding 2) is the row's, w entries: the n-point FFT takes every second.
layout(local_size_x = 256) in;
#include "post/common.glsl"
#include "post/fft_line.glsl"

// Defaults so the file compiles on its own (the glslang check); RealFft2d defines them.
#if !defined(CHANNELS)
#define CHANNELS 3
#endif
#if !defined(FORWARD) && !defined(INVERSE)
#define FORWARD 1
#endif

uniform sampler2D uInput;
uniform ivec2 uSize;  // (w, h)

// Rows of up to 2 · 2048 texels: an invocation keeps its share of the row's channels in
// registers (read once from the texture; on the way back, until all three are done).
const int kMaxPerThread = 2048 / kThreads;

#ifdef FORWARD
layout(std430, binding = 1) writeonly buffer Destination { vec2 dst[]; };

float channel(vec4 texel, int c) {
#if CHANNELS == 1
  return dot(texel.rgb, kLuma);
#else
  return texel[c];
#endif
}

void main() {
  const int row = int(gl_WorkGroupID.x), thread = int(gl_LocalInvocationID.x), n = uSize.x / 2;
  const int plane = (n + 1) * uSize.y;
  // The row's texels, read once: (x[2j], x[2j+1]) of each channel, j = thread + 256·m.
  vec2 values[CHANNELS][kMaxPerThread];
  for (int j = thread, m = 0; j < n; j += kThreads, ++m) {
    const vec4 a = texelFetch(uInput, ivec2(2 * j, row), 0), b = texelFetch(uInput, ivec2(2 * j + 1, row), 0);
    for (int c = 0; c < CHANNELS; ++c) values[c][m] = vec2(channel(a, c), channel(b, c));
  }
  for (int c = 0; c < CHANNELS; ++c) {
    for (int j = thread, m = 0; j < n; j += kThreads, ++m) sLine[j] = values[c][m];
    fftLine(n, 2, -1.0);
    for (int k = thread; k <= n; k += kThreads) {
      const vec2 z = sLine[k % n], mirror = conjugate(sLine[(n - k) % n]);
      const vec2 even = 0.5 * (z + mirror), odd = -0.5 * timesI(z - mirror);  // (z − m) / 2i
      dst[c * plane + row * (n + 1) + k] = even + cmul(root(k, -1.0), odd);
    }
    barrier();  // the next channel refills the line
  }
}
#else
layout(std430, binding = 0) readonly buffer Source { vec2 src[]; };
#ifdef FLOAT_OUTPUT
layout(rgba32f, binding = 0) writeonly uniform image2D uOutput;
#else
layout(rgba8, binding = 0) writeonly uniform image2D uOutput;
#endif
uniform float uScale;
uniform float uOffset;

void main() {
  const int row = int(gl_WorkGroupID.x), thread = int(gl_LocalInvocationID.x), n = uSize.x / 2;
  const int plane = (n + 1) * uSize.y;
  vec2 values[3][kMaxPerThread];  // (x[2j], x[2j+1]) of each channel, j = thread + 256·m
  for (int c = 0; c < 3; ++c) {
    const int base = c * plane + row * (n + 1);
    for (int k = thread; k < n; k += kThreads) {
      const vec2 x = src[base + k], mirror = conjugate(src[base + n - k]);
      const vec2 even = 0.5 * (x + mirror), odd = 0.5 * cmul(x - mirror, root(k, 1.0));
      sLine[k] = even + timesI(odd);
    }
    fftLine(n, 2, 1.0);
    for (int j = thread, m = 0; j < n; j += kThreads, ++m) values[c][m] = sLine[j] * uScale;
    barrier();  // the next channel refills the line
  }
  for (int j = thread, m = 0; j < n; j += kThreads, ++m) {
    for (int half_ = 0; half_ < 2; ++half_) {
      const ivec2 p = ivec2(2 * j + half_, row);
      vec3 rgb = vec3(values[0][m][half_], values[1][m][half_], values[2][m][half_]) + uOffset;
#ifndef FLOAT_OUTPUT
      rgb = clamp(rgb, 0.0, 1.0);
#endif
      imageStore(uOutput, p, vec4(rgb, texelFetch(uInput, p, 0).a));
    }
  }
}
#endif
