#pragma once
// Private to post's CPU backend (cpu.cpp: RGBA frames, cpu_yuv.cpp: YUV planes): the
// pieces both use. Named namespace (not anonymous): both files may share a unity batch.
#include "glint/core/math.h"
#include "glint/image/fourier.h"
#include "glint/image/post.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace glint::post::cpu {

/// body(rowBegin, rowEnd) over [0, rows) in bands, on OpenCV's thread pool.
void parallelRows(int rows, const std::function<void(int, int)>& body);

/// The gray value a Sobel output gives for gradient (gx, gy) (image/post.h's SobelOutput).
inline float sobelValue(float gx, float gy, SobelOutput output, float s) {
  switch (output) {
    case SobelOutput::Horizontal: return std::min(1.0f, s * std::abs(gy));
    case SobelOutput::Vertical: return std::min(1.0f, s * std::abs(gx));
    case SobelOutput::Magnitude: return std::min(1.0f, s * std::sqrt(gx * gx + gy * gy));
    case SobelOutput::SignedX: return std::clamp(0.5f + 0.5f * s * gx, 0.0f, 1.0f);
    case SobelOutput::SignedY: return std::clamp(0.5f + 0.5f * s * gy, 0.0f, 1.0f);
  }
  return 0.0f;
}

/// Sobel of a w × h float luma plane (clamp-to-edge): out(row y, x) = f(gx, gy) written by
/// `write(y, gxRow, gyRow)`, a row at a time (gx, gy of row y, w values each).
void sobelRows(const float* luma, int w, int h, const std::function<void(int y, const float* gx, const float* gy)>& write);

/// A frequency-domain filter on `planes` real w × h planes at once (FFTW r2c, × H, c2r,
/// FFTW's threads): H precomputed with 1/(w·h), real (the filters are zero-phase).
class PlaneFilter {
public:
  PlaneFilter(int w, int h, int planes, const FrequencyFilter& filter);
  ~PlaneFilter();
  PlaneFilter(const PlaneFilter&) = delete;
  PlaneFilter& operator=(const PlaneFilter&) = delete;
  /// The planes, contiguous (plane p at data() + p·w·h): fill, run(), read.
  float* data() { return m_real; }
  void run();

private:
  int m_w, m_h, m_planes;
  float* m_real = nullptr;
  void* m_spectrum = nullptr;  // fftwf_complex
  std::vector<float> m_gain;   // h × (w/2 + 1)
  void* m_forward = nullptr;   // fftwf_plan
  void* m_inverse = nullptr;
};

}  // namespace glint::post::cpu

namespace glint::video {
struct Frame;
}

namespace glint::post {
struct Effect;

/// An effect on the CPU, U8 RGBA frames (alpha passes through); EffectDef::cpu makes it.
class CpuStage {
public:
  virtual ~CpuStage() = default;
  virtual void run(const Image& in, Image& out) = 0;
};

/// An effect on Yuv420 planes (cpu.h's YUV path); EffectDef::yuv makes it.
class YuvStage {
public:
  virtual ~YuvStage() = default;
  /// In place; the frame leaves in BT.709.
  virtual void run(video::Frame& frame) = 0;
};
}  // namespace glint::post

namespace glint::post::cpu {

// The table's factories (src/post/effects.cpp's EffectDef::cpu and ::yuv), one per effect.
std::unique_ptr<CpuStage> sepia(const Effect& effect, ivec2 size);
std::unique_ptr<CpuStage> sobel(const Effect& effect, ivec2 size);
std::unique_ptr<CpuStage> edges(const Effect& effect, ivec2 size);
std::unique_ptr<CpuStage> kuwahara(const Effect& effect, ivec2 size);
std::unique_ptr<CpuStage> spectrum(const Effect& effect, ivec2 size);
std::unique_ptr<CpuStage> filter(const Effect& effect, ivec2 size);  ///< the FFT filters (EffectDef::filter)
std::unique_ptr<YuvStage> sepiaYuv(const Effect& effect, ivec2 size);
std::unique_ptr<YuvStage> sobelYuv(const Effect& effect, ivec2 size);
std::unique_ptr<YuvStage> filterYuv(const Effect& effect, ivec2 size);

}  // namespace glint::post::cpu
