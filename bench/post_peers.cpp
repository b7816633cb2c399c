#include "post_peers.h"

#include <fftw3.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace glint::bench::peers {

namespace {
cv::Mat toMat(const Image& rgba) {
  return cv::Mat(rgba.height(), rgba.width(), CV_8UC4, const_cast<std::byte*>(rgba.bytes().data())).clone();
}
}  // namespace

int peerThreads() { return cv::getNumThreads(); }

Work opencvSepia(const Image& rgba) {
  auto in = std::make_shared<cv::Mat>(toMat(rgba));
  auto out = std::make_shared<cv::Mat>();
  // The widespread sepia matrix (rows R, G, B; alpha kept), applied to 8-bit RGBA.
  auto m = std::make_shared<cv::Mat>((cv::Mat_<float>(4, 4) << 0.393f, 0.769f, 0.189f, 0, 0.349f, 0.686f, 0.168f, 0,
                                      0.272f, 0.534f, 0.131f, 0, 0, 0, 0, 1));
  return [in, out, m] { cv::transform(*in, *out, *m); };
}

Work opencvSobel(const Image& rgba) {
  auto in = std::make_shared<cv::Mat>(toMat(rgba));
  return [in] {
    cv::Mat f, gray, gx, gy, magnitude, out;
    in->convertTo(f, CV_32F, 1.0 / 255.0);
    cv::cvtColor(f, gray, cv::COLOR_RGBA2GRAY);
    cv::Sobel(gray, gx, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
    cv::Sobel(gray, gy, CV_32F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
    cv::magnitude(gx, gy, magnitude);
    magnitude.convertTo(out, CV_8U, 255.0);
  };
}

Work opencvKuwahara(const Image& rgba, int s) {
  auto in = std::make_shared<cv::Mat>(toMat(rgba));
  return [in, s] {
    cv::Mat rgb, f, squares, mean, meanSquares;
    cv::cvtColor(*in, rgb, cv::COLOR_RGBA2RGB);
    rgb.convertTo(f, CV_32FC3, 1.0 / 255.0);
    cv::multiply(f, f, squares);
    // Block statistics with the block's top-left pixel at (x, y): box filter anchored at 0.
    const cv::Size block(s, s);
    cv::Mat padded, paddedSquares;
    const int o = s - 1;
    cv::copyMakeBorder(f, padded, o, o, o, o, cv::BORDER_REPLICATE);
    cv::copyMakeBorder(squares, paddedSquares, o, o, o, o, cv::BORDER_REPLICATE);
    cv::boxFilter(padded, mean, CV_32F, block, cv::Point(0, 0), true, cv::BORDER_REPLICATE);
    cv::boxFilter(paddedSquares, meanSquares, CV_32F, block, cv::Point(0, 0), true, cv::BORDER_REPLICATE);
    cv::Mat out(f.rows, f.cols, CV_32FC3);
    cv::parallel_for_(cv::Range(0, f.rows), [&](const cv::Range& rows) {
      for (int y = rows.start; y < rows.end; ++y) {
        for (int x = 0; x < f.cols; ++x) {
          // Padded index of the block whose top-left pixel is p + corner: p + corner + o.
          const cv::Point corners[4] = {{x, y}, {x + o, y}, {x, y + o}, {x + o, y + o}};
          float best = 1e30f;
          cv::Vec3f chosen;
          for (const auto& c : corners) {
            const cv::Vec3f m = mean.at<cv::Vec3f>(c), q = meanSquares.at<cv::Vec3f>(c);
            const float v = (q[0] - m[0] * m[0]) + (q[1] - m[1] * m[1]) + (q[2] - m[2] * m[2]);
            if (v < best) {
              best = v;
              chosen = m;
            }
          }
          out.at<cv::Vec3f>(y, x) = chosen;
        }
      }
    });
    cv::Mat result;
    out.convertTo(result, CV_8UC3, 255.0);
  };
}

Work opencvSpectrum(const Image& rgba) {
  auto in = std::make_shared<cv::Mat>(toMat(rgba));
  return [in] {
    cv::Mat f, gray, spectrum, planes[2], magnitude, out;
    in->convertTo(f, CV_32F, 1.0 / 255.0);
    cv::cvtColor(f, gray, cv::COLOR_RGBA2GRAY);
    cv::dft(gray, spectrum, cv::DFT_COMPLEX_OUTPUT);
    cv::split(spectrum, planes);
    cv::magnitude(planes[0], planes[1], magnitude);
    magnitude += 1.0f;
    cv::log(magnitude, magnitude);
    magnitude.convertTo(out, CV_8U, 255.0 / std::log(1.0 + double(f.rows) * f.cols));
  };
}

Work opencvFrequencyFilter(const Image& rgba) {
  auto in = std::make_shared<cv::Mat>(toMat(rgba));
  // A real, even transfer function (a Butterworth low-pass), as complex for mulSpectrums.
  auto transfer = std::make_shared<cv::Mat>(in->rows, in->cols, CV_32FC2);
  for (int v = 0; v < in->rows; ++v)
    for (int u = 0; u < in->cols; ++u) {
      const double fu = double(u <= in->cols / 2 ? u : u - in->cols) / in->cols;
      const double fv = double(v <= in->rows / 2 ? v : v - in->rows) / in->rows;
      const double rho = std::sqrt(fu * fu + fv * fv);
      transfer->at<cv::Vec2f>(v, u) = cv::Vec2f(float(1.0 / (1.0 + std::pow(rho / 0.05, 4.0))), 0.0f);
    }
  return [in, transfer] {
    cv::Mat f, channels[4], spectrum, filtered;
    in->convertTo(f, CV_32F, 1.0 / 255.0);
    cv::split(f, channels);
    for (int c = 0; c < 3; ++c) {
      cv::dft(channels[c], spectrum, cv::DFT_COMPLEX_OUTPUT);
      cv::mulSpectrums(spectrum, *transfer, spectrum, 0);
      cv::idft(spectrum, channels[c], cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    }
    cv::merge(channels, 4, filtered);
    filtered.convertTo(f, CV_8UC4, 255.0);
  };
}

namespace {
struct FftwPlan {
  fftwf_complex* in = nullptr;
  fftwf_complex* out = nullptr;
  fftwf_plan plan = nullptr;
  ~FftwPlan() {
    fftwf_destroy_plan(plan);
    fftwf_free(in);
    fftwf_free(out);
  }
};
}  // namespace

Work fftwForward(ivec2 size) {
  static std::once_flag threads;
  std::call_once(threads, [] { fftwf_init_threads(); });
  fftwf_plan_with_nthreads(int(std::max(1u, std::thread::hardware_concurrency())));
  auto p = std::make_shared<FftwPlan>();
  const std::size_t n = std::size_t(size.x) * std::size_t(size.y);
  p->in = fftwf_alloc_complex(n);
  p->out = fftwf_alloc_complex(n);
  p->plan = fftwf_plan_dft_2d(size.y, size.x, p->in, p->out, FFTW_FORWARD, FFTW_MEASURE);
  for (std::size_t i = 0; i < n; ++i) {  // after planning: FFTW_MEASURE overwrites the arrays
    p->in[i][0] = float(i % 255) / 255.0f;
    p->in[i][1] = 0.0f;
  }
  return [p] { fftwf_execute(p->plan); };
}

Work opencvDft(ivec2 size) {
  auto in = std::make_shared<cv::Mat>(size.y, size.x, CV_32FC2, cv::Scalar(0.25, 0.0));
  auto out = std::make_shared<cv::Mat>();
  return [in, out] { cv::dft(*in, *out); };
}

}  // namespace glint::bench::peers
