#include "glint/post/cpu.h"

#include "cpu_kernels.h"

#include "glint/core/error.h"
#include "glint/image/fourier.h"
#include "glint/image/post.h"

#include <fftw3.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <mutex>
#include <thread>

static_assert(std::endian::native == std::endian::little, "the RGBA8 tables assume R in the low byte");

namespace glint::post {

Backend parseBackend(std::string_view name) {
  if (name == "auto") return Backend::Auto;
  if (name == "gpu") return Backend::Gpu;
  if (name == "cpu") return Backend::Cpu;
  fail(ErrorKind::Usage, "--backend must be auto, gpu or cpu, got '{}'", name);
}

const char* backendName(Backend backend) {
  switch (backend) {
    case Backend::Auto: return "auto";
    case Backend::Gpu: return "gpu";
    case Backend::Cpu: return "cpu";
  }
  return "?";
}

bool isSoftwareRenderer(std::string_view r) {
  for (const std::string_view name : {"llvmpipe", "softpipe", "SwiftShader", "GDI Generic", "Software Renderer"}) {
    if (r.find(name) != std::string_view::npos) return true;
  }
  return false;
}

namespace cpu {

void parallelRows(int rows, const std::function<void(int, int)>& body) {
  // Bands of at least 16 rows: enough work per task to hide the pool's overhead.
  const int stripes = std::max(1, std::min(rows / 16, 4 * cv::getNumThreads()));
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& r) { body(r.start, r.end); }, stripes);
}

void sobelRows(const float* luma, int w, int h, const std::function<void(int, const float*, const float*)>& write) {
  parallelRows(h, [&](int begin, int end) {
    const auto n = static_cast<std::size_t>(w);
    std::vector<float> gx(n), gy(n), sx(n + 2), dy(n + 2);
    for (int y = begin; y < end; ++y) {
      const float* up = luma + std::size_t(std::max(y - 1, 0)) * std::size_t(w);
      const float* mid = luma + std::size_t(y) * std::size_t(w);
      const float* down = luma + std::size_t(std::min(y + 1, h - 1)) * std::size_t(w);
      // Vertical passes first (smooth [1 2 1] and difference [-1 0 1]), with the row's ends
      // repeated, then the horizontal ones: separable, and each loop vectorises.
      for (int x = 0; x < w; ++x) {
        sx[std::size_t(x) + 1] = up[x] + 2.0f * mid[x] + down[x];
        dy[std::size_t(x) + 1] = down[x] - up[x];
      }
      sx[0] = sx[1];
      sx[std::size_t(w) + 1] = sx[std::size_t(w)];
      dy[0] = dy[1];
      dy[std::size_t(w) + 1] = dy[std::size_t(w)];
      for (int x = 0; x < w; ++x) {
        gx[std::size_t(x)] = sx[std::size_t(x) + 2] - sx[std::size_t(x)];
        gy[std::size_t(x)] = dy[std::size_t(x)] + 2.0f * dy[std::size_t(x) + 1] + dy[std::size_t(x) + 2];
      }
      write(y, gx.data(), gy.data());
    }
  });
}

namespace {
std::once_flag fftwThreadsOnce;
std::mutex fftwPlanMutex;  // FFTW's planner is not thread-safe

// The single-precision planner, for plans on every hardware thread: FFTW's threads set up
// once, the planner held while the returned lock lives.
std::unique_lock<std::mutex> lockFloatPlanner() {
  std::call_once(fftwThreadsOnce, [] { fftwf_init_threads(); });
  std::unique_lock lock(fftwPlanMutex);
  fftwf_plan_with_nthreads(int(std::max(1u, std::thread::hardware_concurrency())));
  return lock;
}
}  // namespace

PlaneFilter::PlaneFilter(int w, int h, int planes, const FrequencyFilter& filter) : m_w(w), m_h(h), m_planes(planes) {
  const int half = w / 2 + 1;
  const std::size_t n = std::size_t(w) * std::size_t(h), spectrum = std::size_t(half) * std::size_t(h);
  m_real = fftwf_alloc_real(n * std::size_t(planes));
  m_spectrum = fftwf_alloc_complex(spectrum * std::size_t(planes));
  // H on the r2c half-spectrum, with the inverse's 1/(w·h).
  m_gain.resize(spectrum);
  const double scale = 1.0 / double(n);
  if (filter.kind == FilterKind::Kernel) {
    // The kernel is even on the periodic grid, so its DFT is real.
    const std::vector<double> kernel = filterKernel(filter, w, h);
    std::vector<double> in(kernel);
    fftw_complex* out = fftw_alloc_complex(spectrum);
    {
      std::lock_guard lock(fftwPlanMutex);
      fftw_plan p = fftw_plan_dft_r2c_2d(h, w, in.data(), out, FFTW_ESTIMATE);
      fftw_execute(p);
      fftw_destroy_plan(p);
    }
    for (std::size_t i = 0; i < spectrum; ++i) m_gain[i] = float(out[i][0] * scale);
    fftw_free(out);
  } else {
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < half; ++u) m_gain[std::size_t(v) * half + u] = float(filterGain(filter, u, v, w, h) * scale);
  }
  const auto lock = lockFloatPlanner();
  const int dims[2] = {h, w};
  auto* spec = static_cast<fftwf_complex*>(m_spectrum);
  // FFTW_ESTIMATE: at 1920×1080 FFTW_MEASURE spent 9 s planning for a transform no faster
  // than the estimated plan's (measured on this project's 2-core machine).
  m_forward = fftwf_plan_many_dft_r2c(2, dims, planes, m_real, nullptr, 1, int(n), spec, nullptr, 1, int(spectrum),
                                      FFTW_ESTIMATE);
  m_inverse = fftwf_plan_many_dft_c2r(2, dims, planes, spec, nullptr, 1, int(spectrum), m_real, nullptr, 1, int(n),
                                      FFTW_ESTIMATE);
  if (!m_forward || !m_inverse) fail(ErrorKind::Internal, "FFTW could not plan a {}x{} transform", w, h);
}

PlaneFilter::~PlaneFilter() {
  std::lock_guard lock(fftwPlanMutex);
  if (m_forward) fftwf_destroy_plan(static_cast<fftwf_plan>(m_forward));
  if (m_inverse) fftwf_destroy_plan(static_cast<fftwf_plan>(m_inverse));
  fftwf_free(m_real);
  fftwf_free(m_spectrum);
}

void PlaneFilter::run() {
  fftwf_execute(static_cast<fftwf_plan>(m_forward));
  const std::size_t spectrum = m_gain.size();
  auto* spec = static_cast<fftwf_complex*>(m_spectrum);
  const int half = m_w / 2 + 1;
  parallelRows(m_h * m_planes, [&](int begin, int end) {
    for (int row = begin; row < end; ++row) {
      const float* g = m_gain.data() + std::size_t(row % m_h) * std::size_t(half);
      float* s = spec[std::size_t(row / m_h) * spectrum + std::size_t(row % m_h) * std::size_t(half)];
      for (int u = 0; u < half; ++u) {
        s[2 * u] *= g[u];
        s[2 * u + 1] *= g[u];
      }
    }
  });
  fftwf_execute(static_cast<fftwf_plan>(m_inverse));
}


}  // namespace cpu

namespace {
using cpu::parallelRows;

inline std::uint8_t toU8(float v) { return std::uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); }

using RgbaStage = CpuStage;

// The YIQ luma of every pixel, in [0, 1] (float, as the shader's dot product).
void lumaPlane(const Image& in, std::vector<float>& luma) {
  const int w = in.width(), h = in.height();
  luma.resize(std::size_t(w) * std::size_t(h));
  const std::uint8_t* px = in.pixels<std::uint8_t>().data();
  const float r = float(kLumaR) / 255.0f, g = float(kLumaG) / 255.0f, b = float(kLumaB) / 255.0f;
  parallelRows(h, [&](int begin, int end) {
    for (std::size_t i = std::size_t(begin) * w; i < std::size_t(end) * w; ++i) {
      luma[i] = r * float(px[4 * i]) + g * float(px[4 * i + 1]) + b * float(px[4 * i + 2]);
    }
  });
}

// The Sobel gradient of `in`'s luma at every pixel: pixel(src, dst, gx, gy) writes dst's
// RGBA from src's and the gradient (sobel and edges differ only there).
template <typename Pixel>
void eachSobelPixel(const Image& in, Image& out, std::vector<float>& luma, Pixel pixel) {
  lumaPlane(in, luma);
  const int w = in.width();
  const std::uint8_t* src = in.pixels<std::uint8_t>().data();
  std::uint8_t* dst = out.pixels<std::uint8_t>().data();
  cpu::sobelRows(luma.data(), w, in.height(), [&](int y, const float* gx, const float* gy) {
    const std::size_t row = std::size_t(y) * std::size_t(w);
    for (int x = 0; x < w; ++x) {
      const std::size_t i = 4 * (row + std::size_t(x));
      pixel(src + i, dst + i, gx[x], gy[x]);
    }
  });
}

// Sepia: the result is a function of the luma alone (image/post.h), so it is a table
// indexed by the luma, exactly: 1000·255·L = 299·R + 587·G + 114·B is an integer in
// 0..255000, and each entry is the reference's own rounding of sepiaPixel at that luma
// (a 1 MiB table, made once per chain; a video's lumas stay in a few cache lines' worth).
// A coarser table would round differently where L + t·c falls near half a step, and a
// following Sobel doubles such differences.
class SepiaStage final : public RgbaStage {
public:
  explicit SepiaStage(const Effect& e) : m_table(kEntries) {
    const SepiaOptions options{.i = e.value("i"), .q = e.value("q")};
    parallelRows(kEntries, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) {
        const dvec3 rgb = sepiaPixel(dvec3(double(i) / double(kEntries - 1)), options);
        std::uint32_t packed = 0;
        for (int k = 0; k < 3; ++k) packed |= std::uint32_t(std::lround(std::clamp(rgb[k], 0.0, 1.0) * 255.0)) << (8 * k);
        m_table[std::size_t(i)] = packed;
      }
    });
  }
  void run(const Image& in, Image& out) override {
    const std::size_t w = std::size_t(in.width());
    const auto* src = reinterpret_cast<const std::uint32_t*>(in.pixels<std::uint8_t>().data());
    auto* dst = reinterpret_cast<std::uint32_t*>(out.pixels<std::uint8_t>().data());
    const std::uint32_t* table = m_table.data();
    parallelRows(in.height(), [&](int begin, int end) {
      const std::size_t first = std::size_t(begin) * w, last = std::size_t(end) * w;
      for (std::size_t i = first; i < last; ++i) {
        const std::uint32_t p = src[i];  // RGBA in memory: R in the low byte (little-endian)
        const std::uint32_t index = 299u * (p & 0xFF) + 587u * ((p >> 8) & 0xFF) + 114u * ((p >> 16) & 0xFF);
        dst[i] = table[index] | (p & 0xFF000000u);
      }
    });
  }

private:
  static constexpr int kEntries = 255001;  // 1000·255·L for L in [0, 1]
  std::vector<std::uint32_t> m_table;
};

class SobelStage final : public RgbaStage {
public:
  explicit SobelStage(const Effect& e) : m_scale(e.value("scale")) {
    constexpr SobelOutput outputs[] = {SobelOutput::Magnitude, SobelOutput::Horizontal, SobelOutput::Vertical,
                                       SobelOutput::SignedX, SobelOutput::SignedY};
    m_output = outputs[int(e.value("output"))];
  }
  void run(const Image& in, Image& out) override {
    eachSobelPixel(in, out, m_luma, [&](const std::uint8_t* src, std::uint8_t* dst, float gx, float gy) {
      dst[0] = dst[1] = dst[2] = toU8(cpu::sobelValue(gx, gy, m_output, m_scale));
      dst[3] = src[3];
    });
  }

private:
  SobelOutput m_output;
  float m_scale;
  std::vector<float> m_luma;
};

class EdgesStage final : public RgbaStage {
public:
  explicit EdgesStage(const Effect& e) : m_scale(e.value("scale")), m_threshold(e.value("threshold")) {}
  void run(const Image& in, Image& out) override {
    eachSobelPixel(in, out, m_luma, [&](const std::uint8_t* src, std::uint8_t* dst, float gx, float gy) {
      const float e = std::clamp(m_scale * (std::sqrt(gx * gx + gy * gy) - m_threshold), 0.0f, 1.0f);
      for (int c = 0; c < 3; ++c) dst[c] = toU8(float(src[c]) / 255.0f * (1.0f - e));
      dst[3] = src[3];
    });
  }

private:
  float m_scale, m_threshold;
  std::vector<float> m_luma;
};

// Kuwahara: OpenCV's box filter gives every s×s window's sums (Σk per channel, Σ(r²+g²+b²)),
// exact in float (integers below 2²⁴); the variance comparison is then done in 64-bit
// integers, as image/post.h's reference does.
class KuwaharaStage final : public RgbaStage {
public:
  explicit KuwaharaStage(const Effect& e) : m_size(int(e.value("size"))) {}
  void run(const Image& in, Image& out) override {
    const int s = m_size, w = in.width(), h = in.height(), pad = s - 1;
    const cv::Mat rgba(h, w, CV_8UC4, const_cast<std::uint8_t*>(in.pixels<std::uint8_t>().data()));
    cv::Mat padded;
    cv::copyMakeBorder(rgba, padded, pad, pad, pad, pad, cv::BORDER_REPLICATE);
    const int pw = padded.cols, ph = padded.rows;
    m_values.create(ph, pw, CV_32FC4);  // r, g, b, r² + g² + b²
    parallelRows(ph, [&](int begin, int end) {
      for (int y = begin; y < end; ++y) {
        const std::uint8_t* p = padded.ptr<std::uint8_t>(y);
        float* v = m_values.ptr<float>(y);
        for (int x = 0; x < pw; ++x) {
          const float r = p[4 * x], g = p[4 * x + 1], b = p[4 * x + 2];
          v[4 * x] = r;
          v[4 * x + 1] = g;
          v[4 * x + 2] = b;
          v[4 * x + 3] = r * r + g * g + b * b;
        }
      }
    });
    // sums(i, j) = Σ over the window whose top-left corner is padded pixel (i, j).
    cv::boxFilter(m_values, m_sums, CV_32F, cv::Size(s, s), cv::Point(0, 0), false, cv::BORDER_REPLICATE);
    const std::int64_t n = std::int64_t(s) * s;
    const std::uint8_t* src = in.pixels<std::uint8_t>().data();
    std::uint8_t* dst = out.pixels<std::uint8_t>().data();
    const int corner[4][2] = {{-(s - 1), -(s - 1)}, {0, -(s - 1)}, {-(s - 1), 0}, {0, 0}};
    parallelRows(h, [&](int begin, int end) {
      for (int y = begin; y < end; ++y) {
        const float* rows[4];
        for (int q = 0; q < 4; ++q) rows[q] = m_sums.ptr<float>(y + corner[q][1] + pad);
        for (int x = 0; x < w; ++x) {
          int chosen = 0;
          std::int64_t best = INT64_MAX;
          const float* window[4];
          for (int q = 0; q < 4; ++q) {
            window[q] = rows[q] + 4 * (x + corner[q][0] + pad);
            const auto r = std::int64_t(window[q][0]), g = std::int64_t(window[q][1]), b = std::int64_t(window[q][2]);
            const std::int64_t d = n * std::int64_t(window[q][3]) - (r * r + g * g + b * b);
            if (d < best) {
              best = d;
              chosen = q;
            }
          }
          const std::size_t i = 4 * (std::size_t(y) * std::size_t(w) + std::size_t(x));
          for (int c = 0; c < 3; ++c) dst[i + std::size_t(c)] = toU8(window[chosen][c] / float(n * 255));
          dst[i + 3] = src[i + 3];
        }
      }
    });
  }

private:
  int m_size;
  cv::Mat m_values, m_sums;
};

class FilterStage final : public RgbaStage {
public:
  FilterStage(const FrequencyFilter& f, ivec2 size) : m_offset(f.offset), m_filter(size.x, size.y, 3, f) {}
  void run(const Image& in, Image& out) override {
    const std::size_t n = in.pixelCount();
    const std::uint8_t* src = in.pixels<std::uint8_t>().data();
    std::uint8_t* dst = out.pixels<std::uint8_t>().data();
    float* planes = m_filter.data();
    const std::size_t w = std::size_t(in.width());
    parallelRows(in.height(), [&](int begin, int end) {
      for (std::size_t i = std::size_t(begin) * w; i < std::size_t(end) * w; ++i) {
        for (std::size_t c = 0; c < 3; ++c) planes[c * n + i] = float(src[4 * i + c]) / 255.0f;
      }
    });
    m_filter.run();
    parallelRows(in.height(), [&](int begin, int end) {
      for (std::size_t i = std::size_t(begin) * w; i < std::size_t(end) * w; ++i) {
        for (std::size_t c = 0; c < 3; ++c) dst[4 * i + c] = toU8(planes[c * n + i] + m_offset);
        dst[4 * i + 3] = src[4 * i + 3];
      }
    });
  }

private:
  float m_offset;
  cpu::PlaneFilter m_filter;
};

// The spectrum view (image/fourier.h): log(1 + |F|) / log(1 + w·h) of the luma's DFT,
// centred, as gray with alpha 1 — FFTW's real-to-complex transform (single precision,
// threads) gives the half-spectrum; the other half is its mirror, |F(u, v)| =
// |F(w − u, h − v)| for a real input.
class SpectrumStage final : public RgbaStage {
public:
  explicit SpectrumStage(ivec2 size) : m_w(size.x), m_h(size.y), m_half(size.x / 2 + 1) {
    const std::size_t n = std::size_t(m_w) * std::size_t(m_h);
    m_real = fftwf_alloc_real(n);
    m_spectrum = fftwf_alloc_complex(std::size_t(m_half) * std::size_t(m_h));
    const auto lock = cpu::lockFloatPlanner();
    m_plan = fftwf_plan_dft_r2c_2d(m_h, m_w, m_real, m_spectrum, FFTW_ESTIMATE);
    if (!m_plan) fail(ErrorKind::Internal, "FFTW could not plan a {}x{} transform", m_w, m_h);
  }
  ~SpectrumStage() override {
    std::lock_guard lock(cpu::fftwPlanMutex);
    fftwf_destroy_plan(m_plan);
    fftwf_free(m_real);
    fftwf_free(m_spectrum);
  }
  SpectrumStage(const SpectrumStage&) = delete;
  SpectrumStage& operator=(const SpectrumStage&) = delete;

  void run(const Image& in, Image& out) override {
    lumaPlane(in, m_luma);
    std::memcpy(m_real, m_luma.data(), m_luma.size() * sizeof(float));
    fftwf_execute(m_plan);
    const float denominator = float(std::log1p(double(m_w) * double(m_h)));
    std::uint8_t* dst = out.pixels<std::uint8_t>().data();
    parallelRows(m_h, [&](int begin, int end) {
      for (int y = begin; y < end; ++y) {
        const int v = (y - m_h / 2 + m_h) % m_h;  // output row y shows frequency row v
        for (int x = 0; x < m_w; ++x) {
          const int u = (x - m_w / 2 + m_w) % m_w;
          const fftwf_complex& f = u < m_half ? m_spectrum[std::size_t(v) * std::size_t(m_half) + std::size_t(u)]
                                              : m_spectrum[std::size_t((m_h - v) % m_h) * std::size_t(m_half) + std::size_t(m_w - u)];
          const std::uint8_t g = toU8(std::log1p(std::hypot(f[0], f[1])) / denominator);
          std::uint8_t* p = dst + 4 * (std::size_t(y) * std::size_t(m_w) + std::size_t(x));
          p[0] = p[1] = p[2] = g;
          p[3] = 255;
        }
      }
    });
  }

private:
  int m_w, m_h, m_half;
  float* m_real = nullptr;
  fftwf_complex* m_spectrum = nullptr;
  fftwf_plan m_plan = nullptr;
  std::vector<float> m_luma;
};

}  // namespace

namespace cpu {
std::unique_ptr<CpuStage> sepia(const Effect& e, ivec2) { return std::make_unique<SepiaStage>(e); }
std::unique_ptr<CpuStage> sobel(const Effect& e, ivec2) { return std::make_unique<SobelStage>(e); }
std::unique_ptr<CpuStage> edges(const Effect& e, ivec2) { return std::make_unique<EdgesStage>(e); }
std::unique_ptr<CpuStage> kuwahara(const Effect& e, ivec2) { return std::make_unique<KuwaharaStage>(e); }
std::unique_ptr<CpuStage> spectrum(const Effect&, ivec2 size) { return std::make_unique<SpectrumStage>(size); }
std::unique_ptr<CpuStage> filter(const Effect& e, ivec2 size) {
  return std::make_unique<FilterStage>(e.def->filter(e), size);
}
}  // namespace cpu

std::string cpuMissing(std::span<const Effect> effects) {
  std::string missing;
  for (const Effect& e : effects) {
    if (e.def->cpu || missing.find(e.name()) != std::string::npos) continue;
    missing += (missing.empty() ? "" : ", ") + std::string(e.name());
  }
  return missing;
}

bool cpuWorksOnYuv(std::span<const Effect> effects) { return effects.size() == 1 && effects[0].def->yuv; }

struct CpuChain::Impl {
  ivec2 size;
  std::vector<Effect> effects;
  std::vector<std::unique_ptr<CpuStage>> stages;
  std::unique_ptr<YuvStage> yuv;  // a one-effect chain with a YUV path
  Image scratch;
};

CpuChain::CpuChain(ivec2 size, std::vector<Effect> effects) : m_impl(std::make_unique<Impl>()) {
  for (const Effect& e : effects) validateEffect(e, size);
  if (const std::string missing = cpuMissing(effects); !missing.empty()) {
    fail(ErrorKind::Usage, "--backend cpu: no CPU version of {} yet (use --backend gpu)", missing);
  }
  m_impl->size = size;
  for (const Effect& e : effects) m_impl->stages.push_back(e.def->cpu(e, size));
  if (effects.size() == 1 && effects[0].def->yuv && size.x % 2 == 0 && size.y % 2 == 0)
    m_impl->yuv = effects[0].def->yuv(effects[0], size);
  m_impl->effects = std::move(effects);
}

CpuChain::~CpuChain() = default;
CpuChain::CpuChain(CpuChain&&) noexcept = default;
CpuChain& CpuChain::operator=(CpuChain&&) noexcept = default;

Image CpuChain::run(const Image& input) {
  Image frame = postInput(input);
  if (frame.width() != m_impl->size.x || frame.height() != m_impl->size.y) {
    fail(ErrorKind::Internal, "CpuChain: a {}x{} frame for a {}x{} chain", frame.width(), frame.height(),
         m_impl->size.x, m_impl->size.y);
  }
  Image& scratch = m_impl->scratch;
  if (scratch.width() != frame.width() || scratch.height() != frame.height()) {
    scratch = Image(frame.width(), frame.height(), 4, PixelType::U8);
  }
  for (auto& stage : m_impl->stages) {
    stage->run(frame, scratch);
    std::swap(frame, scratch);
  }
  return frame;
}

void CpuChain::run(video::Frame& frame) {
  if (frame.format == video::FrameFormat::Yuv420) {
    if (!m_impl->yuv) fail(ErrorKind::Internal, "CpuChain: a YUV frame for a chain without a YUV path");
    m_impl->yuv->run(frame);
    return;
  }
  if (m_impl->stages.empty()) return;
  Image& scratch = m_impl->scratch;
  if (scratch.width() != frame.image.width() || scratch.height() != frame.image.height()) {
    scratch = Image(frame.image.width(), frame.image.height(), 4, PixelType::U8);
  }
  for (auto& stage : m_impl->stages) {
    stage->run(frame.image, scratch);
    std::swap(frame.image, scratch);
  }
}

bool CpuChain::worksOnYuv() const { return m_impl->yuv != nullptr; }
ivec2 CpuChain::size() const { return m_impl->size; }
const std::vector<Effect>& CpuChain::effects() const { return m_impl->effects; }

std::string CpuChain::describe() const {
  std::string s;
  for (const auto& e : m_impl->effects) s += (s.empty() ? "" : " → ") + e.describe();
  return s;
}

}  // namespace glint::post
