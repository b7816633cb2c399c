#pragma once
// glint/post/cpu.h — glint post's CPU backend: every effect of post/effects.h on the CPU, threaded (OpenCV's parallel_for_) and vectorised, with
// FFTW (single precision, threads) for the spectrum view and the frequency-domain filters
// and OpenCV's box filter for Kuwahara's statistics. `glint post --backend cpu` uses it,
// and `--backend auto` (the default) whenever the GL renderer is a software one (Mesa's
// llvmpipe or softpipe, SwiftShader): there a "GPU" pass is CPU work plus uploads and
// readbacks.
//
/// ```cpp
/// #include <glint/image/post.h>
/// #include <glint/post/cpu.h>
/// const std::vector<std::string> specs = {"sepia"};
/// glint::post::CpuChain chain({1920, 1080}, glint::post::parseEffects(specs));
/// glint::video::Frame frame;                  // from a Source opened with options.yuv420 = chain.worksOnYuv()
/// chain.run(frame);                           // in place: Rgba stays Rgba, Yuv420 stays Yuv420 (BT.709)
/// const glint::Image photo = glint::postInput(glint::loadImage("photo.png"));
/// const glint::Image out = chain.run(photo);  // U8 RGBA in, U8 RGBA out
/// ```
//
// Results: the same definitions as the GPU passes (image/post.h, image/fourier.h), within
// the oracles' tolerances — one 8-bit step per effect on RGBA frames (the GPU writes RGBA8
// targets, rounding to nearest; so does this backend).
//
// YUV frames (video/frame.h's Yuv420): a chain of one effect defined on luma or linear in
// colour runs on the decoder's planes and hands the encoder its planes, skipping both
// RGB ↔ YUV conversions. The result is written in BT.709, limited range (what glint's
// H.264 sink writes), whatever the input's matrix:
//   sepia       out RGB is a function of the YIQ luma L alone (L + t(L)·c, image/post.h),
//               so Y' and the chroma are affine in L and t(L) (a clamped linear function);
//               L is computed from Y' and the chroma (exactly Y' for a BT.601 input, plus
//               the chroma interpolated where H.264 sites it for BT.709). Chroma out: the
//               pixels' values filtered as an encoder subsamples ([1 2 1] across, 2 rows).
//   sobel       gray: Y' = 16 + 219·v from the Sobel of L, chroma 128.
//   lowpass highpass bandpass blur bokeh
//               linear filters commute with the (linear) YUV matrix: Y filtered at full
//               size (+ offset), U and V at half size with the filter scaled to their grid.
//   others      (chains of several effects, kuwahara, edges, posterize) work on RGBA.
// Against the GPU path on the same video (decoded to RGB, effect, encoded from RGB) the
// YUV path differs only by how the RGB path rounds, clips out-of-gamut colours and filters
// chroma: a few 8-bit steps on average at colour edges, more where the RGB path clips
// (tests/post/backend_test.cpp states the measured bounds).

#include "glint/core/math.h"
#include "glint/image/image.h"
#include "glint/post/effects.h"
#include "glint/video/frame.h"

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint::post {

/// Where `glint post` runs its effects.
enum class Backend {
  Auto,  ///< the CPU when the GL renderer is a software one and the CPU has every effect; else the GPU
  Gpu,   ///< OpenGL (render/post/chain.h, through the job's GpuBackend), whatever the renderer
  Cpu    ///< this header's CpuChain; no GL context is made
};

/// "auto", "gpu" or "cpu" → Backend; Error(Usage) "--backend must be auto, gpu or cpu, got 'x'".
Backend parseBackend(std::string_view name);
const char* backendName(Backend backend);
/// Whether a GL_RENDERER string names a software rasterizer: Mesa's llvmpipe and softpipe,
/// SwiftShader, Microsoft's "GDI Generic" and Apple's "Software Renderer".
bool isSoftwareRenderer(std::string_view glRenderer);
/// The effects of `effects` the CPU backend lacks, comma-separated; empty when it has them
/// all (today it has every effect of post/effects.h: each entry carries its CPU stage).
std::string cpuMissing(std::span<const Effect> effects);

/// Whether a CpuChain of `effects` keeps Yuv420 frames in YUV (one effect with a YUV path;
/// even frame sizes only): whether to open a video source with SourceOptions::yuv420.
bool cpuWorksOnYuv(std::span<const Effect> effects);

class CpuChain {
public:
  /// Prepares each effect for frames of `size` (FFT plans, tables). Error(Usage) from
  /// validateEffect, and for an effect the CPU backend lacks (see cpuMissing).
  CpuChain(ivec2 size, std::vector<Effect> effects);
  ~CpuChain();
  CpuChain(CpuChain&&) noexcept;
  CpuChain& operator=(CpuChain&&) noexcept;

  /// Every effect on `input` (U8 RGB or RGBA of the chain's size): U8 RGBA, 8-bit rounding
  /// between effects as on the GPU.
  Image run(const Image& input);
  /// A video frame in place: Rgba as above, Yuv420 in YUV when worksOnYuv() (else
  /// Error(Internal): open the source without yuv420).
  void run(video::Frame& frame);
  /// Whether the chain keeps Yuv420 frames in YUV (see the header): then a video source is
  /// best opened with SourceOptions::yuv420.
  bool worksOnYuv() const;
  ivec2 size() const;
  const std::vector<Effect>& effects() const;
  /// "sepia(i=0.2,q=0)", as Chain::describe.
  std::string describe() const;

  struct Impl;

private:
  std::unique_ptr<Impl> m_impl;
};

}  // namespace glint::post
