// render/post's CPU backend on Yuv420 planes (cpu.h explains which effects and why).
#include "cpu_kernels.h"

#include "glint/core/error.h"
#include "glint/image/post.h"
#include "glint/post/effects.h"
#include "glint/video/frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

namespace glint::post::cpu {

namespace yuv {

// Limited range: Y' = 16 + 219·Y, C' = 128 + 224·C, Y in [0, 1], C in [−0.5, 0.5].
constexpr float kYScale = 219.0f, kCScale = 224.0f;

struct Matrix {
  double kr, kb;
  double kg() const { return 1.0 - kr - kb; }
  // d(R, G, B)/dCb and d(R, G, B)/dCr.
  dvec3 perCb() const { return {0.0, -2.0 * kb * (1.0 - kb) / kg(), 2.0 * (1.0 - kb)}; }
  dvec3 perCr() const { return {2.0 * (1.0 - kr), -2.0 * kr * (1.0 - kr) / kg(), 0.0}; }
  dvec3 weights() const { return {kr, kg(), kb}; }
};
constexpr Matrix kBt601{0.299, 0.114}, kBt709{0.2126, 0.0722};
Matrix matrixOf(video::YuvMatrix m) { return m == video::YuvMatrix::Bt709 ? kBt709 : kBt601; }

// The luma with weights `w` of a pixel (Y, Cb, Cr) in matrix m is Y + a·Cb + b·Cr (the
// weights sum to 1 and RGB = Y·(1, 1, 1) + Cb·perCb + Cr·perCr).
std::pair<float, float> lumaFromChroma(const Matrix& m, dvec3 w) {
  return {float(glm::dot(w, m.perCb())), float(glm::dot(w, m.perCr()))};
}

struct Planes {
  std::uint8_t *y, *u, *v;
  int w, h;
};
Planes planesOf(video::Frame& frame, ivec2 size) {
  if (frame.image.width() != size.x || frame.image.height() != size.y + size.y / 2) {
    fail(ErrorKind::Internal, "CpuChain: a YUV frame of the wrong size");
  }
  auto* y = reinterpret_cast<std::uint8_t*>(frame.image.bytes().data());
  auto* u = y + std::size_t(size.x) * std::size_t(size.y);
  return {y, u, u + std::size_t(size.x / 2) * std::size_t(size.y / 2), size.x, size.y};
}

// Luma with weights `w`, normalized, a row at a time. The chroma term (zero when `w` are the
// input's own weights) is interpolated to the pixel as H.264's default chroma siting places
// the samples: co-sited with the even columns, halfway between two rows (bilinear; a
// decoder's RGB conversion interpolates too, so Sobel's edges see about the same luma).
class LumaRows {
public:
  LumaRows(const Planes& p, const Matrix& m, dvec3 w) : m_p(p) {
    std::tie(m_a, m_b) = lumaFromChroma(m, w);
    m_chroma = std::abs(m_a) > 1e-6f || std::abs(m_b) > 1e-6f;
  }
  /// Row y's luma into out[0, w); `scratch` holds 2·(w/2 + 1) floats.
  void row(int y, float* out, float* scratch) const {
    const std::uint8_t* in = m_p.y + std::size_t(y) * std::size_t(m_p.w);
    const int w = m_p.w, cw = w / 2;
    if (!m_chroma) {
      for (int x = 0; x < w; ++x) out[x] = (float(in[x]) - 16.0f) * (1.0f / kYScale);
      return;
    }
    // Even rows: 3/4 of chroma row y/2 and 1/4 of the row above; odd rows: 3/4 of row
    // (y − 1)/2 and 1/4 of the row below.
    const int cy = y / 2, other = std::clamp(y % 2 == 0 ? cy - 1 : cy + 1, 0, m_p.h / 2 - 1);
    const std::uint8_t *u0 = m_p.u + std::size_t(cy) * std::size_t(cw), *v0 = m_p.v + std::size_t(cy) * std::size_t(cw);
    const std::uint8_t *u1 = m_p.u + std::size_t(other) * std::size_t(cw), *v1 = m_p.v + std::size_t(other) * std::size_t(cw);
    float* term = scratch;
    const float a = m_a / kCScale, b = m_b / kCScale;
    for (int x = 0; x < cw; ++x) {
      const float u = 0.75f * float(u0[x]) + 0.25f * float(u1[x]) - 128.0f;
      const float v = 0.75f * float(v0[x]) + 0.25f * float(v1[x]) - 128.0f;
      term[x] = a * u + b * v;
    }
    term[cw] = term[cw - 1];
    for (int x = 0; x < cw; ++x) {
      out[2 * x] = (float(in[2 * x]) - 16.0f) * (1.0f / kYScale) + term[x];
      out[2 * x + 1] = (float(in[2 * x + 1]) - 16.0f) * (1.0f / kYScale) + 0.5f * (term[x] + term[x + 1]);
    }
  }

private:
  Planes m_p;
  float m_a = 0, m_b = 0;
  bool m_chroma = false;
};

// The whole plane (Sobel and the filters need neighbours).
void lumaPlane(const Planes& p, const Matrix& m, dvec3 w, std::vector<float>& out) {
  out.resize(std::size_t(p.w) * std::size_t(p.h));
  const LumaRows rows(p, m, w);
  parallelRows(p.h, [&](int begin, int end) {
    std::vector<float> scratch(static_cast<std::size_t>(p.w + 2));
    for (int y = begin; y < end; ++y) rows.row(y, out.data() + std::size_t(y) * std::size_t(p.w), scratch.data());
  });
}

std::uint8_t clampByte(float v, float lo = 0.0f, float hi = 255.0f) { return std::uint8_t(std::clamp(v, lo, hi) + 0.5f); }

// Sepia: the output is L·(1, 1, 1) + t(L)·c (image/post.h), with t the largest value ≤ 1
// that keeps every channel in [0, 1]: t = max(0, min(1, slope_k·L + bias_k)) over the
// channels. Its BT.709 Y' and chroma are then affine in L and t: a few multiply-adds per
// pixel, vectorised, no tables.
class SepiaYuv final : public YuvStage {
public:
  SepiaYuv(const Effect& e, ivec2 size) : m_size(size) {
    const dvec3 c = sepiaOffset({.i = e.value("i"), .q = e.value("q")});
    for (int k = 0; k < 3; ++k) {
      m_slope[k] = c[k] > 0 ? float(-1.0 / c[k]) : c[k] < 0 ? float(-1.0 / c[k]) : 0.0f;
      m_bias[k] = c[k] > 0 ? float(1.0 / c[k]) : c[k] < 0 ? 0.0f : 1.0f;
    }
    const double yc = glm::dot(kBt709.weights(), c);  // Y709 = L + t·yc
    m_yc = float(yc);
    m_uc = float((c.b - yc) / (2.0 * (1.0 - kBt709.kb)));
    m_vc = float((c.r - yc) / (2.0 * (1.0 - kBt709.kr)));
  }
  void run(video::Frame& frame) override {
    const Planes p = planesOf(frame, m_size);
    const LumaRows luma(p, matrixOf(frame.matrix), dvec3(kLumaR, kLumaG, kLumaB));
    parallelRows(p.h / 2, [&](int begin, int end) {
      // Locals only in the loops: a store through a uint8_t pointer may alias anything, so
      // members and captures would be reloaded every pixel and nothing would vectorise.
      const int w = p.w, cw = w / 2;
      const float s0 = m_slope[0], s1 = m_slope[1], s2 = m_slope[2], b0 = m_bias[0], b1 = m_bias[1], b2 = m_bias[2];
      const float yc = m_yc, uc = kCScale * m_uc * 0.125f, vc = kCScale * m_vc * 0.125f;
      const auto n = static_cast<std::size_t>(w);
      std::vector<float> l(n), t0(n + 1), t1(n + 1), scratch(n + 2);
      for (int cy = begin; cy < end; ++cy) {
        for (int r = 0; r < 2; ++r) {
          luma.row(2 * cy + r, l.data(), scratch.data());
          float* t = r == 0 ? t0.data() : t1.data();
          const float* lp = l.data();
          std::uint8_t* yo = p.y + std::size_t(2 * cy + r) * n;
          for (int x = 0; x < w; ++x) {
            const float lx = std::min(std::max(lp[x], 0.0f), 1.0f);
            const float tx = std::max(0.0f, std::min(std::min(1.0f, s0 * lx + b0), std::min(s1 * lx + b1, s2 * lx + b2)));
            t[x] = tx;
            yo[x] = std::uint8_t(int(16.5f + kYScale * (lx + tx * yc)));
          }
        }
        // Chroma where H.264 sites it: [1 2 1]/4 across columns 2x − 1, 2x, 2x + 1 (the
        // left edge repeated), the mean of the two rows.
        std::uint8_t* uo = p.u + std::size_t(cy) * std::size_t(cw);
        std::uint8_t* vo = p.v + std::size_t(cy) * std::size_t(cw);
        const float* a = t0.data();
        const float* b = t1.data();
        const auto chroma = [&](int x, int left) {
          const float tf = a[left] + 2.0f * a[2 * x] + a[2 * x + 1] + b[left] + 2.0f * b[2 * x] + b[2 * x + 1];
          uo[x] = std::uint8_t(int(128.5f + tf * uc));
          vo[x] = std::uint8_t(int(128.5f + tf * vc));
        };
        chroma(0, 0);
        for (int x = 1; x < cw; ++x) {
          const float tf = a[2 * x - 1] + 2.0f * a[2 * x] + a[2 * x + 1] + b[2 * x - 1] + 2.0f * b[2 * x] + b[2 * x + 1];
          uo[x] = std::uint8_t(int(128.5f + tf * uc));
          vo[x] = std::uint8_t(int(128.5f + tf * vc));
        }
      }
    });
    frame.matrix = video::YuvMatrix::Bt709;
  }

private:
  ivec2 m_size;
  float m_slope[3], m_bias[3];
  float m_yc, m_uc, m_vc;
};

// Sobel: gray, so Y' = 16 + 219·v and both chroma planes 128.
class SobelYuv final : public YuvStage {
public:
  SobelYuv(const Effect& e, ivec2 size) : m_size(size), m_scale(e.value("scale")) {
    constexpr SobelOutput outputs[] = {SobelOutput::Magnitude, SobelOutput::Horizontal, SobelOutput::Vertical,
                                       SobelOutput::SignedX, SobelOutput::SignedY};
    m_output = outputs[int(e.value("output"))];
  }
  void run(video::Frame& frame) override {
    const Planes p = planesOf(frame, m_size);
    lumaPlane(p, matrixOf(frame.matrix), dvec3(kLumaR, kLumaG, kLumaB), m_luma);
    sobelRows(m_luma.data(), p.w, p.h, [&](int y, const float* gx, const float* gy) {
      std::uint8_t* out = p.y + std::size_t(y) * std::size_t(p.w);
      // Y' = 16 + 219·v; v in [0, 1], so no clamp. Locals: see SepiaYuv.
      const int w = p.w;
      const float scale = m_scale;
      if (m_output == SobelOutput::Magnitude) {
        for (int x = 0; x < w; ++x) {
          const float v = std::min(1.0f, scale * std::sqrt(gx[x] * gx[x] + gy[x] * gy[x]));
          out[x] = std::uint8_t(int(16.5f + kYScale * v));
        }
      } else {
        const SobelOutput output = m_output;
        for (int x = 0; x < w; ++x) out[x] = std::uint8_t(int(16.5f + kYScale * sobelValue(gx[x], gy[x], output, scale)));
      }
    });
    std::memset(p.u, 128, std::size_t(p.w / 2) * std::size_t(p.h / 2) * 2);
    frame.matrix = video::YuvMatrix::Bt709;
  }

private:
  ivec2 m_size;
  float m_scale;
  SobelOutput m_output;
  std::vector<float> m_luma;
};

// A frequency-domain filter: Y at full size, Cb and Cr at half size with the filter scaled
// to their grid (frequencies per chroma sample are twice those per pixel), all in BT.709.
class FilterYuv final : public YuvStage {
public:
  FilterYuv(const FrequencyFilter& f, ivec2 size)
      : m_size(size), m_offset(f.offset), m_luma(size.x, size.y, 1, f), m_chroma(size.x / 2, size.y / 2, 2, halved(f)) {}
  void run(video::Frame& frame) override {
    const Planes p = planesOf(frame, m_size);
    const Matrix in = matrixOf(frame.matrix);
    // Into BT.709: Y709 = Y + a·Cb + b·Cr; Cb709, Cr709 a 2×2 map of (Cb, Cr) (identity for a 709 input).
    std::vector<float>& y = m_lumaIn;
    lumaPlane(p, in, kBt709.weights(), y);
    std::memcpy(m_luma.data(), y.data(), y.size() * sizeof(float));
    const auto [a, b] = lumaFromChroma(in, kBt709.weights());
    const dvec3 cb = in.perCb(), cr = in.perCr();
    const float bb = float((cb.b - a) / (2.0 * (1.0 - kBt709.kb))), bc = float((cr.b - b) / (2.0 * (1.0 - kBt709.kb)));
    const float rb = float((cb.r - a) / (2.0 * (1.0 - kBt709.kr))), rc = float((cr.r - b) / (2.0 * (1.0 - kBt709.kr)));
    const std::size_t cn = std::size_t(p.w / 2) * std::size_t(p.h / 2);
    float* c = m_chroma.data();
    for (std::size_t i = 0; i < cn; ++i) {
      const float u = (float(p.u[i]) - 128.0f) / kCScale, v = (float(p.v[i]) - 128.0f) / kCScale;
      c[i] = bb * u + bc * v;
      c[cn + i] = rb * u + rc * v;
    }
    m_luma.run();
    m_chroma.run();
    const float* yl = m_luma.data();
    parallelRows(p.h, [&](int begin, int end) {
      for (std::size_t i = std::size_t(begin) * std::size_t(p.w); i < std::size_t(end) * std::size_t(p.w); ++i) {
        p.y[i] = clampByte(16.0f + kYScale * (yl[i] + m_offset), 16.0f, 235.0f);
      }
    });
    for (std::size_t i = 0; i < cn; ++i) {
      p.u[i] = clampByte(128.0f + kCScale * c[i], 16.0f, 240.0f);
      p.v[i] = clampByte(128.0f + kCScale * c[cn + i], 16.0f, 240.0f);
    }
    frame.matrix = video::YuvMatrix::Bt709;
  }

private:
  static FrequencyFilter halved(FrequencyFilter f) {
    f.cutoff *= 2.0f;
    f.low *= 2.0f;
    f.size *= 0.5f;
    f.offset = 0.0f;  // the offset is grey: luma only
    return f;
  }
  ivec2 m_size;
  float m_offset;
  PlaneFilter m_luma, m_chroma;
  std::vector<float> m_lumaIn;
};

}  // namespace yuv

std::unique_ptr<YuvStage> sepiaYuv(const Effect& e, ivec2 size) { return std::make_unique<yuv::SepiaYuv>(e, size); }
std::unique_ptr<YuvStage> sobelYuv(const Effect& e, ivec2 size) { return std::make_unique<yuv::SobelYuv>(e, size); }
std::unique_ptr<YuvStage> filterYuv(const Effect& e, ivec2 size) {
  return std::make_unique<yuv::FilterYuv>(e.def->filter(e), size);
}

}  // namespace glint::post::cpu
