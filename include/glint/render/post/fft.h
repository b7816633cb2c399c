#pragma once
// glint/render/post/fft.h — a 2D FFT in OpenGL compute shaders (seed 001's "real-time FFT"
// on float render targets), the spectrum view and frequency-domain filters built on it.
//
// Contents
//   Fft2d                 forward and inverse complex 2D FFT of w × h values in float
//   SpectrumPass          frame → log-magnitude spectrum of its luma, centred
//   FrequencyFilterPass   frame → DFT → × H(u, v) → inverse DFT → frame (low/high/band-pass,
//                         convolution by a Gaussian or a disk)
//
// The transform is Stockham's autosort FFT, rows then columns, ping-ponging between two
// shader storage buffers. An axis of up to 4096 whose radices are all 2, 3, 4 or 5 (every
// video size) runs in one dispatch (shaders/post/fft_axis.comp: a workgroup per line, the
// line in shared memory through every pass, read and written once; issue 37); any other
// axis one dispatch per radix pass (shaders/post/fft.comp). On a software rasterizer every
// axis goes pass by pass (setSharedAxes).
// Sizes need not be powers of two: each axis is factored into radices 4, 2, 3, 5 (every
// video size — 640, 480, 1080, 1920, 2160, 3840 — is 2·3·5-smooth) and any other prime
// factor p gets a direct radix-p step (O(p) per element). No padding, so the spectrum of a
// 1920 × 1080 frame is the DFT of those pixels, with image/fourier.h's conventions:
// forward unnormalized with e^(−2πi…), inverse with 1/(w·h), data row-major with row 0 the
// picture's top row. Twiddle factors come from a table computed in double on the CPU, so
// precision does not depend on the GPU's sin/cos: relative L2 error against FFTW in double
// is about 1e-7 (tests/post, docs/post.md).
//
// Elements are complex floats, `lanes` at a time: lanes = 1 stores vec2 (re, im); lanes = 2
// stores vec4, two independent transforms in one pass — the filter packs R + iG and B in
// them (a real kernel filters real and imaginary parts independently).
//
/// ```cpp
/// const std::vector<std::complex<float>> samples(512 * 512, {1.0f, 0.0f});
/// glint::render::post::Fft2d fft({512, 512});
/// const std::vector<std::complex<float>> spectrum = fft.forward(samples);  // upload, FFT, download
/// const std::vector<std::complex<float>> back = fft.inverse(spectrum);     // the samples, within ~1e-7
/// ```
//
// Needs a current 4.5 context (compute shaders, SSBOs, image load/store).

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/image/fourier.h"

#include <complex>
#include <map>
#include <memory>
#include <span>
#include <vector>

namespace glint::render::post {

enum class FftDirection {
  Forward,  ///< e^(−2πi…), unnormalized
  Inverse   ///< e^(+2πi…), divided by w·h
};

class Fft2d {
public:
  /// Plans the transform: factors each axis, builds the twiddle tables and the two data
  /// buffers (w·h elements of 2·lanes floats). Error(Usage) for sizes below 1 or lanes not 1 or 2.
  explicit Fft2d(ivec2 size, int lanes = 1);

  ivec2 size() const { return m_size; }
  int lanes() const { return m_lanes; }
  /// The two data buffers the passes ping-pong between.
  const gl::Buffer& buffer(int index) const { return m_data[index]; }
  /// Transforms the contents of buffer(from); returns the index of the buffer holding the
  /// result (from, or the other one: each pass swaps).
  int run(int from, FftDirection direction);
  /// Radices of each axis, in pass order (for reports).
  const std::vector<int>& radices(int axis) const { return m_axes[axis].radices; }
  /// Whether `axis` runs in one dispatch through shared memory (see above), and the
  /// switch to run every axis pass by pass instead. By default on, but on a software
  /// rasterizer (llvmpipe runs workgroup barriers as coroutines: twice the passes' time);
  /// GLINT_FFT_AXES=shared or =passes sets the default.
  bool inSharedMemory(int axis) const { return m_sharedAxes && m_axes[axis].fitsShared; }
  void setSharedAxes(bool on) { m_sharedAxes = on; }
  /// Dispatches a run() makes (each reads and writes the whole data buffer once).
  int dispatches() const;

  /// Convenience (tests, tools; lanes = 1): upload, transform, download.
  std::vector<std::complex<float>> transform(std::span<const std::complex<float>> data, FftDirection direction);
  std::vector<std::complex<float>> forward(std::span<const std::complex<float>> data) {
    return transform(data, FftDirection::Forward);
  }
  std::vector<std::complex<float>> inverse(std::span<const std::complex<float>> data) {
    return transform(data, FftDirection::Inverse);
  }

private:
  struct Axis {
    int length = 1;
    std::vector<int> radices;
    gl::Buffer twiddles;  // e^(−2πi·m/length), m = 0..length−1, vec2 per entry
    bool fitsShared = false;
  };
  const gl::Program& program(int radix);
  const gl::Program& axisProgram();

  ivec2 m_size{0};
  int m_lanes = 1;
  Axis m_axes[2];
  gl::Buffer m_data[2];
  std::map<int, gl::Program> m_programs;  // by radix
  gl::Program m_axisProgram;              // fft_axis.comp
  bool m_sharedAxes = true;
};

/// The spectrum view (image/fourier.h's spectrumReference): luma → FFT → centred
/// log(1 + |F|) / log(1 + w·h), gray, into an RGBA8 (or other image-storable RGBA) texture.
class SpectrumPass {
public:
  SpectrumPass() = default;
  void run(const gl::Texture& input, const gl::Texture& output);

private:
  void prepare(ivec2 size);
  std::unique_ptr<Fft2d> m_fft;
  gl::Program m_load, m_show, m_showFloat;  // m_showFloat: for RGBA32F outputs
};

/// A frequency-domain filter (image/fourier.h's frequencyFilterReference): R + iG and B
/// transformed together, multiplied by H(u, v), transformed back, plus the filter's offset,
/// clamped into the output. H is computed once per size and filter (in double on the CPU
/// for the radial filters; the kernel's own FFT on the GPU for convolutions).
class FrequencyFilterPass {
public:
  FrequencyFilterPass() = default;
  void run(const gl::Texture& input, const gl::Texture& output, const FrequencyFilter& filter);

private:
  void prepare(ivec2 size, const FrequencyFilter& filter);
  std::unique_ptr<Fft2d> m_fft;
  std::unique_ptr<Fft2d> m_kernelFft;
  gl::Buffer m_transfer;  // H(u, v) as vec2 per frequency
  FrequencyFilter m_prepared;
  bool m_hasTransfer = false;
  gl::Program m_load, m_multiply, m_store, m_storeFloat;  // m_storeFloat: for RGBA32F outputs
};

}  // namespace glint::render::post
