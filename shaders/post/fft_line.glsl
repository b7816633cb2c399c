// One line of an FFT in shared memory (render/post/fft.h; issue 37): what fft_axis.comp
// and the real-input transform (fft_real_rows.comp, fft_real_columns.comp) share. A
// workgroup of 256 holds the line in `sLine` and runs every Stockham pass of fft.comp on
// it there — the same indexing, the same twiddle table — so the line leaves global memory
// once, however many passes it takes. Lines of up to 4096 complex floats (32 KB, what every
// GL 4.3 gives a workgroup) whose radices are all 2, 3, 4 or 5.
//
// The including shader declares local_size_x = kThreads and sets uPasses and uRadices (the
// line's radices in pass order, as Fft2d factors them).

const int kThreads = 256;
const int kMaxLength = 4096;
// Outputs an invocation holds between a pass's reads and writes: ceil(N / R / 256) · R.
const int kMaxOutputs = kMaxLength / kThreads + 5;

layout(std430, binding = 2) readonly buffer Twiddles { vec2 twiddles[]; };  // e^(−2πi·m/L), m < L

uniform int uPasses;  // how many radices
uniform int uRadices[16];

shared vec2 sLine[kMaxLength];

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 conjugate(vec2 a) { return vec2(a.x, -a.y); }
vec2 timesI(vec2 a) { return vec2(-a.y, a.x); }

// e^(sign·2πi·m/L), L the table's length: the table's entry, conjugated for sign = +1.
vec2 root(int m, float sign) {
  vec2 t = twiddles[m];
  return vec2(t.x, -sign * t.y);
}

// sLine[0, n) ← its DFT, e^(sign·2πi·jk/n), unnormalized. `spacing` = L / n: the table's
// entries per root of the line (1 when the table was made for n). Starts and ends with every
// invocation's shared-memory writes visible to all (barrier()).
void fftLine(int n, int spacing, float sign) {
  barrier();
  int p = 1;  // the product of the earlier radices
  for (int pass = 0; pass < uPasses; ++pass) {
    const int radix = uRadices[pass], quarter = n / radix, step = n / (p * radix) * spacing;
    // Every butterfly of the pass reads before any writes: outputs wait in registers.
    vec2 outputs[kMaxOutputs];
    int count = 0;
    for (int i = int(gl_LocalInvocationID.x); i < quarter; i += kThreads) {
      const int k = i % p;
      vec2 u[5];
      for (int s = 0; s < radix; ++s) {
        vec2 x = sLine[i + s * quarter];
        u[s] = (s == 0 || k == 0) ? x : cmul(x, root(s * k * step, sign));
      }
      // The radix-point DFT, its roots e^(±2πi·(s·t mod R)/R) from the table (entry
      // (s·t mod R)·L/R): no sin or cos on the GPU.
      for (int t = 0; t < radix; ++t) {
        vec2 y = u[0];
        for (int s = 1; s < radix; ++s) y += t == 0 ? u[s] : cmul(u[s], root(((s * t) % radix) * quarter * spacing, sign));
        outputs[count++] = y;
      }
    }
    barrier();
    count = 0;
    for (int i = int(gl_LocalInvocationID.x); i < quarter; i += kThreads) {
      const int k = i % p, first = (i - k) * radix + k;
      for (int t = 0; t < radix; ++t) sLine[first + t * p] = outputs[count++];
    }
    barrier();
    p *= radix;
  }
}
