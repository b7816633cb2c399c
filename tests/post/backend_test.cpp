// glint post's CPU backend (post/cpu.h): every CPU effect against the CPU references
// (image/post.h, image/fourier.h) and against the GPU passes on llvmpipe, the YUV path
// against the RGB path it replaces (decode to RGB, effect, encode to BT.709 YUV), the
// backend's parsing and the choice `auto` makes, and `glint post --backend` as a user runs it.
#include "glint/core/error.h"
#include "glint/gl/context.h"
#include "glint/image/fourier.h"
#include "glint/image/post.h"
#include "glint/post/cpu.h"
#include "glint/render/post/chain.h"
#include "glint/video/sink.h"
#include "glint/video/source.h"

#include "post_test_util.h"
#include "support/cli.h"
#include "support/gl_test.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

using namespace glint;
using namespace glint::post;
using namespace glint::render::post;
using glint::testing::compareSteps;
using glint::testing::crop;
using glint::testing::noiseImage;
using glint::testing::photograph;
using glint::testing::runGlint;

namespace {
class PostCpu : public glint::testing::GlTest {};

std::vector<std::pair<std::string, Image>> inputs() { return glint::testing::postInputs(); }

Image cpuRun(const Image& image, const std::string& spec) {
  CpuChain chain({image.width(), image.height()}, parseEffects(std::vector<std::string>{spec}));
  return chain.run(image);
}

// ---- The YUV side, written out independently of cpu_yuv.cpp: BT.601/709, limited range.
struct Kr {
  double r, b;
};
Kr kOf(video::YuvMatrix m) { return m == video::YuvMatrix::Bt709 ? Kr{0.2126, 0.0722} : Kr{0.299, 0.114}; }

// An RGBA image → a Yuv420 frame (chroma: the 2×2 mean), as an encoder would.
video::Frame toYuv(const Image& rgba, video::YuvMatrix m) {
  const Kr k = kOf(m);
  const int w = rgba.width(), h = rgba.height();
  video::Frame f;
  f.format = video::FrameFormat::Yuv420;
  f.matrix = m;
  f.image = Image(w, h + h / 2, 1, PixelType::U8);
  auto* y = reinterpret_cast<std::uint8_t*>(f.image.bytes().data());
  auto* u = y + w * h;
  auto* v = u + (w / 2) * (h / 2);
  std::vector<double> cb(std::size_t(w) * h), cr(std::size_t(w) * h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double r = rgba.at(i, j, 0), g = rgba.at(i, j, 1), b = rgba.at(i, j, 2);
      const double l = k.r * r + (1 - k.r - k.b) * g + k.b * b;
      y[j * w + i] = std::uint8_t(std::lround(16 + 219 * l));
      cb[std::size_t(j) * w + i] = (b - l) / (2 * (1 - k.b));
      cr[std::size_t(j) * w + i] = (r - l) / (2 * (1 - k.r));
    }
  }
  for (int j = 0; j < h / 2; ++j) {
    for (int i = 0; i < w / 2; ++i) {
      const auto mean = [&](const std::vector<double>& c) {
        return (c[std::size_t(2 * j) * w + 2 * i] + c[std::size_t(2 * j) * w + 2 * i + 1] +
                c[std::size_t(2 * j + 1) * w + 2 * i] + c[std::size_t(2 * j + 1) * w + 2 * i + 1]) / 4;
      };
      u[j * (w / 2) + i] = std::uint8_t(std::lround(128 + 224 * mean(cb)));
      v[j * (w / 2) + i] = std::uint8_t(std::lround(128 + 224 * mean(cr)));
    }
  }
  return f;
}

// A Yuv420 frame → RGBA8 (chroma of the pixel's 2×2 block), clamped, as a decoder would.
Image toRgb(const video::Frame& f, int w, int h) {
  const Kr k = kOf(f.matrix);
  const auto* y = reinterpret_cast<const std::uint8_t*>(f.image.bytes().data());
  const auto* u = y + w * h;
  const auto* v = u + (w / 2) * (h / 2);
  Image out(w, h, 4);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double l = (y[j * w + i] - 16) / 219.0;
      const double cb = (u[(j / 2) * (w / 2) + i / 2] - 128) / 224.0, cr = (v[(j / 2) * (w / 2) + i / 2] - 128) / 224.0;
      const double r = l + 2 * (1 - k.r) * cr, b = l + 2 * (1 - k.b) * cb;
      const double g = (l - k.r * r - k.b * b) / (1 - k.r - k.b);
      out.set(i, j, 0, float(std::clamp(r, 0.0, 1.0)));
      out.set(i, j, 1, float(std::clamp(g, 0.0, 1.0)));
      out.set(i, j, 2, float(std::clamp(b, 0.0, 1.0)));
      out.set(i, j, 3, 1.0f);
    }
  }
  return out;
}
}  // namespace

TEST_F(PostCpu, EveryCpuEffectMatchesItsReferenceWithinAStep) {
  // The same bounds as the GPU passes (gpu_test.cpp): one 8-bit step, the reference being
  // unrounded; Kuwahara's quadrant choice is exact (64-bit integer variances), so its result
  // is the reference's mean rounded.
  for (const auto& [name, image] : inputs()) {
    for (const char* sepia : {"sepia", "sepia:i=-0.3,q=0.25"}) {
      const Effect e = parseEffects(std::vector<std::string>{sepia})[0];
      EXPECT_LE(compareSteps(cpuRun(image, sepia), sepiaReference(image, {.i = e.value("i"), .q = e.value("q")})).maxSteps, 1)
          << name << " " << sepia;
    }
    const std::vector<std::pair<const char*, SobelOutput>> sobels = {
        {"magnitude", SobelOutput::Magnitude}, {"horizontal", SobelOutput::Horizontal},
        {"vertical", SobelOutput::Vertical},   {"dx", SobelOutput::SignedX}, {"dy", SobelOutput::SignedY}};
    for (const auto& [output, kind] : sobels) {
      const Image cpu = cpuRun(image, std::string("sobel:scale=2,output=") + output);
      EXPECT_LE(compareSteps(cpu, sobelReference(image, {.output = kind, .scale = 2.0f})).maxSteps, 1) << name << " " << output;
    }
    EXPECT_LE(compareSteps(cpuRun(image, "edges"), edgesReference(image)).maxSteps, 1) << name;
    // FFTW's transform against the reference's own DFT in double (image/fourier.h).
    EXPECT_LE(compareSteps(cpuRun(image, "spectrum"), spectrumReference(image)).maxSteps, 1) << name;
    for (int size = 2; size <= 8; size += 3) {
      const auto reference = kuwaharaReference(image, {.size = size});
      const auto d = compareSteps(cpuRun(image, "kuwahara:size=" + std::to_string(size)), reference.image, 0);
      EXPECT_LE(d.maxSteps, 1) << name << " s=" << size;  // .5 cases may round either way
    }
  }
  // The FFT filters against the direct DFT in double (gpu_test.cpp's filters, same size).
  const Image image = crop(photograph(), 130, 80, 60, 44);
  for (const char* spec : {"lowpass:cutoff=0.08", "lowpass:cutoff=0.1,order=0", "highpass:cutoff=0.05",
                           "bandpass:high=0.2,low=0.05", "blur:sigma=2.5", "bokeh:radius=4"}) {
    const Effect e = parseEffects(std::vector<std::string>{spec})[0];
    FrequencyFilter f;
    const std::string name = e.name();
    if (name == "blur" || name == "bokeh") {
      f = {.kind = FilterKind::Kernel, .kernel = name == "blur" ? KernelShape::Gaussian : KernelShape::Disk,
           .size = e.value(name == "blur" ? "sigma" : "radius")};
    } else {
      f.kind = name == "lowpass" ? FilterKind::LowPass : name == "highpass" ? FilterKind::HighPass : FilterKind::BandPass;
      f.cutoff = e.value(name == "bandpass" ? "high" : "cutoff");
      if (name == "bandpass") f.low = e.value("low");
      f.order = int(e.value("order"));
      f.offset = e.value("offset");
    }
    const auto d = compareSteps(cpuRun(image, spec), frequencyFilterReference(image, f));
    EXPECT_LE(d.maxSteps, 1) << spec << " at " << d.worstX << "," << d.worstY;
  }
}

TEST_F(PostCpu, CpuEqualsTheGpuPathWithinAStep) {
  // Both are within a step of the same unrounded reference, and round the same values: on
  // these inputs they never differ by more than one step.
  for (const auto& [name, image] : inputs()) {
    for (const char* spec : {"sepia", "sobel", "sobel:output=dy,scale=3", "edges", "kuwahara", "posterize", "spectrum",
                             "lowpass", "highpass", "blur:sigma=3"}) {
      if (std::string(spec) == "blur:sigma=3" && name == "odd") continue;  // σ must be < min(w, h)/2
      const std::vector<std::string> specs{spec};
      CpuChain cpu({image.width(), image.height()}, parseEffects(specs));
      Chain gpu({image.width(), image.height()}, parseEffects(specs));
      const auto d = compareSteps(cpu.run(image), gpu.run(image));
      EXPECT_LE(d.maxSteps, 1) << name << " " << spec << " at " << d.worstX << "," << d.worstY;
      std::printf("[figure] %s %s: cpu vs gpu max %d step(s), mean %.4f\n", name.c_str(), spec, d.maxSteps, d.meanSteps);
    }
  }
}

TEST_F(PostCpu, TheYuvPathMatchesTheRgbPathItReplaces) {
  // The RGB path: decode (to RGBA8, chroma of the pixel's block), the effect, encode to
  // BT.709 4:2:0 (2×2 mean). The YUV path works on the planes. Compared after decoding both
  // to RGB they differ where the RGB path clips colours a 4:2:0 frame puts out of gamut and
  // where the two interpolate chroma differently: colour edges. Measured (the [figure]
  // lines): max 21 steps at such edges, mean 0.23–0.68 steps. Bounds: mean under one step,
  // max under 32; a wrong matrix, a swapped plane or a shifted row gives means of 5 and more.
  const Image photo = photograph();
  const int w = photo.width(), h = photo.height();
  for (const video::YuvMatrix matrix : {video::YuvMatrix::Bt601, video::YuvMatrix::Bt709}) {
    const video::Frame input = toYuv(photo, matrix);
    const Image decoded = toRgb(input, w, h);  // what the GPU path works on
    for (const char* spec : {"sepia", "sobel", "sobel:output=dx", "lowpass", "highpass", "blur"}) {
      const std::vector<std::string> specs{spec};
      CpuChain chain({w, h}, parseEffects(specs));
      ASSERT_TRUE(chain.worksOnYuv()) << spec;
      video::Frame frame = input;
      chain.run(frame);
      ASSERT_EQ(frame.format, video::FrameFormat::Yuv420);
      EXPECT_EQ(frame.matrix, video::YuvMatrix::Bt709) << "the YUV path writes BT.709";
      const Image viaRgb = toRgb(toYuv(chain.run(decoded), video::YuvMatrix::Bt709), w, h);
      const Image viaYuv = toRgb(frame, w, h);
      const auto d = compareSteps(viaYuv, viaRgb, 3);
      EXPECT_LT(d.maxSteps, 32) << spec << " at " << d.worstX << "," << d.worstY;
      EXPECT_LT(d.meanSteps, 1.0) << spec;
      std::printf("[figure] yuv path %s (%s in): max %d step(s), mean %.3f vs the rgb path\n", spec,
                  matrix == video::YuvMatrix::Bt709 ? "709" : "601", d.maxSteps, d.meanSteps);
    }
  }
  // Chains of several effects and Kuwahara work on RGBA.
  EXPECT_FALSE(CpuChain({w, h}, parseEffects(std::vector<std::string>{"kuwahara"})).worksOnYuv());
  EXPECT_FALSE(CpuChain({w, h}, parseEffects(std::vector<std::string>{"sepia", "sobel"})).worksOnYuv());
  EXPECT_FALSE(cpuWorksOnYuv(parseEffects(std::vector<std::string>{"posterize"})));
}

TEST(PostBackend, ParsingAndSoftwareRenderers) {
  EXPECT_EQ(parseBackend("auto"), Backend::Auto);
  EXPECT_EQ(parseBackend("gpu"), Backend::Gpu);
  EXPECT_EQ(parseBackend("cpu"), Backend::Cpu);
  for (const char* bad : {"", "CPU", "vulkan", "cpu "}) {
    try {
      parseBackend(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage);
      EXPECT_EQ(std::string(e.what()), fmt::format("--backend must be auto, gpu or cpu, got '{}'", bad));
    }
  }
  EXPECT_STREQ(backendName(Backend::Cpu), "cpu");
  EXPECT_TRUE(isSoftwareRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
  EXPECT_TRUE(isSoftwareRenderer("softpipe"));
  EXPECT_TRUE(isSoftwareRenderer("Google SwiftShader"));
  EXPECT_FALSE(isSoftwareRenderer("NVIDIA H100 80GB HBM3/PCIe/SSE2"));
  EXPECT_FALSE(isSoftwareRenderer("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.7, DRM 3.54, 6.5.0)"));
  // Every effect glint post has runs on the CPU too: `auto` never falls back to a software GPU.
  const std::vector<std::string> every = effectNames();
  ASSERT_GE(every.size(), 10u);
  EXPECT_EQ(cpuMissing(parseEffects(every)), "");
  for (const std::string& name : every) EXPECT_NO_THROW(CpuChain({64, 64}, parseEffects(std::vector<std::string>{name}))) << name;
}

TEST(PostBackend, TheCommandChoosesAndReportsItsBackend) {
  const auto d = glint::testing::freshDir("post-backend", "cli");
  const std::string in = (d / "in.png").string();
  saveImage(photograph(), in);
  // This suite runs on llvmpipe: auto is the CPU, unless an effect has no CPU version.
  const auto autoRun = runGlint("-v post " + in + " -o " + (d / "a.png").string() + " -e sepia");
  ASSERT_EQ(autoRun.status, 0) << autoRun.output;
  const std::string renderer = [] {
    const auto context = gl::HeadlessContext::create();
    return gl::queryContextInfo().renderer;
  }();
  const bool software = isSoftwareRenderer(renderer);
  // The cheap test auto makes first never calls a GPU software.
  if (gl::onlySoftwareDevices()) {
    EXPECT_TRUE(software) << renderer;
  }
  std::printf("[figure] renderer %s; EGL lists only software devices: %s\n", renderer.c_str(),
              gl::onlySoftwareDevices() ? "yes" : "no");
  EXPECT_NE(autoRun.output.find(software ? "(cpu)" : "(gpu)"), std::string::npos) << renderer << "\n" << autoRun.output;
  const auto spectrum = runGlint("-v post " + in + " -o " + (d / "s.png").string() + " -e spectrum");
  ASSERT_EQ(spectrum.status, 0) << spectrum.output;
  EXPECT_NE(spectrum.output.find(software ? "(cpu)" : "(gpu)"), std::string::npos) << spectrum.output;
  // Forced either way: the same picture within a step.
  for (const char* backend : {"cpu", "gpu"}) {
    const auto r = runGlint(fmt::format("-v post {} -o {} -e posterize --backend {}", in, (d / fmt::format("{}.png", backend)).string(), backend));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(fmt::format("({})", backend)), std::string::npos) << r.output;
  }
  EXPECT_LE(compareSteps(loadImage(d / "cpu.png"), loadImage(d / "gpu.png")).maxSteps, 1);
  // Bad values and effects the CPU lacks: one line, usage status.
  const auto bad = runGlint("post " + in + " -o " + (d / "b.png").string() + " -e sepia --backend metal");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("--backend must be auto, gpu or cpu, got 'metal'"), std::string::npos) << bad.output;
  // No texture limit on the CPU: an image wider than any GPU's largest texture (16384 on
  // llvmpipe) is processed.
  Image wide(16400, 4, 4);
  for (auto& b : wide.bytes()) b = std::byte(200);
  saveImage(wide, d / "wide.png");
  const auto wideRun = runGlint("post " + (d / "wide.png").string() + " -o " + (d / "w.png").string() + " -e sepia --backend cpu");
  EXPECT_EQ(wideRun.status, 0) << wideRun.output;
  EXPECT_LE(compareSteps(loadImage(d / "w.png"), sepiaReference(wide)).maxSteps, 1);
  const auto help = runGlint("post --help");
  EXPECT_NE(help.output.find("--backend"), std::string::npos);
}

TEST(PostBackend, VideoOnTheCpuMatchesTheGpuPath) {
  // A lossless H.264 (CRF 0, yuv420p) clip: the YUV path (sepia, sobel, lowpass) and the
  // RGBA path (posterize) against --backend gpu on the same file, decoded. The bound is the
  // H.264 round trip's own oracle (video_test.cpp's H264RoundTripIsClose: mean absolute
  // difference under 0.02, what 4:2:0 costs testsrc2's sharp coloured edges): the two paths
  // differ by the decoder's bicubic chroma (and its clipping) against the YUV path's
  // bilinear chroma, which Sobel of the BT.601 luma of a BT.709 video sees at every
  // coloured edge. Measured: mean 0.6 (sepia), 2.0 (sobel), 0.9 (lowpass) steps; posterize
  // (RGBA on both) 0.
  const auto d = glint::testing::freshDir("post-backend", "video");
  const std::string clip = (d / "clip.mp4").string();
  {
    video::Source pattern = video::Source::open("lavfi:testsrc2=size=320x240:rate=24:duration=0.5");
    video::Sink sink(clip, {.codec = video::Codec::H264, .size = {320, 240}, .frameRate = {24, 1},
                            .timeBase = pattern.info().timeBase, .crf = 0, .preset = "ultrafast"});
    video::Frame f;
    while (pattern.read(f)) sink.write(f);
    sink.finish();
  }
  for (const char* effect : {"sepia", "sobel", "lowpass", "posterize"}) {
    std::vector<std::vector<video::Frame>> outputs;
    for (const char* backend : {"cpu", "gpu"}) {
      const std::string out = (d / fmt::format("{}-{}.mp4", effect, backend)).string();
      const auto r = runGlint(fmt::format("-v post {} -o {} -e {} --crf 0 --preset ultrafast --backend {}", clip, out,
                                          effect, backend));
      ASSERT_EQ(r.status, 0) << r.output;
      if (std::string(backend) == "cpu" && std::string(effect) != "posterize") {
        EXPECT_NE(r.output.find("(in YUV)"), std::string::npos) << r.output;
      }
      video::Source source = video::Source::open(out);
      std::vector<video::Frame> frames;
      video::Frame f;
      while (source.read(f)) frames.push_back(f);
      outputs.push_back(std::move(frames));
    }
    ASSERT_EQ(outputs[0].size(), 12u);
    ASSERT_EQ(outputs[1].size(), outputs[0].size());
    int worst = 0;
    double mean = 0;
    for (std::size_t i = 0; i < outputs[0].size(); ++i) {
      const auto diff = compareSteps(outputs[0][i].image, outputs[1][i].image, 4);
      worst = std::max(worst, diff.maxSteps);
      mean += diff.meanSteps / double(outputs[0].size());
    }
    std::printf("[figure] video %s: cpu vs gpu max %d step(s), mean %.3f\n", effect, worst, mean);
    EXPECT_LT(mean, 0.02 * 255.0) << effect;
    if (std::string(effect) == "posterize") {
      EXPECT_LE(worst, 1) << "the RGBA path: the GPU's within a step";
    }
  }
}
