#version 450 core
// A whole axis of the 2D FFT in one dispatch (issue 37, render/post/fft.h): a workgroup per
// line holds the line in shared memory and runs every radix pass there — fft.comp's
// Stockham passes, the same indexing and twiddle table — so the line is read from the
// data buffer once and written once, where fft.comp reads and writes it once a pass.
// Lines of up to 4096 complex floats (32 KB of shared memory, what every GL 4.3 gives)
// whose radices are all 2, 3, 4 or 5 (every video size); Fft2d runs fft.comp for others.
// Defines: LANES (1: vec2 elements; 2: vec4, two transforms, one after the other).
layout(local_size_x = 256) in;

#if !defined(LANES)
#define LANES 1  // the default lets the file compile on its own (the glslang check)
#endif
#if LANES == 1
#define T vec2
#else
#define T vec4
#endif

const int kThreads = 256;
const int kMaxLength = 4096;
// Outputs an invocation holds between a pass's reads and writes: ceil(N / R / 256) · R.
const int kMaxOutputs = kMaxLength / kThreads + 5;

layout(std430, binding = 0) readonly buffer Source { T src[]; };
layout(std430, binding = 1) writeonly buffer Destination { T dst[]; };
layout(std430, binding = 2) readonly buffer Twiddles { vec2 twiddles[]; };  // e^(−2πi·m/N)

uniform int uAxis;        // 0: along rows (x), 1: along columns (y)
uniform int uLength;      // N, the axis length
uniform ivec2 uSize;      // (w, h)
uniform float uSign;      // −1 forward, +1 inverse
uniform float uScale;     // 1, or 1/(w·h) on the inverse's last axis
uniform int uPasses;      // how many radices
uniform int uRadices[16];

shared vec2 sLine[kMaxLength];

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

// e^(uSign·2πi·m/N): the table's value, conjugated for the inverse.
vec2 twiddle(int m) {
  vec2 t = twiddles[m];
  return vec2(t.x, -uSign * t.y);
}

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
    barrier();
    int p = 1;  // the product of the earlier radices
    for (int pass = 0; pass < uPasses; ++pass) {
      const int radix = uRadices[pass], quarter = n / radix, step = n / (p * radix);
      // Every butterfly of the pass reads before any writes: outputs wait in registers.
      vec2 outputs[kMaxOutputs];
      int count = 0;
      for (int i = thread; i < quarter; i += kThreads) {
        const int k = i % p;
        vec2 u[5];
        for (int s = 0; s < radix; ++s) {
          vec2 x = sLine[i + s * quarter];
          u[s] = (s == 0 || k == 0) ? x : cmul(x, twiddle(s * k * step));
        }
        // The radix-point DFT, its roots e^(±2πi·(s·t mod R)/R) from the table (entry
        // (s·t mod R)·N/R): no sin or cos on the GPU.
        for (int t = 0; t < radix; ++t) {
          vec2 y = u[0];
          for (int s = 1; s < radix; ++s) y += t == 0 ? u[s] : cmul(u[s], twiddle(((s * t) % radix) * quarter));
          outputs[count++] = y;
        }
      }
      barrier();
      count = 0;
      for (int i = thread; i < quarter; i += kThreads) {
        const int k = i % p, first = (i - k) * radix + k;
        for (int t = 0; t < radix; ++t) sLine[first + t * p] = outputs[count++];
      }
      barrier();
      p *= radix;
    }
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
