// The GPU passes of render/post against their CPU references (image/post.h, image/fourier.h)
// on a real photograph, on noise and at odd sizes: within one 8-bit step, the Kuwahara
// quadrant choice exactly, the sepia luma kept, chains and the PBO stream equal to the
// references applied in turn.
#include "glint/core/error.h"
#include "glint/image/fourier.h"
#include "glint/image/post.h"
#include "glint/render/post/chain.h"
#include "glint/render/post/fft.h"
#include "glint/render/post/passes.h"

#include "post_test_util.h"
#include "support/gl_test.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

using namespace glint;
using namespace glint::render::post;
using glint::testing::compareSteps;
using glint::testing::crop;
using glint::testing::noiseImage;
using glint::testing::photograph;

namespace {
class PostGpu : public glint::testing::GlTest {};

std::vector<std::pair<std::string, Image>> inputs() { return glint::testing::postInputs(); }

Image runPass(const Image& input, const std::function<void(const gl::Texture&, const gl::Texture&)>& pass) {
  const gl::Texture in = uploadFrame(input, "test-input");
  gl::Texture out(GL_TEXTURE_2D, "test-output");
  out.storage(GL_RGBA8, input.width(), input.height());
  pass(in, out);
  return readFrame(out);
}
}  // namespace

TEST_F(PostGpu, SepiaMatchesTheYiqReferenceAndKeepsLuma) {
  SepiaPass sepia;
  for (const SepiaOptions options : {SepiaOptions{}, SepiaOptions{.i = 0.1f, .q = 0.08f}, SepiaOptions{.i = -0.15f}}) {
    for (const auto& [name, image] : inputs()) {
      const Image gpu = runPass(image, [&](auto& in, auto& out) { sepia.run(in, out, options); });
      const auto d = compareSteps(gpu, sepiaReference(image, options));
      EXPECT_LE(d.maxSteps, 1) << name << " i=" << options.i << " q=" << options.q;
      // Luma of the 8-bit result against the input's: each channel is rounded by at most half
      // a step and the weights sum to 1, so at most half a step (plus float noise).
      double worst = 0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
          const double in = kLumaR * image.at(x, y, 0) + kLumaG * image.at(x, y, 1) + kLumaB * image.at(x, y, 2);
          const double out = kLumaR * gpu.at(x, y, 0) + kLumaG * gpu.at(x, y, 1) + kLumaB * gpu.at(x, y, 2);
          worst = std::max(worst, std::abs(in - out));
        }
      EXPECT_LE(worst * 255.0, 0.5 + 1e-3) << name << ": luma moved by " << worst * 255.0 << " steps";
      std::printf("[figure] sepia %s i=%g q=%g: max %d step(s) from the YIQ reference; luma within %.3f steps\n",
                  name.c_str(), options.i, options.q, d.maxSteps, worst * 255.0);
    }
  }
}

TEST_F(PostGpu, SobelAndEdgesMatchTheirReferences) {
  SobelPass sobel;
  EdgesPass edges;
  for (const auto& [name, image] : inputs()) {
    for (SobelOutput output : {SobelOutput::Horizontal, SobelOutput::Vertical, SobelOutput::Magnitude,
                               SobelOutput::SignedX, SobelOutput::SignedY}) {
      const SobelOptions options{.output = output, .scale = 1.5f};
      const Image gpu = runPass(image, [&](auto& in, auto& out) { sobel.run(in, out, options); });
      EXPECT_LE(compareSteps(gpu, sobelReference(image, options)).maxSteps, 1) << name << " output " << int(output);
    }
    const Image gpu = runPass(image, [&](auto& in, auto& out) { edges.run(in, out, {}); });
    EXPECT_LE(compareSteps(gpu, edgesReference(image)).maxSteps, 1) << name;
  }
}

// The compute passes (the default, issue 37) and the fragment passes they replaced (sepia,
// Sobel, edges, Kuwahara's two) share one
// function per texel (shaders/post/<pass>.glsl): the same bytes from RGBA8 targets, the
// same floats from RGBA32F ones, on every input (odd sizes too: the last compute groups
// overhang the image).
TEST_F(PostGpu, ComputeAndFragmentPassesGiveTheSameTexels) {
  const auto both = [](const Image& image, GLenum format, const auto& run) {
    const gl::Texture in = uploadFrame(image, "test-input");
    std::array<Image, 2> out;
    for (int k = 0; k < 2; ++k) {
      gl::Texture target(GL_TEXTURE_2D, "test-output");
      target.storage(format, image.width(), image.height());
      run(k == 0 ? PassStage::Compute : PassStage::Fragment, in, target);
      out[std::size_t(k)] = readFrame(target);
    }
    return out;
  };
  int compared = 0;
  for (const auto& [name, image] : inputs()) {
    for (const GLenum format : {GLenum(GL_RGBA8), GLenum(GL_RGBA32F)}) {
      const auto sepia = both(image, format, [](PassStage stage, auto& in, auto& out) {
        SepiaPass(stage).run(in, out, {.i = 0.1f, .q = 0.08f});
      });
      EXPECT_TRUE(sepia[0] == sepia[1]) << "sepia " << name << (format == GL_RGBA8 ? " rgba8" : " rgba32f");
      const auto sobel = both(image, format, [](PassStage stage, auto& in, auto& out) {
        SobelPass(stage).run(in, out, {.output = SobelOutput::SignedX, .scale = 1.5f});
      });
      EXPECT_TRUE(sobel[0] == sobel[1]) << "sobel " << name << (format == GL_RGBA8 ? " rgba8" : " rgba32f");
      const auto edges = both(image, format, [](PassStage stage, auto& in, auto& out) { EdgesPass(stage).run(in, out, {}); });
      EXPECT_TRUE(edges[0] == edges[1]) << "edges " << name << (format == GL_RGBA8 ? " rgba8" : " rgba32f");
      const auto kuwahara = both(image, format, [](PassStage stage, auto& in, auto& out) {
        KuwaharaPass(stage).run(in, out, {.size = 4});
      });
      EXPECT_TRUE(kuwahara[0] == kuwahara[1]) << "kuwahara " << name << (format == GL_RGBA8 ? " rgba8" : " rgba32f");
      const auto quadrants = both(image, format, [](PassStage stage, auto& in, auto& out) {
        KuwaharaPass(stage).run(in, out, {.size = 3}, /*showQuadrant=*/true);
      });
      EXPECT_TRUE(quadrants[0] == quadrants[1]) << "kuwahara quadrants " << name;
      EXPECT_EQ(sepia[0].type(), format == GL_RGBA8 ? PixelType::U8 : PixelType::F32);
      compared += 5;
    }
  }
  EXPECT_GE(compared, 20);
  EXPECT_EQ(SepiaPass().stage(), PassStage::Compute);
}

TEST_F(PostGpu, KuwaharaChoosesTheReferenceQuadrantExactly) {
  KuwaharaPass kuwahara;
  for (int size : {2, 3, 4, 5, 8}) {
    for (const auto& [name, image] : inputs()) {
      const KuwaharaOptions options{.size = size};
      const auto reference = kuwaharaReference(image, options);
      const Image quadrant = runPass(image, [&](auto& in, auto& out) { kuwahara.run(in, out, options, true); });
      const Image gpu = runPass(image, [&](auto& in, auto& out) { kuwahara.run(in, out, options); });
      std::size_t differ = 0, ties = 0;
      for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
          const std::size_t i = std::size_t(y) * std::size_t(image.width()) + std::size_t(x);
          const int chosen = int(std::lround(quadrant.at(x, y, 0) * 255.0f));
          ties += std::popcount(unsigned(reference.tied[i])) > 1;
          if (chosen != reference.chosen[i]) ++differ;
        }
      }
      // The compute pass (kuwahara.comp) sums and compares in integers, as the reference
      // does: the same choice everywhere, exact ties (ties counts them) broken the same way.
      // (The fragment version stores D in a float texture: exact for s ≤ 4, rounded once,
      // order-preserving, above.)
      EXPECT_EQ(differ, 0u) << name << " s=" << size << " (" << ties << " exact ties)";
      std::printf("[figure] kuwahara %s %dx%d s=%d: %zu of %zu quadrant choices differ from the brute force "
                  "(%zu exact ties)\n", name.c_str(), image.width(), image.height(), size, differ, image.pixelCount(), ties);
      const auto d = compareSteps(gpu, reference.image);
      EXPECT_LE(d.maxSteps, 1) << name << " s=" << size;
    }
  }
}

TEST_F(PostGpu, SpectrumAndFiltersMatchTheDftReference) {
  // Small sizes: the reference is a direct DFT in double. With GLINT_FFT_AXES=passes both
  // sizes take the complex FFT pass by pass (llvmpipe's default). With =shared, 60×40
  // (30 = 2·3·5, 40 = 2·4·5) takes the real-input transform fused with the view or the
  // filter (RealFft2d); 60×44 (44 = 4·11) does not fit it: the complex FFT, its rows in one
  // dispatch (fft_axis.comp; the filters' two lanes too), its columns (11) pass by pass.
  ASSERT_TRUE(RealFft2d::fits({60, 40}));
  ASSERT_FALSE(RealFft2d::fits({60, 44}));
  for (const auto& [height, axes] : {std::pair{44, "passes"}, std::pair{44, "shared"}, std::pair{40, "shared"}}) {
  ::setenv("GLINT_FFT_AXES", axes, 1);
  SCOPED_TRACE(fmt::format("60x{} {}", height, axes));
  const Image image = crop(photograph(), 130, 80, 60, height);
  SpectrumPass spectrum;
  const Image s = runPass(image, [&](auto& in, auto& out) { spectrum.run(in, out); });
  EXPECT_LE(compareSteps(s, spectrumReference(image)).maxSteps, 1);
  FrequencyFilterPass filter;
  const std::vector<std::pair<const char*, FrequencyFilter>> filters = {
      {"lowpass", {.kind = FilterKind::LowPass, .cutoff = 0.08f}},
      {"ideal lowpass", {.kind = FilterKind::LowPass, .cutoff = 0.1f, .order = 0}},
      {"highpass", {.kind = FilterKind::HighPass, .cutoff = 0.05f, .offset = 0.5f}},
      {"bandpass", {.kind = FilterKind::BandPass, .cutoff = 0.2f, .low = 0.05f, .offset = 0.5f}},
      {"gaussian", {.kind = FilterKind::Kernel, .kernel = KernelShape::Gaussian, .size = 2.5f}},
      {"disk", {.kind = FilterKind::Kernel, .kernel = KernelShape::Disk, .size = 4.0f}}};
  for (const auto& entry : filters) {
    const auto& [name, f0] = entry;
    const FrequencyFilter& f = f0;  // a plain reference: the lambda captures it (clang 14 cannot capture bindings)
    const Image gpu = runPass(image, [&](auto& in, auto& out) { filter.run(in, out, f); });
    const auto d = compareSteps(gpu, frequencyFilterReference(image, f));
    EXPECT_LE(d.maxSteps, 1) << name << " at " << d.worstX << "," << d.worstY;
    std::printf("[figure] %s 60x%d (%s) vs the direct DFT in double: max %d step(s), mean %.4f\n", name, height,
                height == 40 ? "real-input, fused" : axes, d.maxSteps, d.meanSteps);
  }
  }
  // The widest rows the real-input path takes (4096 texels: 2048 complex values, the most its
  // inverse rows keep in registers), on noise: every frequency present.
  ::setenv("GLINT_FFT_AXES", "shared", 1);
  const Image wide = noiseImage(4096, 2, 3);
  {
    const FrequencyFilter f{.kind = FilterKind::HighPass, .cutoff = 0.2f, .offset = 0.5f};
    FrequencyFilterPass pass;
    const Image gpu = runPass(wide, [&](auto& in, auto& out) { pass.run(in, out, f); });
    const auto d = compareSteps(gpu, frequencyFilterReference(wide, f));
    EXPECT_LE(d.maxSteps, 1) << "4096x2 at " << d.worstX << "," << d.worstY;
    std::printf("[figure] filter 4096x2 (real-input, fused) vs the direct DFT in double: max %d step(s), mean %.4f\n",
                d.maxSteps, d.meanSteps);
  }
  ::unsetenv("GLINT_FFT_AXES");
}

TEST_F(PostGpu, ChainsAndTheStreamEqualTheReferencesInTurn) {
  const Image image = photograph();
  Chain posterize(ivec2(image.width(), image.height()), parseEffects(std::vector<std::string>{"posterize"}));
  EXPECT_EQ(posterize.effects().size(), 2u);
  const Image gpu = posterize.run(image);
  const Image expected = edgesReference(quantizeToU8(kuwaharaReference(image).image));
  EXPECT_LE(compareSteps(gpu, expected).maxSteps, 1);

  // The stream (PBOs, fences, frames in flight) gives exactly what the chain gives, in order.
  const auto effects = parseEffects(std::vector<std::string>{"sepia", "sobel:output=vertical"});
  Chain chain(ivec2(96, 64), effects);
  for (int depth : {1, 3}) {
    FrameStream stream(ivec2(96, 64), effects, depth);
    std::vector<Image> frames, results;
    for (unsigned i = 0; i < 7; ++i) frames.push_back(noiseImage(96, 64, 100 + i));
    Image out;
    for (const auto& f : frames) {
      if (stream.full()) {
        ASSERT_TRUE(stream.pop(out));
        results.push_back(out);
      }
      stream.push(f);
    }
    while (stream.pop(out)) results.push_back(out);
    ASSERT_EQ(results.size(), frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(results[i], chain.run(frames[i])) << "depth " << depth << " frame " << i;
  }
}

TEST_F(PostGpu, EffectParsingAndValidation) {
  const auto chain = parseEffects(std::vector<std::string>{"sepia:i=0.3", "sobel", "posterize"},
                                  std::vector<std::string>{"scale=3", "sobel.output=dx", "size=4"});
  ASSERT_EQ(chain.size(), 4u);
  EXPECT_FLOAT_EQ(chain[0].value("i"), 0.3f);
  EXPECT_FLOAT_EQ(chain[1].value("scale"), 3.0f);
  EXPECT_EQ(chain[1].value("output"), 3.0f);  // dx: SobelOutput::SignedX
  EXPECT_EQ(chain[2].value("size"), 4.0f);
  EXPECT_FLOAT_EQ(chain[3].value("scale"), 3.0f);
  EXPECT_EQ(chain[0].describe(), "sepia(i=0.3,q=0)");
  EXPECT_EQ(chain[1].describe(), "sobel(output=dx,scale=3)");
  const auto message = [](std::vector<std::string> specs, std::vector<std::string> sets) -> std::string {
    try {
      parseEffects(specs, sets);
    } catch (const Error& e) {
      if (e.kind() == ErrorKind::Usage && std::string(e.what()).find('\n') == std::string::npos) return e.what();
      return "not a one-line usage error";
    }
    return "accepted";
  };
  const auto usage = [&](std::vector<std::string> specs, std::vector<std::string> sets) {
    const std::string m = message(specs, sets);
    return m != "accepted" && m != "not a one-line usage error";
  };
  EXPECT_TRUE(usage({"sharpen"}, {}));
  EXPECT_TRUE(usage({"sepia:x=1"}, {}));
  EXPECT_TRUE(usage({"sepia:i=abc"}, {}));
  EXPECT_TRUE(usage({"sepia"}, {"cutoff=0.1"}));
  EXPECT_TRUE(usage({"sepia"}, {"sobel.scale=2"}));
  EXPECT_TRUE(usage({"sobel:output=diagonal"}, {}));
  // Out of range at parse time, a float too large for a float included (it was "must be a number").
  EXPECT_NE(message({"blur"}, {"sigma=1e40"}).find("out of range"), std::string::npos) << message({"blur"}, {"sigma=1e40"});
  EXPECT_NE(message({"blur"}, {"sigma=9000"}).find("blur.sigma: 9000 is out of range (0, 8192]"), std::string::npos)
      << message({"blur"}, {"sigma=9000"});
  EXPECT_NE(message({"kuwahara:size=9"}, {}).find("out of range (2..8)"), std::string::npos);
  EXPECT_NE(message({"sobel:scale=0"}, {}).find("sobel.scale: 0 is out of range (0, ∞)"), std::string::npos) << message({"sobel:scale=0"}, {});
  // The strict parsers: no spaces, no trailing text, integers for integer parameters.
  EXPECT_TRUE(usage({"lowpass:order=2.0"}, {}));
  EXPECT_TRUE(usage({"sepia:i= 0.1"}, {}));
  EXPECT_TRUE(usage({"sepia:i=0.1x"}, {}));
  EXPECT_FALSE(usage({"sepia:i=+0.1", "lowpass:order=3"}, {}));
  // A value a program or a slider set outside the range is refused by the chain.
  auto sepia = parseEffects(std::vector<std::string>{"sepia"});
  sepia[0].values[0] = 2.0f;
  EXPECT_THROW(validateEffect(sepia[0], ivec2(64, 64)), Error);
  EXPECT_THROW(Chain(ivec2(64, 64), parseEffects(std::vector<std::string>{"kuwahara:size=9"})), Error);
  EXPECT_THROW(Chain(ivec2(16, 16), parseEffects(std::vector<std::string>{"blur:sigma=12"})), Error);
}

// post's table is GL-free and the GPU registers its passes against it by name: every entry
// (aliases aside) must find its pass here and carry its CPU stage there, or an effect would
// parse and then fail on one backend.
TEST_F(PostGpu, EveryEffectOfTheTableHasAGpuPassAndACpuStage) {
  int effects = 0;
  for (const EffectDef& def : effectTable()) {
    if (!def.expandsTo.empty()) continue;
    ++effects;
    EXPECT_TRUE(gpuHas(def)) << def.name;
    EXPECT_NE(def.cpu, nullptr) << def.name;
    EXPECT_NE(gpuStage(def), nullptr) << def.name;  // (backend_test builds a CpuChain of each)
  }
  EXPECT_GE(effects, 9);  // sepia, sobel, edges, kuwahara, spectrum and the five FFT filters
  EXPECT_FALSE(gpuHas(EffectDef{.name = "no-such-effect"}));
  EXPECT_THROW(gpuStage(EffectDef{.name = "no-such-effect"}), Error);
}
