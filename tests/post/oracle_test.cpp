// glint post's GPU passes against independent libraries: Sobel and the spectrum against
// OpenCV (cv::Sobel with BORDER_REPLICATE, cv::dft), the FFT against FFTW in double —
// relative L2 error, inverse(forward(x)) = x and Parseval — at power-of-two, mixed-radix and
// prime sizes. Each test prints its figure ("[figure] ...") for docs/post.md.
//
// OpenCV's headers are heavy: this is the only test file that includes them.
#include "glint/core/error.h"
#include "glint/image/fourier.h"
#include "glint/image/post.h"
#include "glint/render/post/chain.h"
#include "glint/render/post/fft.h"
#include "glint/render/post/passes.h"

#include "post_test_util.h"
#include "support/gl_test.h"

#include <fftw3.h>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

using namespace glint;
using namespace glint::render::post;
using glint::testing::compareSteps;
using glint::testing::noiseImage;
using glint::testing::photograph;

namespace {
class PostOracle : public glint::testing::GlTest {};

cv::Mat toMat(const Image& rgba) {
  cv::Mat m(rgba.height(), rgba.width(), CV_8UC4, const_cast<std::byte*>(rgba.bytes().data()));
  return m.clone();
}

// OpenCV's luma of an RGBA8 image, in float: cvtColor's RGBA2GRAY weights are BT.601's.
cv::Mat grayOf(const Image& rgba) {
  cv::Mat f, gray;
  toMat(rgba).convertTo(f, CV_32F, 1.0 / 255.0);
  cv::cvtColor(f, gray, cv::COLOR_RGBA2GRAY);
  return gray;
}

// A one-channel float Mat as a gray F32 RGBA Image.
Image grayImage(const cv::Mat& m) {
  Image out(m.cols, m.rows, 4, PixelType::F32);
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x) {
      for (int c = 0; c < 3; ++c) out.set(x, y, c, m.at<float>(y, x));
      out.set(x, y, 3, 1.0f);
    }
  return out;
}

Image runPass(const Image& input, const std::function<void(const gl::Texture&, const gl::Texture&)>& pass) {
  const gl::Texture in = uploadFrame(input, "oracle-input");
  gl::Texture out(GL_TEXTURE_2D, "oracle-output");
  out.storage(GL_RGBA8, input.width(), input.height());
  pass(in, out);
  return readFrame(out);
}

double relativeL2(std::span<const std::complex<float>> a, std::span<const std::complex<double>> b) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += std::norm(std::complex<double>(a[i]) - b[i]);
    den += std::norm(b[i]);
  }
  return std::sqrt(num / den);
}

std::vector<std::complex<double>> fftw(std::span<const std::complex<float>> in, int w, int h, int sign) {
  std::vector<std::complex<double>> a(in.begin(), in.end()), out(a.size());
  fftw_plan plan = fftw_plan_dft_2d(h, w, reinterpret_cast<fftw_complex*>(a.data()),
                                    reinterpret_cast<fftw_complex*>(out.data()), sign, FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  return out;
}
}  // namespace

TEST_F(PostOracle, SobelMatchesOpenCv) {
  SobelPass sobel;
  for (const auto& [name, image] : {std::pair<std::string, Image>{"photo", photograph()}, {"noise", noiseImage(128, 96, 5)}}) {
    const cv::Mat gray = grayOf(image);
    cv::Mat gx, gy, magnitude;
    cv::Sobel(gray, gx, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
    cv::Sobel(gray, gy, CV_32F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
    cv::magnitude(gx, gy, magnitude);
    const float scale = 1.5f;
    const auto clamp01 = [](const cv::Mat& m) {
      cv::Mat r;
      cv::min(cv::max(m, 0.0), 1.0, r);
      return r;
    };
    const std::vector<std::pair<SobelOutput, cv::Mat>> cases = {
        {SobelOutput::Magnitude, clamp01(magnitude * scale)},
        {SobelOutput::Horizontal, clamp01(cv::abs(gy) * scale)},
        {SobelOutput::Vertical, clamp01(cv::abs(gx) * scale)},
        {SobelOutput::SignedX, clamp01(0.5 + 0.5 * scale * gx)},
        {SobelOutput::SignedY, clamp01(0.5 + 0.5 * scale * gy)}};
    for (const auto& [output, expected] : cases) {
      const SobelOutput which = output;  // a plain copy: the lambda captures it (clang 14 cannot capture bindings)
      const Image gpu = runPass(image, [&](auto& in, auto& out) { sobel.run(in, out, {.output = which, .scale = scale}); });
      const auto d = compareSteps(gpu, grayImage(expected));
      EXPECT_LE(d.maxSteps, 1) << name << " output " << int(output) << " at " << d.worstX << "," << d.worstY;
      std::printf("[figure] sobel %s output %d vs cv::Sobel: max %d step(s), mean %.4f steps\n", name.c_str(),
                  int(output), d.maxSteps, d.meanSteps);
    }
  }
}

// Both GPU paths: on llvmpipe the complex FFT pass by pass (the default there), and the
// real-input transform fused with the view (GLINT_FFT_AXES=shared; both sizes fit it).
TEST_F(PostOracle, SpectrumMatchesOpenCvDft) {
  for (const char* axes : {"passes", "shared"})
  for (const Image& image : {photograph(), noiseImage(90, 64, 9)}) {
    ::setenv("GLINT_FFT_AXES", axes, 1);
    const int w = image.width(), h = image.height();
    cv::Mat complexSpectrum;
    cv::dft(grayOf(image), complexSpectrum, cv::DFT_COMPLEX_OUTPUT);
    Image expected(w, h, 4, PixelType::F32);
    const double denominator = std::log1p(double(w) * double(h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const auto f = complexSpectrum.at<cv::Vec2f>(centredIndex(y, h), centredIndex(x, w));
        const float s = float(std::log1p(std::hypot(double(f[0]), double(f[1]))) / denominator);
        for (int c = 0; c < 3; ++c) expected.set(x, y, c, s);
        expected.set(x, y, 3, 1.0f);
      }
    SpectrumPass spectrum;
    const Image gpu = runPass(image, [&](auto& in, auto& out) { spectrum.run(in, out); });
    const auto d = compareSteps(gpu, expected);
    EXPECT_LE(d.maxSteps, 1) << w << "x" << h;
    std::printf("[figure] spectrum %dx%d (%s) vs cv::dft: max %d step(s), mean %.4f steps\n", w, h,
                RealFft2d::fits({w, h}) && std::string_view(axes) == "shared" ? "real-input, fused" : "complex, passes",
                d.maxSteps, d.meanSteps);
  }
  ::unsetenv("GLINT_FFT_AXES");
}

// The real-input transform (RealFft2d: the spectrum's and the filters' path on a GPU): each
// channel's half spectrum against FFTW's r2c in double of the same values — the luma
// (1 channel) and R, G, B (3) — at a video size, a small odd-radix one (90 = 2·45) and the
// widest the path takes (4096: rows of 2048 complex values).
TEST_F(PostOracle, RealFftMatchesFftwR2cInDouble) {
  for (const ivec2 size : {ivec2(90, 64), ivec2(640, 480), ivec2(4096, 4)}) {
    ASSERT_TRUE(RealFft2d::fits(size));
    const Image image = noiseImage(size.x, size.y, 5);
    const gl::Texture texture = uploadFrame(image, "real-fft-input");
    const std::size_t n = std::size_t(size.x) * std::size_t(size.y), half = std::size_t(size.x / 2 + 1);
    std::vector<double> x(n);
    std::vector<std::complex<double>> expected(half * std::size_t(size.y));
    for (const int channels : {1, 3}) {
      RealFft2d fft(size, channels);
      for (int c = 0; c < channels; ++c) {
        for (int y = 0; y < size.y; ++y)
          for (int px = 0; px < size.x; ++px) {
            const auto value = [&](int k) { return double(float(image.at(px, y, k))); };
            x[std::size_t(y) * std::size_t(size.x) + std::size_t(px)] =
                channels == 1 ? 0.299 * value(0) + 0.587 * value(1) + 0.114 * value(2) : value(c);
          }
        fftw_plan plan = fftw_plan_dft_r2c_2d(size.y, size.x, x.data(), reinterpret_cast<fftw_complex*>(expected.data()),
                                              FFTW_ESTIMATE);
        fftw_execute(plan);
        fftw_destroy_plan(plan);
        const double error = relativeL2(fft.halfSpectrum(texture, c), expected);
        EXPECT_LE(error, 1e-5) << size.x << "x" << size.y << " channel " << c << " of " << channels;
        std::printf("[figure] real-input FFT %dx%d, channel %d of %d, vs FFTW r2c in double: relative L2 %.3g\n", size.x,
                    size.y, c, channels, error);
      }
    }
  }
  // Sizes it does not take (the passes fall back on the complex FFT), and a texture of
  // another size: usage errors, nothing dispatched.
  EXPECT_FALSE(RealFft2d::fits({91, 64}));   // odd width
  EXPECT_FALSE(RealFft2d::fits({4098, 4}));  // rows over 2048 complex values
  EXPECT_FALSE(RealFft2d::fits({60, 44}));   // a factor 11
  EXPECT_THROW(RealFft2d({91, 64}, 1), Error);
  EXPECT_THROW(RealFft2d({90, 64}, 2), Error);
  RealFft2d small({90, 64}, 1);
  const gl::Texture other = uploadFrame(noiseImage(64, 64, 1), "real-fft-other");
  EXPECT_THROW(small.forwardRows(other), Error);
}

static void checkAgainstFftw(ivec2 size, bool sharedAxes) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  {
    const std::size_t n = std::size_t(size.x) * std::size_t(size.y);
    std::vector<std::complex<float>> x(n);
    for (auto& v : x) v = {u(rng), u(rng)};
    Fft2d fft(size);
    fft.setSharedAxes(sharedAxes);
    const auto forward = fft.forward(x);
    const double forwardError = relativeL2(forward, fftw(x, size.x, size.y, FFTW_FORWARD));
    auto backward = fftw(x, size.x, size.y, FFTW_BACKWARD);  // FFTW's inverse is unnormalized
    for (auto& v : backward) v /= double(n);
    const double inverseError = relativeL2(fft.inverse(x), backward);
    const auto roundTrip = fft.inverse(forward);
    std::vector<std::complex<double>> xd(x.begin(), x.end());
    const double roundTripError = relativeL2(roundTrip, xd);
    double energy = 0, spectralEnergy = 0;
    for (std::size_t i = 0; i < n; ++i) {
      energy += std::norm(std::complex<double>(x[i]));
      spectralEnergy += std::norm(std::complex<double>(forward[i]));
    }
    const double parseval = std::abs(spectralEnergy / double(n) - energy) / energy;
    EXPECT_LE(forwardError, 1e-5) << size.x << "x" << size.y;
    EXPECT_LE(inverseError, 1e-5) << size.x << "x" << size.y;
    EXPECT_LE(roundTripError, 1e-5) << size.x << "x" << size.y;
    EXPECT_LE(parseval, 1e-5) << size.x << "x" << size.y;
    std::printf("[figure] fft %dx%d (%s, %d dispatches) vs FFTW double: forward %.2e, inverse %.2e, inverse(forward) "
                "%.2e, Parseval %.2e\n",
                size.x, size.y, fft.inSharedMemory(0) || fft.inSharedMemory(1) ? "shared-memory axes" : "passes",
                fft.dispatches(), forwardError, inverseError, roundTripError, parseval);
  }
}

// Powers of two, a video size (2·3·5-smooth: radices 4, 2, 3, 5), primes (direct radix-p
// steps; 97 > 16 takes the no-array path). Pass by pass and with the shared-memory axes
// (fft_axis.comp; the primes stay pass by pass).
TEST_F(PostOracle, FftMatchesFftwInDouble) {
  for (const bool shared : {false, true})
    for (const ivec2 size : {ivec2(256, 256), ivec2(512, 512), ivec2(640, 480), ivec2(97, 61)})
      checkAgainstFftw(size, shared);
  Fft2d video({1920, 1080});
  video.setSharedAxes(true);
  EXPECT_TRUE(video.inSharedMemory(0) && video.inSharedMemory(1));
  EXPECT_EQ(video.dispatches(), 2);
  video.setSharedAxes(false);
  EXPECT_EQ(video.dispatches(), int(video.radices(0).size() + video.radices(1).size()));
}

// The largest sizes (about 5 s on llvmpipe, most of it FFTW planning-free execution
// and the transfers).
TEST_F(PostOracle, FftMatchesFftwAtLargeSizes) {
  // Pass by pass at both; the shared-memory axes at 1024² (at 2048² they double llvmpipe's
  // time: FftMatchesFftwInDouble has them at four other sizes).
  for (const ivec2 size : {ivec2(1024, 1024), ivec2(2048, 2048)}) checkAgainstFftw(size, false);
  checkAgainstFftw({1024, 1024}, true);
}
