#version 450 core
// One radix pass of Stockham's autosort FFT along one axis of a w × h grid (render/post/fft.h).
// Defines: RADIX (the pass's radix), LANES (1: vec2 elements, one transform; 2: vec4, two).
//
// Invocation i < N/R of a line reads R inputs spaced N/R apart, twiddles them by
// e^(∓2πi·s·k/(p·R)) (k = i mod p, p = product of the earlier radices), takes their
// R-point DFT, and writes the outputs p apart starting at (i − k)·R + k. After the last
// pass the line holds its DFT in natural order: no bit reversal.
layout(local_size_x = 64) in;

// Defaults so the file compiles on its own (the glslang check); Fft2d always defines both.
#if !defined(RADIX)
#define RADIX 4
#endif
#if !defined(LANES)
#define LANES 1
#endif

#if LANES == 1
#define T vec2
#else
#define T vec4
#endif

layout(std430, binding = 0) readonly buffer Source { T src[]; };
layout(std430, binding = 1) writeonly buffer Destination { T dst[]; };
layout(std430, binding = 2) readonly buffer Twiddles { vec2 twiddles[]; };  // e^(−2πi·m/N)

uniform int uAxis;     // 0: along rows (x), 1: along columns (y)
uniform int uLength;   // N, the axis length
uniform int uStride;   // p
uniform ivec2 uSize;   // (w, h)
uniform float uSign;   // −1 forward, +1 inverse
uniform float uScale;  // 1, or 1/(w·h) on the inverse's last pass

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
#if LANES == 1
T twiddleBy(T a, vec2 w) { return cmul(a, w); }
T timesI(T a) { return vec2(-a.y, a.x); }
#else
T twiddleBy(T a, vec2 w) { return vec4(cmul(a.xy, w), cmul(a.zw, w)); }
T timesI(T a) { return vec4(-a.y, a.x, -a.w, a.z); }
#endif

// e^(uSign·2πi·m/N): the table's value, conjugated for the inverse.
vec2 twiddle(int m) {
  vec2 t = twiddles[m];
  return vec2(t.x, -uSign * t.y);
}

// The element at `position` along this invocation's line. The line is a parameter, not a
// global: Mesa warns "'line' used uninitialized" for a global set in main and read here.
int address(int line, int position) { return uAxis == 0 ? line * uSize.x + position : position * uSize.x + line; }

void main() {
  int quarter = uLength / RADIX;
  int line, i;
  if (uAxis == 0) {
    i = int(gl_GlobalInvocationID.x);
    line = int(gl_GlobalInvocationID.y);
    if (i >= quarter || line >= uSize.y) return;
  } else {
    line = int(gl_GlobalInvocationID.x);
    i = int(gl_GlobalInvocationID.y);
    if (line >= uSize.x || i >= quarter) return;
  }
  int p = uStride;
  int k = i % p;
  int step = uLength / (p * RADIX);  // twiddle index per s·k
  int first = (i - k) * RADIX + k;

#if RADIX <= 16
  T u[RADIX];
  for (int s = 0; s < RADIX; ++s) {
    T x = src[address(line, i + s * quarter)];
    u[s] = (s == 0 || k == 0) ? x : twiddleBy(x, twiddle(s * k * step));
  }
#if RADIX == 2
  dst[address(line, first)] = (u[0] + u[1]) * uScale;
  dst[address(line, first + p)] = (u[0] - u[1]) * uScale;
#elif RADIX == 4
  T a = u[0] + u[2], b = u[0] - u[2], c = u[1] + u[3], d = timesI(u[1] - u[3]) * uSign;
  dst[address(line, first)] = (a + c) * uScale;
  dst[address(line, first + p)] = (b + d) * uScale;
  dst[address(line, first + 2 * p)] = (a - c) * uScale;
  dst[address(line, first + 3 * p)] = (b - d) * uScale;
#else
  // A direct R-point DFT; its roots of unity are table entries (N/R)·(s·t mod R).
  for (int t = 0; t < RADIX; ++t) {
    T sum = u[0];
    for (int s = 1; s < RADIX; ++s) sum += twiddleBy(u[s], twiddle(((s * t) % RADIX) * quarter));
    dst[address(line, first + t * p)] = sum * uScale;
  }
#endif
#else
  // Large prime radix: no register array; each output re-reads its R inputs (O(R) per output).
  for (int t = 0; t < RADIX; ++t) {
    T sum = T(0.0);
    for (int s = 0; s < RADIX; ++s) {
      T x = src[address(line, i + s * quarter)];
      if (s != 0 && k != 0) x = twiddleBy(x, twiddle(s * k * step));
      sum += twiddleBy(x, twiddle(((s * t) % RADIX) * quarter));
    }
    dst[address(line, first + t * p)] = sum * uScale;
  }
#endif
}
