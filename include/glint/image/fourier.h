#pragma once
// glint/image/fourier.h — the frequency domain on the CPU: a direct DFT (slow, obvious,
// the reference), the spectrum picture, and the transfer functions of glint post's
// frequency-domain filters. render/post/fft.h is the GPU side; FFTW is its oracle in the
// tests.
//
// Contents
//   dft2d                direct 2D DFT in double, both directions
//   frequencyOf          an index's signed frequency; the centred (fftshift) layout
//   spectrumReference    log magnitude of the luma's DFT, centred, as a gray image
//   FrequencyFilter      low/high/band-pass and convolution by a kernel: H(u, v)
//   frequencyFilterReference  an image through a filter, via dft2d
//
// Conventions (the GPU FFT follows them)
//   - Forward: F(u, v) = Σ_y Σ_x f(x, y) · e^(−2πi (u·x/W + v·y/H)), unnormalized (FFTW's
//     FFTW_FORWARD and cv::dft's default). Inverse: e^(+2πi ...) with 1/(W·H), so
//     inverse(forward(f)) = f (FFTW's backward transform has no 1/(W·H)).
//   - Data is row-major, row 0 first (the image's top row): F[v·W + u].
//   - Any size: the GPU transform is mixed radix (no padding), so every size has the same
//     spectrum here and there.
//   - Filtering multiplies the DFT, so it is circular: the image is treated as periodic,
//     and a blur near the left edge mixes in pixels from the right edge.

#include "glint/image/image.h"

#include <complex>
#include <span>
#include <vector>

namespace glint {

/// Direct 2D DFT of w × h complex values (row-major), rows then columns, O(w·h·(w + h)),
/// in double; `inverse` uses e^(+2πi...) and divides by w·h. For references at small
/// sizes (256² takes about a second).
std::vector<std::complex<double>> dft2d(std::span<const std::complex<double>> data, int w, int h, bool inverse);

/// The signed frequency of DFT index `index` along an axis of n samples: index for
/// index ≤ n/2, index − n above (cycles per n samples).
inline int frequencyOf(int index, int n) { return index <= n / 2 ? index : index - n; }
/// The DFT index a centred (fftshift) picture shows at position p: p − ⌊n/2⌋, wrapped.
/// Position ⌊n/2⌋ shows the DC term.
inline int centredIndex(int p, int n) { return ((p - n / 2) % n + n) % n; }

/// The spectrum view: s(x, y) = log(1 + |F|) / log(1 + w·h), F the DFT of postLuma at the
/// centred index (x, y) (the DC term at (⌊w/2⌋, ⌊h/2⌋), u to the right, v downwards). The
/// fixed denominator (|F| ≤ w·h for luma in [0, 1]) keeps the picture comparable between
/// frames: no per-frame maximum. F32 RGBA, gray, alpha 1.
Image spectrumReference(const Image& rgba);
/// The same from a DFT already computed (w·h values of a luma image's forward transform).
Image spectrumImage(std::span<const std::complex<double>> spectrum, int w, int h);

// ---------------------------------------------------------------------------
// Frequency-domain filters

enum class FilterKind {
  LowPass,   ///< keeps frequencies below `cutoff`
  HighPass,  ///< 1 − LowPass: removes them (and the mean: add `offset` to see the result)
  BandPass,  ///< LowPass(cutoff) − LowPass(low): keeps low ≤ ρ ≤ cutoff
  Kernel     ///< convolution by a kernel: H = DFT(kernel)
};

enum class KernelShape {
  Gaussian,  ///< exp(−r²/(2σ²)), `size` = σ in pixels
  Disk       ///< 1 inside radius `size` (a lens's bokeh), anti-aliased edge
};

/// A filter's transfer function H(u, v). The radial frequency is
/// ρ = √((u'/W)² + (v'/H)²) in cycles per pixel (u', v' from frequencyOf; ρ ≤ 0.707):
/// a cutoff of 0.5 is the Nyquist frequency along an axis.
struct FrequencyFilter {
  FilterKind kind = FilterKind::LowPass;
  float cutoff = 0.05f;  ///< LowPass/HighPass: the edge; BandPass: the upper edge (cycles/pixel)
  float low = 0.02f;     ///< BandPass: the lower edge
  int order = 2;         ///< Butterworth order: 1/(1 + (ρ/cutoff)^(2·order)); 0 = ideal (a brick wall: rings)
  KernelShape kernel = KernelShape::Gaussian;  ///< Kernel filters
  float size = 4.0f;     ///< Kernel: σ (Gaussian) or radius (disk) in pixels
  float offset = 0.0f;   ///< added to the filtered image (0.5 shows a high-pass around mid-gray)
};

/// H(u, v) for LowPass, HighPass and BandPass at DFT index (u, v) of a w × h transform
/// (real and even: zero phase). Error(Usage) for Kernel filters (their H is complex).
double filterGain(const FrequencyFilter& filter, int u, int v, int w, int h);
/// The kernel of a Kernel filter on the periodic w × h grid: centred on pixel (0, 0) (so
/// pixel (w − 1, 0) is one to the left of the centre), normalized to sum 1. Row-major.
std::vector<double> filterKernel(const FrequencyFilter& filter, int w, int h);
/// Error(Usage), one line naming the parameter, for cutoffs outside (0, 0.75], low ≥ cutoff,
/// a negative order, or a kernel size outside (0, min(w, h)/2).
void validateFilter(const FrequencyFilter& filter, int w, int h);

/// R, G and B each through the filter (DFT, multiply, inverse DFT — circular), plus
/// `offset`; alpha passes through. F32 RGBA, unclamped.
Image frequencyFilterReference(const Image& rgba, const FrequencyFilter& filter);

}  // namespace glint
