#include "glint/image/fourier.h"

#include "glint/core/error.h"
#include "glint/image/post.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace glint {

namespace {
using Complex = std::complex<double>;

// One 1D DFT of n values read with `stride`, written back the same way.
void dft1d(Complex* data, int n, std::size_t stride, bool inverse, std::vector<Complex>& scratch,
           const std::vector<Complex>& roots) {
  scratch.assign(std::size_t(n), Complex(0.0));
  for (int k = 0; k < n; ++k) {
    Complex sum(0.0);
    for (int j = 0; j < n; ++j) {
      // e^(∓2πi·j·k/n) from a table indexed by j·k mod n: exact periodicity, no drift.
      const Complex w = roots[std::size_t((std::int64_t(j) * k) % n)];
      sum += data[std::size_t(j) * stride] * (inverse ? std::conj(w) : w);
    }
    scratch[std::size_t(k)] = sum;
  }
  for (int k = 0; k < n; ++k) data[std::size_t(k) * stride] = scratch[std::size_t(k)];
}

std::vector<Complex> unitRoots(int n) {
  std::vector<Complex> roots(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double a = -2.0 * std::numbers::pi * double(j) / double(n);
    roots[std::size_t(j)] = Complex(std::cos(a), std::sin(a));
  }
  return roots;
}

double radialFrequency(int u, int v, int w, int h) {
  const double fu = double(frequencyOf(u, w)) / double(w), fv = double(frequencyOf(v, h)) / double(h);
  return std::sqrt(fu * fu + fv * fv);
}

double lowPass(double rho, double cutoff, int order) {
  if (order == 0) return rho <= cutoff ? 1.0 : 0.0;
  return 1.0 / (1.0 + std::pow(rho / cutoff, 2.0 * order));
}
}  // namespace

std::vector<std::complex<double>> dft2d(std::span<const std::complex<double>> data, int w, int h, bool inverse) {
  if (w <= 0 || h <= 0 || data.size() != std::size_t(w) * std::size_t(h)) {
    fail(ErrorKind::Usage, "dft2d: {} values do not make a {}x{} grid", data.size(), w, h);
  }
  std::vector<Complex> out(data.begin(), data.end());
  std::vector<Complex> scratch;
  const auto rowRoots = unitRoots(w), columnRoots = unitRoots(h);
  for (int y = 0; y < h; ++y) dft1d(out.data() + std::size_t(y) * std::size_t(w), w, 1, inverse, scratch, rowRoots);
  for (int x = 0; x < w; ++x) dft1d(out.data() + x, h, std::size_t(w), inverse, scratch, columnRoots);
  if (inverse) {
    const double scale = 1.0 / (double(w) * double(h));
    for (auto& v : out) v *= scale;
  }
  return out;
}

Image spectrumImage(std::span<const std::complex<double>> spectrum, int w, int h) {
  Image out(w, h, 4, PixelType::F32);
  const double denominator = std::log1p(double(w) * double(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Complex f = spectrum[std::size_t(centredIndex(y, h)) * std::size_t(w) + std::size_t(centredIndex(x, w))];
      const float s = float(std::log1p(std::abs(f)) / denominator);
      for (int c = 0; c < 3; ++c) out.set(x, y, c, s);
      out.set(x, y, 3, 1.0f);
    }
  }
  return out;
}

Image spectrumReference(const Image& rgba) {
  const Image in = postInput(rgba);
  std::vector<Complex> luma(in.pixelCount());
  for (int y = 0; y < in.height(); ++y)
    for (int x = 0; x < in.width(); ++x)
      luma[std::size_t(y) * std::size_t(in.width()) + std::size_t(x)] =
          double(postLuma(vec3(in.at(x, y, 0), in.at(x, y, 1), in.at(x, y, 2))));
  return spectrumImage(dft2d(luma, in.width(), in.height(), false), in.width(), in.height());
}

void validateFilter(const FrequencyFilter& f, int w, int h) {
  if (f.kind == FilterKind::Kernel) {
    const float limit = 0.5f * float(std::min(w, h));
    if (!(f.size > 0.0f) || !(f.size < limit)) {
      fail(ErrorKind::Usage, "kernel size must be in (0, {}) pixels for a {}x{} image, got {}", limit, w, h, f.size);
    }
    return;
  }
  if (!(f.cutoff > 0.0f) || !(f.cutoff <= 0.75f)) {
    fail(ErrorKind::Usage, "cutoff must be in (0, 0.75] cycles per pixel (0.5 = Nyquist), got {}", f.cutoff);
  }
  if (f.kind == FilterKind::BandPass && !(f.low >= 0.0f && f.low < f.cutoff)) {
    fail(ErrorKind::Usage, "band-pass: low must be in [0, cutoff) = [0, {}), got {}", f.cutoff, f.low);
  }
  if (f.order < 0 || f.order > 16) fail(ErrorKind::Usage, "order must be 0 (ideal) to 16, got {}", f.order);
}

double filterGain(const FrequencyFilter& f, int u, int v, int w, int h) {
  const double rho = radialFrequency(u, v, w, h);
  switch (f.kind) {
    case FilterKind::LowPass: return lowPass(rho, f.cutoff, f.order);
    case FilterKind::HighPass: return 1.0 - lowPass(rho, f.cutoff, f.order);
    case FilterKind::BandPass:
      return lowPass(rho, f.cutoff, f.order) - (f.low > 0.0f ? lowPass(rho, f.low, f.order) : 0.0);
    case FilterKind::Kernel: break;
  }
  fail(ErrorKind::Usage, "filterGain: a kernel filter's transfer function is the DFT of its kernel");
}

std::vector<double> filterKernel(const FrequencyFilter& f, int w, int h) {
  std::vector<double> k(std::size_t(w) * std::size_t(h), 0.0);
  double sum = 0.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double dx = frequencyOf(x, w), dy = frequencyOf(y, h);  // wrapped offsets from pixel (0, 0)
      const double r = std::sqrt(dx * dx + dy * dy);
      double value = 0.0;
      if (f.kernel == KernelShape::Gaussian) value = std::exp(-r * r / (2.0 * double(f.size) * double(f.size)));
      else value = std::clamp(double(f.size) + 0.5 - r, 0.0, 1.0);
      k[std::size_t(y) * std::size_t(w) + std::size_t(x)] = value;
      sum += value;
    }
  }
  for (auto& v : k) v /= sum;
  return k;
}

Image frequencyFilterReference(const Image& rgba, const FrequencyFilter& filter) {
  const Image in = postInput(rgba);
  const int w = in.width(), h = in.height();
  validateFilter(filter, w, h);
  std::vector<Complex> transfer(std::size_t(w) * std::size_t(h));
  if (filter.kind == FilterKind::Kernel) {
    const auto kernel = filterKernel(filter, w, h);
    transfer = dft2d(std::vector<Complex>(kernel.begin(), kernel.end()), w, h, false);
  } else {
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) transfer[std::size_t(v) * std::size_t(w) + std::size_t(u)] = filterGain(filter, u, v, w, h);
  }
  Image out(w, h, 4, PixelType::F32);
  std::vector<Complex> channel(in.pixelCount());
  for (int c = 0; c < 3; ++c) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) channel[std::size_t(y) * std::size_t(w) + std::size_t(x)] = double(in.at(x, y, c));
    auto spectrum = dft2d(channel, w, h, false);
    for (std::size_t i = 0; i < spectrum.size(); ++i) spectrum[i] *= transfer[i];
    const auto filtered = dft2d(spectrum, w, h, true);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        out.set(x, y, c, float(filtered[std::size_t(y) * std::size_t(w) + std::size_t(x)].real() + filter.offset));
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out.set(x, y, 3, in.at(x, y, 3));
  return out;
}

}  // namespace glint
