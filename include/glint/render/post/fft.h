#pragma once
// glint/render/post/fft.h — a 2D FFT in OpenGL compute shaders (WWDC 2003 session 212's "real-time FFT"
// on float render targets), the spectrum view and frequency-domain filters built on it.
//
// Contents
//   Fft2d                 forward and inverse complex 2D FFT of w × h values in float
//   RealFft2d             the real-input transform of an image's luma or RGB, fused with
//                         the spectrum view or a filter (3 dispatches a filter, 2 a spectrum)
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
#include <string>
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

/// The real-input 2D FFT of an image (issue 37), fused with what the spectrum and the
/// filters do around it: the GPU path of SpectrumPass and FrequencyFilterPass wherever
/// Fft2d's axes run in shared memory and the size fits(). An image's channels are real, so
/// half of each row's DFT is the conjugate of the other half: a row of w values is
/// transformed as w/2 complex ones (x[2j] + i·x[2j+1]) and unpacked into its w/2 + 1
/// frequencies; the columns run on those only. Per channel that is half the transform and
/// half the data of a complex FFT: the filter's three channels take 3 planes of
/// (w/2 + 1)·h complex values where the complex path's two lanes (R + iG, B + 0i) take 2 of
/// w·h. And the steps around the transform are fused into it:
///
///   spectrum: rows of the luma straight from the texture → columns, written as the
///             centred log-magnitude view (each column also draws its mirror)   2 dispatches
///   filter:   rows of R, G, B from the texture → per column: FFT, × H, inverse FFT, in
///             place → inverse rows + offset, clamped, into the output image    3 dispatches
///
/// where the complex path takes load, the axes, multiply, the inverse axes and store (7 on a
/// GPU, one a radix pass on a software rasterizer). Same conventions as Fft2d; the half
/// spectrum of channel c is plane c, h rows of w/2 + 1 complex values.
class RealFft2d {
public:
  /// Whether the fused path takes `size`: w even, w/2 ≤ 2048 (w ≤ 4096) and h ≤ 4096, both
  /// w/2 and h with radices 2, 3, 4, 5 only — every video size up to 4096 wide.
  static bool fits(ivec2 size);
  /// channels: 1 (the luma) or 3 (R, G, B). Error(Usage) for a size that does not fit().
  RealFft2d(ivec2 size, int channels);

  ivec2 size() const { return m_size; }
  int channels() const { return m_channels; }
  /// Frequencies a row keeps: w/2 + 1.
  int halfWidth() const { return m_size.x / 2 + 1; }
  /// The planes of the half spectrum after forwardRows() / filterColumns().
  const gl::Buffer& buffer() const { return m_data; }

  /// Dispatch 1: every row of the input texture (w × h, any float-sampled format) to its
  /// real DFT, per channel. Every texture argument must be w × h (else Error(Usage)). After it, plane c holds the rows' transforms (not the 2D DFT).
  void forwardRows(const gl::Texture& input);
  /// Dispatch 1 and the columns' forward FFT, for tests: the half spectrum of channel c,
  /// row-major (v·(w/2 + 1) + u), equal to FFTW's r2c of the same values.
  std::vector<std::complex<float>> halfSpectrum(const gl::Texture& input, int channel);
  /// Dispatch 2 of the spectrum (channels = 1): the columns' FFT drawn straight into
  /// `output` (RGBA8 or RGBA32F, w × h) as SpectrumPass draws it.
  void spectrum(const gl::Texture& output);
  /// Dispatch 2 of a filter (channels = 3): each column's FFT, × `transfer` (H(u, v) for
  /// u ≤ w/2 as vec2, column-major: u·h + v), the inverse FFT, in place.
  void filterColumns(const gl::Buffer& transfer);
  /// Dispatch 3 of a filter: the inverse rows, scaled by 1/((w/2)·h), plus `offset`, into
  /// `output` (RGBA8 clamped, or RGBA32F), alpha from `input`.
  void inverseRows(const gl::Texture& input, const gl::Texture& output, float offset);

private:
  const gl::Program& program(gl::Program& slot, const char* file, std::vector<std::string> defines);
  void columns(const gl::Program& p, int channels);
  void checkSize(const gl::Texture& texture, const char* what) const;

  ivec2 m_size{0};
  int m_channels = 1;
  std::vector<int> m_rowRadices, m_columnRadices;  // of w/2 and of h
  gl::Buffer m_rowTwiddles, m_columnTwiddles;      // e^(−2πi·m/w), e^(−2πi·m/h)
  gl::Buffer m_data;
  gl::Program m_rows, m_inverseRows, m_inverseRowsFloat, m_columns, m_spectrum, m_spectrumFloat, m_columnsOnly;
};

/// Which transform SpectrumPass and FrequencyFilterPass run.
enum class FftPath {
  Auto,       ///< RealInput where the size fits and Fft2d's axes run in shared memory (a GPU), else Complex
  RealInput,  ///< RealFft2d wherever the size fits it (else Complex), on any renderer
  Complex     ///< Fft2d with load, multiply and store passes around it
};

/// The spectrum view (image/fourier.h's spectrumReference): luma → FFT → centred
/// log(1 + |F|) / log(1 + w·h), gray, into an RGBA8 (or other image-storable RGBA) texture.
class SpectrumPass {
public:
  SpectrumPass() = default;
  void run(const gl::Texture& input, const gl::Texture& output);
  /// The transform it runs (benches compare them); Auto by default.
  void setPath(FftPath path) { m_path = path; }
  /// Whether the last run() took RealFft2d's fused path.
  bool realInput() const { return m_real != nullptr; }

private:
  void prepare(ivec2 size);
  std::unique_ptr<Fft2d> m_fft;
  std::unique_ptr<RealFft2d> m_real;        // the RealInput path (FftPath)
  FftPath m_path = FftPath::Auto;
  FftPath m_preparedPath = FftPath::Auto;   // what m_fft or m_real were chosen for
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
  /// The transform it runs (benches compare them); Auto by default.
  void setPath(FftPath path) { m_path = path; }
  /// Whether the last run() took RealFft2d's fused path.
  bool realInput() const { return m_real != nullptr; }

private:
  void prepare(ivec2 size, const FrequencyFilter& filter);
  std::unique_ptr<Fft2d> m_fft;
  std::unique_ptr<Fft2d> m_kernelFft;
  std::unique_ptr<RealFft2d> m_real;  // the RealInput path (FftPath)
  FftPath m_path = FftPath::Auto;
  FftPath m_preparedPath = FftPath::Auto;  // what m_fft or m_real were chosen for
  gl::Buffer m_transfer;  // H(u, v) as vec2 per frequency (m_real: u ≤ w/2, column-major)
  FrequencyFilter m_prepared;
  bool m_hasTransfer = false;
  gl::Program m_load, m_multiply, m_store, m_storeFloat;  // m_storeFloat: for RGBA32F outputs
};

}  // namespace glint::render::post
