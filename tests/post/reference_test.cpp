// The CPU references of image/post.h and image/fourier.h on inputs whose answers are known:
// the YIQ algebra behind "a dot product and an add", luma preservation, Sobel's signs and
// borders, Kuwahara on edges and ties, and the DFT's conventions.
#include "glint/core/error.h"
#include "glint/image/fourier.h"
#include "glint/image/post.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

using namespace glint;

namespace {
Image solid(int w, int h, vec3 rgb) {
  Image image(w, h, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) image.set(x, y, c, rgb[c]);
      image.set(x, y, 3, 1.0f);
    }
  return image;
}

Image randomImage(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  Image image(w, h, 4);
  auto px = image.pixels<std::uint8_t>();
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = std::uint8_t(i % 4 == 3 ? 255 : rng() & 0xFF);
  return image;
}

double luma(dvec3 c) { return kLumaR * c.r + kLumaG * c.g + kLumaB * c.b; }
}  // namespace

TEST(PostReference, YiqMatricesAreInverseAndGrayStaysGray) {
  const auto m = yiqFromRgb(), inv = rgbFromYiq();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += inv[std::size_t(i)][std::size_t(k)] * m[std::size_t(k)][std::size_t(j)];
      EXPECT_NEAR(s, i == j ? 1.0 : 0.0, 1e-12);
    }
  // The I and Q rows sum to zero, so the inverse's first column is (1, 1, 1): with I and Q
  // fixed, RGB' = Y·(1,1,1) + c. That is WWDC 2003 session 212's "dot product and an add".
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(inv[std::size_t(i)][0], 1.0, 1e-12);
  const dvec3 c = sepiaOffset({});
  EXPECT_NEAR(c.r, 0.1912, 5e-4);
  EXPECT_NEAR(c.g, -0.0544, 5e-4);
  EXPECT_NEAR(c.b, -0.2212, 5e-4);
  EXPECT_NEAR(luma(c), 0.0, 1e-12) << "the offset has no luma";
}

TEST(PostReference, SepiaIsDotAndAddInGamutAndKeepsLumaEverywhere) {
  // Mid-gray: in gamut, so exactly Y + c.
  const dvec3 mid = sepiaPixel(dvec3(0.5), {});
  const dvec3 c = sepiaOffset({});
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mid[k], 0.5 + c[k], 1e-12);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0), iq(-0.4, 0.4);
  for (int n = 0; n < 20000; ++n) {
    const dvec3 rgb(u(rng), u(rng), u(rng));
    const SepiaOptions options{.i = n % 2 ? 0.2f : float(iq(rng)), .q = n % 2 ? 0.0f : float(iq(rng))};
    const dvec3 s = sepiaPixel(rgb, options);
    EXPECT_NEAR(luma(s), luma(rgb), 1e-12) << "luma preserved, also where the offset was shortened";
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(s[k], -1e-12);
      EXPECT_LE(s[k], 1.0 + 1e-12);
    }
  }
  // Black and white stay black and white (the offset is shortened to nothing).
  EXPECT_NEAR(glm::length(sepiaPixel(dvec3(0.0), {})), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(sepiaPixel(dvec3(1.0), {}) - dvec3(1.0)), 0.0, 1e-12);
}

TEST(PostReference, SobelSignsAndBorders) {
  // Dark left half, bright right half: vertical edge, Gx = +4 (1 + 2 + 1) across it.
  Image step = solid(8, 6, vec3(0.0f));
  for (int y = 0; y < 6; ++y)
    for (int x = 4; x < 8; ++x)
      for (int c = 0; c < 3; ++c) step.set(x, y, c, 1.0f);
  EXPECT_NEAR(sobelGradient(step, 3, 2).x, 4.0f, 1e-6);  // the kernel straddles the edge at x = 3|4 …
  EXPECT_NEAR(sobelGradient(step, 4, 2).x, 4.0f, 1e-6);  // … from both sides: (1+2+1)·(1 − 0)
  EXPECT_NEAR(sobelGradient(step, 2, 2).x, 0.0f, 1e-6);
  EXPECT_NEAR(sobelGradient(step, 3, 0).y, 0.0f, 1e-6);  // clamp-to-edge: no edge at the top border
  EXPECT_NEAR(sobelGradient(step, 0, 2).x, 0.0f, 1e-6);  // nor at the left border
  const Image sx = sobelReference(step, {.output = SobelOutput::SignedX});
  EXPECT_GT(sx.at(4, 2, 0), 0.5f) << "brighter to the right: positive";
  const Image v = sobelReference(step, {.output = SobelOutput::Vertical});
  const Image h = sobelReference(step, {.output = SobelOutput::Horizontal});
  EXPECT_FLOAT_EQ(v.at(4, 3, 0), 1.0f);  // min(1, 4)
  EXPECT_FLOAT_EQ(h.at(4, 3, 0), 0.0f);
  // Bright bottom rows: Gy positive (y grows downwards).
  Image floor = solid(6, 8, vec3(0.0f));
  for (int y = 5; y < 8; ++y)
    for (int x = 0; x < 6; ++x)
      for (int c = 0; c < 3; ++c) floor.set(x, y, c, 1.0f);
  EXPECT_GT(sobelReference(floor, {.output = SobelOutput::SignedY}).at(2, 5, 0), 0.5f);
  EXPECT_FLOAT_EQ(sobelReference(floor, {.output = SobelOutput::Horizontal}).at(2, 5, 0), 1.0f);
}

TEST(PostReference, KuwaharaPreservesEdgesAndBreaksTiesInOrder) {
  // A step edge survives untouched: every pixel has a quadrant entirely on its own side.
  Image step = solid(10, 10, vec3(0.2f));
  for (int y = 0; y < 10; ++y)
    for (int x = 5; x < 10; ++x)
      for (int c = 0; c < 3; ++c) step.set(x, y, c, 0.8f);
  const auto k = kuwaharaReference(step);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) EXPECT_NEAR(k.image.at(x, y, 0), step.at(x, y, 0), 1e-6) << x << "," << y;
  // Uniform image: all four quadrants tie; the first (upper-left) is chosen.
  const auto flat = kuwaharaReference(solid(4, 4, vec3(0.5f)));
  for (std::size_t i = 0; i < flat.chosen.size(); ++i) {
    EXPECT_EQ(flat.chosen[i], 0);
    EXPECT_EQ(flat.tied[i], 0xF);
  }
  // Noise plus a calm corner: next to the calm region the calm quadrant wins.
  Image noise = randomImage(12, 12, 7);
  for (int y = 6; y < 12; ++y)
    for (int x = 6; x < 12; ++x)
      for (int c = 0; c < 3; ++c) noise.set(x, y, c, 0.5f);
  const auto n = kuwaharaReference(noise, {.size = 3});
  EXPECT_EQ(n.chosen[6 * 12 + 6], 3) << "the lower-right quadrant of (6, 6) is the flat one";
  EXPECT_NEAR(n.image.at(6, 6, 1), 128.0f / 255.0f, 1e-6);  // 0.5 stored as 8 bits
  EXPECT_THROW(kuwaharaReference(noise, {.size = 1}), Error);
}

TEST(PostReference, DftConventions) {
  const int w = 12, h = 10;  // not powers of two
  std::vector<std::complex<double>> delta(std::size_t(w * h), 0.0);
  delta[0] = 1.0;
  for (const auto& f : dft2d(delta, w, h, false)) EXPECT_NEAR(std::abs(f - 1.0), 0.0, 1e-12);
  // A single cosine along x at frequency 3: peaks at u = 3 and u = w − 3, each w·h/2.
  std::vector<std::complex<double>> wave(std::size_t(w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) wave[std::size_t(y * w + x)] = std::cos(2 * std::numbers::pi * 3 * x / w);
  const auto f = dft2d(wave, w, h, false);
  EXPECT_NEAR(f[3].real(), w * h / 2.0, 1e-9);
  EXPECT_NEAR(f[std::size_t(w - 3)].real(), w * h / 2.0, 1e-9);
  EXPECT_NEAR(std::abs(f[4]), 0.0, 1e-9);
  const auto back = dft2d(f, w, h, true);
  for (std::size_t i = 0; i < wave.size(); ++i) EXPECT_NEAR(std::abs(back[i] - wave[i]), 0.0, 1e-12);
  // Centred layout: the DC term sits at ⌊n/2⌋, for odd sizes too.
  EXPECT_EQ(centredIndex(6, 12), 0);
  EXPECT_EQ(centredIndex(2, 5), 0);
  EXPECT_EQ(centredIndex(0, 5), 3);
  EXPECT_EQ(frequencyOf(3, 5), -2);
}

TEST(PostReference, SpectrumAndFiltersOnKnownImages) {
  // A constant image has only a DC term: one bright pixel at the centre.
  const Image gray = solid(9, 8, vec3(0.5f));
  const Image s = spectrumReference(gray);
  const double stored = 128.0 / 255.0;  // 0.5 as 8 bits
  EXPECT_NEAR(s.at(4, 4, 0), std::log1p(stored * 72) / std::log1p(72.0), 1e-6);
  EXPECT_NEAR(s.at(3, 4, 0), 0.0, 1e-6);
  // Low-pass at DC is 1, high-pass 0; any kernel preserves a constant image.
  EXPECT_DOUBLE_EQ(filterGain({.kind = FilterKind::LowPass}, 0, 0, 9, 8), 1.0);
  EXPECT_DOUBLE_EQ(filterGain({.kind = FilterKind::HighPass}, 0, 0, 9, 8), 0.0);
  EXPECT_NEAR(filterGain({.kind = FilterKind::LowPass, .cutoff = 0.25f, .order = 2}, 2, 0, 8, 8), 0.5, 1e-12)
      << "Butterworth is 1/2 at the cutoff";
  const Image blurred = frequencyFilterReference(gray, {.kind = FilterKind::Kernel, .size = 2.0f});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 9; ++x) EXPECT_NEAR(blurred.at(x, y, 1), stored, 1e-6);
  double sum = 0;
  for (double k : filterKernel({.kind = FilterKind::Kernel, .kernel = KernelShape::Disk, .size = 3.0f}, 16, 16)) sum += k;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_THROW(validateFilter({.cutoff = 0.0f}, 8, 8), Error);
  EXPECT_THROW(validateFilter({.kind = FilterKind::BandPass, .cutoff = 0.1f, .low = 0.2f}, 8, 8), Error);
}
