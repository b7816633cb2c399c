// render/post's CPU backend on Yuv420 planes (cpu.h explains which effects and why).
#include "cpu_kernels.h"

#include "glint/core/error.h"
#include "glint/image/post.h"
#include "glint/render/post/effects.h"
#include "glint/video/frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace glint::render::post::cpu {

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

// Luma with weights `w` per pixel, normalized. The chroma term (zero when `w` are the
// input's own weights) is interpolated to the pixel as H.264's default chroma siting places
// the samples: co-sited with the even columns, halfway between two rows (bilinear; a
// decoder's RGB conversion interpolates too, so Sobel's edges see the same luma).
void lumaPlane(const Planes& p, const Matrix& m, dvec3 w, std::vector<float>& out) {
  out.resize(std::size_t(p.w) * std::size_t(p.h));
  const auto [a, b] = lumaFromChroma(m, w);
  const int cw = p.w / 2, ch = p.h / 2;
  const bool chroma = std::abs(a) > 1e-6f || std::abs(b) > 1e-6f;
  const auto termRow = [&](int cy, float* t) {
    const std::uint8_t* u = p.u + std::size_t(cy) * std::size_t(cw);
    const std::uint8_t* v = p.v + std::size_t(cy) * std::size_t(cw);
    for (int x = 0; x < cw; ++x) t[x] = (a * (float(u[x]) - 128.0f) + b * (float(v[x]) - 128.0f)) / kCScale;
  };
  parallelRows(p.h, [&](int begin, int end) {
    const auto n = static_cast<std::size_t>(cw);
    std::vector<float> near(n), far(n), term(n + 1);
    for (int y = begin; y < end; ++y) {
      const std::uint8_t* in = p.y + std::size_t(y) * std::size_t(p.w);
      float* o = out.data() + std::size_t(y) * std::size_t(p.w);
      if (!chroma) {
        for (int x = 0; x < p.w; ++x) o[x] = (float(in[x]) - 16.0f) / kYScale;
        continue;
      }
      // Even rows: 3/4 of chroma row y/2 and 1/4 of the row above; odd rows: 3/4 of row
      // (y − 1)/2 and 1/4 of the row below.
      const int cy = y / 2;
      const int other = std::clamp(y % 2 == 0 ? cy - 1 : cy + 1, 0, ch - 1);
      termRow(cy, near.data());
      termRow(other, far.data());
      for (std::size_t x = 0; x < n; ++x) term[x] = 0.75f * near[x] + 0.25f * far[x];
      term[n] = term[n - 1];
      for (int x = 0; x < p.w; ++x) {
        const std::size_t c = std::size_t(x / 2);
        const float t = x % 2 == 0 ? term[c] : 0.5f * (term[c] + term[c + 1]);
        o[x] = (float(in[x]) - 16.0f) / kYScale + t;
      }
    }
  });
}

std::uint8_t clampByte(float v, float lo = 0.0f, float hi = 255.0f) { return std::uint8_t(std::clamp(v, lo, hi) + 0.5f); }

// Sepia: the output RGB is a function of the YIQ luma L alone, so are its BT.709 Y', Cb', Cr'.
class SepiaYuv final : public YuvStage {
public:
  SepiaYuv(const Effect& e, ivec2 size) : m_size(size) {
    const SepiaOptions options{.i = e.value("i"), .q = e.value("q")};
    const dvec3 w709 = kBt709.weights();
    for (int i = 0; i < kSteps; ++i) {
      const double l = double(i) / double(kSteps - 1);
      dvec3 rgb = sepiaPixel(dvec3(l), options);  // grey in: L = l
      for (int c = 0; c < 3; ++c) rgb[c] = std::round(std::clamp(rgb[c], 0.0, 1.0) * 255.0) / 255.0;  // the RGBA8 target
      const double y = glm::dot(w709, rgb);
      m_y[std::size_t(i)] = clampByte(16.0f + kYScale * float(y));
      m_u[std::size_t(i)] = float((rgb.b - y) / (2.0 * (1.0 - kBt709.kb)));
      m_v[std::size_t(i)] = float((rgb.r - y) / (2.0 * (1.0 - kBt709.kr)));
    }
  }
  void run(video::Frame& frame) override {
    const Planes p = planesOf(frame, m_size);
    lumaPlane(p, matrixOf(frame.matrix), dvec3(kLumaR, kLumaG, kLumaB), m_luma);
    const int cw = p.w / 2;
    parallelRows(p.h / 2, [&](int begin, int end) {
      std::vector<int> index(static_cast<std::size_t>(2 * p.w));
      for (int cy = begin; cy < end; ++cy) {
        for (int r = 0; r < 2; ++r) {
          const float* l = m_luma.data() + std::size_t(2 * cy + r) * std::size_t(p.w);
          int* idx = index.data() + std::size_t(r) * std::size_t(p.w);
          for (int x = 0; x < p.w; ++x) idx[x] = int(std::clamp(l[x], 0.0f, 1.0f) * float(kSteps - 1) + 0.5f);
          std::uint8_t* yo = p.y + std::size_t(2 * cy + r) * std::size_t(p.w);
          for (int x = 0; x < p.w; ++x) yo[x] = m_y[std::size_t(idx[x])];
        }
        std::uint8_t* uo = p.u + std::size_t(cy) * std::size_t(cw);
        std::uint8_t* vo = p.v + std::size_t(cy) * std::size_t(cw);
        const int* i0 = index.data();
        const int* i1 = index.data() + p.w;
        // Chroma where H.264 sites it: [1 2 1]/4 across columns 2x−1, 2x, 2x+1 (edges
        // repeated), the mean of the two rows.
        for (int x = 0; x < cw; ++x) {
          const int l = std::max(2 * x - 1, 0), c = 2 * x, r = 2 * x + 1;
          const auto filtered = [&](const std::array<float, kSteps>& t) {
            return 0.125f * (t[std::size_t(i0[l])] + 2.0f * t[std::size_t(i0[c])] + t[std::size_t(i0[r])] +
                             t[std::size_t(i1[l])] + 2.0f * t[std::size_t(i1[c])] + t[std::size_t(i1[r])]);
          };
          uo[x] = clampByte(128.0f + kCScale * filtered(m_u));
          vo[x] = clampByte(128.0f + kCScale * filtered(m_v));
        }
      }
    });
    frame.matrix = video::YuvMatrix::Bt709;
  }

private:
  static constexpr int kSteps = 4096;  // L's table: 1/4095 apart, far below an 8-bit step of the output
  ivec2 m_size;
  std::array<std::uint8_t, kSteps> m_y{};
  std::array<float, kSteps> m_u{}, m_v{};
  std::vector<float> m_luma;
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
      for (int x = 0; x < p.w; ++x) {
        // round(255·v) first, as the GPU's RGBA8 target stores it.
        const float v = std::round(sobelValue(gx[x], gy[x], m_output, m_scale) * 255.0f) / 255.0f;
        out[x] = std::uint8_t(16.0f + kYScale * v + 0.5f);
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

std::unique_ptr<YuvStage> YuvStage::make(const Effect& e, ivec2 size) {
  if (size.x % 2 != 0 || size.y % 2 != 0) return nullptr;
  const std::string_view name = e.name();
  if (name == "sepia") return std::make_unique<yuv::SepiaYuv>(e, size);
  if (name == "sobel") return std::make_unique<yuv::SobelYuv>(e, size);
  if (FrequencyFilter f; frequencyFilterOf(e, f)) return std::make_unique<yuv::FilterYuv>(f, size);
  return nullptr;
}

}  // namespace glint::render::post::cpu
