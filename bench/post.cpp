// bench post — WWDC 2003 session 212's effects per frame at the talk's camera size (640×480), 1080p and
// 4K, on the GPU and on the CPU backend (post/cpu.h), each against its CPU
// equivalent in OpenCV (and the FFT against FFTW) measured in the same run, alternating
// runs, medians; and `glint post` end to end (decode → effect → encode, H.264) at 640×480
// and 1080p against FFmpeg's nearest filter chain on the same file with the same encoder
// settings, and the 1080p GPU pipeline against the same pipeline without effects.
//
// Every GPU row's note gives the bytes its passes must move at least (each texel read and
// written once per pass) and the time that takes at an H100's 3.35 TB/s: the memory-
// bandwidth bound the issue asks each effect to be compared with on a GPU.
#include "glint/bench/bench.h"
#include "glint/gl/timer.h"
#include "glint/post/cpu.h"
#include "glint/render/post/chain.h"
#include "glint/render/post/fft.h"
#include "glint/render/post/passes.h"
#include "glint/core/error.h"

#include <cmath>
#include "glint/video/sink.h"
#include "glint/video/source.h"
#include "glint/video/transcode.h"

#include "post_peers.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <unistd.h>

namespace glint::bench {
namespace {
namespace post = render::post;
using Clock = std::chrono::steady_clock;

constexpr double kH100Bandwidth = 3.35e12;  // bytes/s, H100 SXM HBM3

double msOf(const std::function<void()>& work, bool gl) {
  const auto start = Clock::now();
  work();
  if (gl) glFinish();
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Medians of `rounds` alternating runs of the GPU work (with glFinish) and the peer's, after
// one warm-up of each: both see the same machine state (clocks, other load).
std::pair<double, double> alternating(const std::function<void()>& gpu, const std::function<void()>& peer, int rounds) {
  msOf(gpu, true);
  if (peer) msOf(peer, false);
  std::vector<double> a, b;
  for (int i = 0; i < rounds; ++i) {
    a.push_back(msOf(gpu, true));
    if (peer) b.push_back(msOf(peer, false));
  }
  return {median(a), peer ? median(b) : 0.0};
}

Image noise(ivec2 size) {
  std::mt19937 rng(7);
  Image image(size.x, size.y, 4);
  auto px = image.pixels<std::uint8_t>();
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = std::uint8_t(i % 4 == 3 ? 255 : rng() & 0xFF);
  return image;
}

std::string bound(double bytes) {
  return fmt::format("≥ {:.0f} MB/frame: ≥ {:.0f} µs at 3.35 TB/s", bytes / 1e6, bytes / kH100Bandwidth * 1e6);
}

// Bytes one FFT pass sequence moves: every radix pass reads and writes each element.
double fftBytes(const post::Fft2d& fft) {
  const double elements = double(fft.size().x) * fft.size().y;
  const double passes = double(fft.dispatches());  // each reads and writes the buffer once
  return passes * elements * 2.0 * 8.0 * fft.lanes();
}

void runEffects(Recorder& recorder) {
  // GLINT_BENCH_POST_SIZES=640x480,1920x1080 measures only those sizes (unset: all three).
  // GLINT_BENCH_QUICK: 160×120 only, two rounds.
  const char* only = std::getenv("GLINT_BENCH_POST_SIZES");
  const std::vector<ivec2> sizes =
      quick() ? std::vector<ivec2>{{160, 120}} : std::vector<ivec2>{{640, 480}, {1920, 1080}, {3840, 2160}};
  for (const ivec2 size : sizes) {
    if (only && !quick() && !std::strstr(only, fmt::format("{}x{}", size.x, size.y).c_str())) continue;
    const std::string group = fmt::format("{}x{}", size.x, size.y);
    const double pixels = double(size.x) * size.y;
    const int rounds = quick() ? 2 : size.x >= 3840 ? 3 : size.x >= 1920 ? 5 : 9;
    const Image input = noise(size);  // the cost of these effects does not depend on the content
    const gl::Texture in = post::uploadFrame(input, "bench-input");
    gl::Texture out(GL_TEXTURE_2D, "bench-output");
    out.storage(GL_RGBA8, size.x, size.y);

    const auto row = [&](const std::string& name, const std::function<void()>& gpu, const std::string& peerName,
                         const peers::Work& peer, const std::string& peerNote, double bytes) {
      const auto [gpuMs, peerMs] = alternating(gpu, peer, rounds);
      const double timerMs = gl::GpuTimer::measureMs(gpu, rounds, 1);
      if (peer) recorder.record({.group = group, .name = peerName, .value = peerMs, .unit = "ms", .note = peerNote});
      recorder.record({.group = group, .name = name, .value = gpuMs, .unit = "ms", .ratioTo = peer ? peerName : "",
                       .note = fmt::format("wall incl. glFinish; GL_TIME_ELAPSED {:.3f} ms; {:.0f} Mpixel/s; {}",
                                           timerMs, pixels / (gpuMs * 1e3), bound(bytes))});
    };
    const std::string threads = fmt::format("{} thread(s)", peers::peerThreads());
    // The CPU backend on the same frame, against the same peer (same run, alternating).
    video::Frame frame{.image = input};  // run in place, frame after frame (the cost does not depend on the content)
    const auto cpuRow = [&](const std::string& spec, const std::string& peerName, const peers::Work& peer) {
      glint::post::CpuChain chain(size, post::parseEffects(std::vector<std::string>{spec}));
      const auto [cpuMs, peerMs] = alternating([&] { chain.run(frame); }, peer, rounds);
      (void)peerMs;
      recorder.record({.group = group, .name = spec + " cpu", .value = cpuMs, .unit = "ms", .ratioTo = peerName,
                       .note = fmt::format("post/cpu.h on RGBA8, {:.0f} Mpixel/s",
                                           pixels / (cpuMs * 1e3))});
      if (!chain.worksOnYuv()) return;
      // The video path: the decoder's 4:2:0 planes in, the encoder's out (no RGB at all).
      video::Frame yuv{.image = Image(size.x, size.y + size.y / 2, 1), .format = video::FrameFormat::Yuv420};
      std::mt19937 rng(3);
      for (auto& b : yuv.image.bytes()) b = std::byte(16 + rng() % 220);
      // In place, frame after frame: these effects' cost does not depend on the content.
      const auto [yuvMs, unused] = alternating([&] { chain.run(yuv); }, {}, rounds);
      (void)unused;
      recorder.record({.group = group, .name = spec + " cpu yuv", .value = yuvMs, .unit = "ms", .ratioTo = peerName,
                       .note = "the same on YUV 4:2:0 planes, as glint post runs it on H.264"});
    };

    post::SepiaPass sepia;
    row("sepia gpu", [&] { sepia.run(in, out); }, "sepia opencv", peers::opencvSepia(input),
        "cv::transform, the 4×4 colour-matrix sepia, 8-bit, " + threads, pixels * 8);
    cpuRow("sepia", "sepia opencv", peers::opencvSepia(input));
    // The fragment version of each compute pass (issue 37), same frame, same run: the ratio
    // column is fragment ÷ compute, above 1 where the compute shader is faster.
    const auto fragmentRow = [&](const std::string& pass, const std::function<void()>& work) {
      const auto [ms, unused] = alternating(work, {}, rounds);
      (void)unused;
      recorder.record({.group = group, .name = pass + " gpu (fragment)", .value = ms, .unit = "ms",
                       .ratioTo = pass + " gpu",
                       .note = fmt::format("the same texels as a fragment pass; GL_TIME_ELAPSED {:.3f} ms",
                                           gl::GpuTimer::measureMs(work, rounds, 1))});
    };
    post::SepiaPass sepiaFragment(post::PassStage::Fragment);
    fragmentRow("sepia", [&] { sepiaFragment.run(in, out); });
    post::SobelPass sobel;
    row("sobel gpu", [&] { sobel.run(in, out); }, "sobel opencv", peers::opencvSobel(input),
        "cvtColor + 2× cv::Sobel + magnitude, float, " + threads, pixels * 8);
    cpuRow("sobel", "sobel opencv", peers::opencvSobel(input));
    post::SobelPass sobelFragment(post::PassStage::Fragment);
    fragmentRow("sobel", [&] { sobelFragment.run(in, out); });
    post::EdgesPass edges, edgesFragment(post::PassStage::Fragment);
    row("edges gpu", [&] { edges.run(in, out); }, "", {}, "", pixels * 8);
    fragmentRow("edges", [&] { edgesFragment.run(in, out); });
    post::KuwaharaPass kuwahara, kuwaharaFragment(post::PassStage::Fragment);
    row("kuwahara gpu", [&] { kuwahara.run(in, out); }, "kuwahara opencv", peers::opencvKuwahara(input),
        "cv::boxFilter of I and I² + quadrant selection (parallel_for_), " + threads,
        pixels * (4 + 16) + pixels * (16 + 4 + 4));
    cpuRow("kuwahara", "kuwahara opencv", peers::opencvKuwahara(input));
    fragmentRow("kuwahara", [&] { kuwaharaFragment.run(in, out); });
    post::Chain posterize(size, post::parseEffects(std::vector<std::string>{"posterize"}));
    const auto kuwaharaPeer = peers::opencvKuwahara(input), sobelPeer = peers::opencvSobel(input);
    row("posterize gpu", [&] { posterize.run(in); }, "posterize opencv", [&] { kuwaharaPeer(); sobelPeer(); },
        "the OpenCV Kuwahara and Sobel above, together", pixels * (4 + 16) + pixels * (16 + 4 + 4) + pixels * 8);
    cpuRow("posterize", "posterize opencv", [&] { kuwaharaPeer(); sobelPeer(); });
    post::SpectrumPass spectrum;
    post::Fft2d luma(size, 1), colour(size, 2);
    // Bytes a frame moves. The real-input path (RealFft2d): the texture in (4 a pixel), the
    // half planes (8 bytes a frequency, about half a pixel's worth a channel) written and
    // read once per dispatch, the image out. The complex path: load, the axes, the show or
    // multiply and store passes, each through the whole buffer.
    const double half = double(size.x / 2 + 1) * size.y * 8.0;
    const auto spectrumBytes = [&](bool real) {
      return real ? pixels * 4 + 2 * half + pixels * 4 : pixels * (4 + 8) + fftBytes(luma) + pixels * (8 + 4);
    };
    const auto filterBytes = [&](bool real) {  // real: rows, columns and H (a plane), inverse rows with the alpha
      return real ? pixels * 4 + 3 * half + 6 * half + half + 3 * half + pixels * 8
                  : pixels * (4 + 16) + 2 * fftBytes(colour) + pixels * (16 + 8 + 16) + pixels * (16 + 4 + 4);
    };
    spectrum.run(in, out);  // decides its path
    row("spectrum gpu", [&] { spectrum.run(in, out); }, "spectrum opencv", peers::opencvSpectrum(input),
        "cvtColor + cv::dft + magnitude + log, " + threads, spectrumBytes(spectrum.realInput()));
    cpuRow("spectrum", "spectrum opencv", peers::opencvSpectrum(input));
    post::FrequencyFilterPass lowpass;
    const FrequencyFilter filter{.kind = FilterKind::LowPass, .cutoff = 0.05f, .order = 2};
    lowpass.run(in, out, filter);
    row("lowpass gpu", [&] { lowpass.run(in, out, filter); }, "lowpass opencv", peers::opencvFrequencyFilter(input),
        "3× (cv::dft + mulSpectrums + idft), " + threads, filterBytes(lowpass.realInput()));
    cpuRow("lowpass", "lowpass opencv", peers::opencvFrequencyFilter(input));
    // The other transform (issue 37), same frame, same run: the real-input one fused with the
    // view or the filter (2 or 3 dispatches), or the complex one with its load, multiply and
    // store passes. The default is the first on a GPU. The ratio column is other ÷ default.
    const auto otherPath = [&](const std::string& name, bool realByDefault, const std::function<void(post::FftPath)>& set,
                               const std::function<void()>& work, const std::function<double(bool)>& bytes) {
      if (!realByDefault && !post::RealFft2d::fits(size)) return;
      set(realByDefault ? post::FftPath::Complex : post::FftPath::RealInput);
      work();  // plans the other path
      const auto [ms, unused] = alternating(work, {}, rounds);
      (void)unused;
      recorder.record({.group = group, .name = name + (realByDefault ? " gpu (complex FFT)" : " gpu (real-input, fused)"),
                       .value = ms, .unit = "ms", .ratioTo = name + " gpu",
                       .note = fmt::format("GL_TIME_ELAPSED {:.3f} ms; {}", gl::GpuTimer::measureMs(work, rounds, 1),
                                           bound(bytes(!realByDefault)))});
      set(post::FftPath::Auto);
    };
    otherPath("spectrum", spectrum.realInput(), [&](post::FftPath p) { spectrum.setPath(p); },
              [&] { spectrum.run(in, out); }, spectrumBytes);
    otherPath("lowpass", lowpass.realInput(), [&](post::FftPath p) { lowpass.setPath(p); },
              [&] { lowpass.run(in, out, filter); }, filterBytes);
    row("fft gpu", [&] { luma.run(0, post::FftDirection::Forward); }, "fft fftw", peers::fftwForward(size),
        fmt::format("fftwf_execute, 2D complex float, FFTW_MEASURE, {} thread(s)", std::max(1u, std::thread::hardware_concurrency())),
        fftBytes(luma));
    {
      // The other way to run the axes (issue 37): one dispatch an axis through shared memory
      // (fft_axis.comp), or one a radix pass; the default is the first on a GPU, the second
      // on a software rasterizer. The ratio column is other ÷ default.
      const bool shared = luma.inSharedMemory(0) || luma.inSharedMemory(1);
      const int dispatches = luma.dispatches();
      luma.setSharedAxes(!shared);
      const auto other = [&] { luma.run(0, post::FftDirection::Forward); };
      const auto [otherMs, none] = alternating(other, {}, rounds);
      (void)none;
      recorder.record({.group = group, .name = shared ? "fft gpu (per-radix passes)" : "fft gpu (one dispatch an axis)",
                       .value = otherMs, .unit = "ms", .ratioTo = "fft gpu",
                       .note = fmt::format("{} dispatches against the default's {}; GL_TIME_ELAPSED {:.3f} ms",
                                           luma.dispatches(), dispatches, gl::GpuTimer::measureMs(other, rounds, 1))});
      luma.setSharedAxes(shared);
    }
    const auto [dftMs, unused] = alternating(peers::opencvDft(size), {}, rounds);
    (void)unused;
    recorder.record({.group = group, .name = "fft opencv", .value = dftMs, .unit = "ms", .ratioTo = "fft fftw",
                     .note = "cv::dft, 2D complex float, " + threads});
  }
}

// An identity stage that does nothing on the GPU: the pipeline's peer (decode → encode).
class PassThrough final : public video::FrameProcessor {
public:
  void process(video::Frame&& frame, const Emit& emit) override { emit(std::move(frame)); }
  void flush(const Emit&) override {}
};

void runEndToEnd(Recorder& recorder) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / fmt::format("glint-bench-post-{}", getpid());
  fs::create_directories(dir);
  const fs::path clip = dir / "clip.mp4";
  const ivec2 size(1920, 1080);
  {  // The input: 48 frames of a moving test pattern, H.264.
    video::Source pattern = video::Source::open("lavfi:testsrc2=size=1920x1080:rate=24:duration=2");
    video::Sink sink(clip, {.codec = video::Codec::H264, .size = size, .frameRate = {24, 1},
                            .timeBase = pattern.info().timeBase, .preset = "ultrafast"});
    video::Frame f;
    while (pattern.read(f)) sink.write(f);
    sink.finish();
  }
  const std::string group = "1080p H.264";
  const std::string preset = "veryfast";
  // Decoding alone: the ceiling of any pipeline on this file.
  {
    const auto start = Clock::now();
    video::Source source = video::Source::open(clip.string());
    video::Frame f;
    std::int64_t n = 0;
    while (source.read(f)) ++n;
    const double s = std::chrono::duration<double>(Clock::now() - start).count();
    recorder.record({.group = group, .name = "decode only", .value = double(n) / s, .unit = "fps",
                     .note = "libavcodec + swscale to RGBA"});
  }
  const auto transcodeFps = [&](video::FrameProcessor& processor) {
    video::Source source = video::Source::open(clip.string());
    video::Sink sink(dir / "out.mp4", {.codec = video::Codec::H264, .size = size, .frameRate = source.info().frameRate,
                                       .timeBase = source.info().timeBase, .preset = preset});
    const auto stats = video::transcode(source, sink, processor);
    return double(stats.framesWritten) / stats.seconds;
  };
  PassThrough passThrough;
  recorder.record({.group = group, .name = "decode+encode", .value = transcodeFps(passThrough), .unit = "fps",
                   .note = fmt::format("the same pipeline without the GPU (x264 preset {})", preset)});
  for (const char* effect : {"sepia", "posterize"}) {
    post::FrameStream stream(size, post::parseEffects(std::vector<std::string>{effect}));
    video::StreamProcessor processor(stream);
    recorder.record({.group = group, .name = fmt::format("post -e {} gpu", effect), .value = transcodeFps(processor),
                     .unit = "fps", .ratioTo = "decode+encode",
                     .note = "decode → PBO upload → effect → PBO readback → encode, overlapped on 3 threads"});
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// Wall seconds of a shell command; negative when it fails.
double commandSeconds(const std::string& command) {
  const auto start = Clock::now();
  const int status = std::system(command.c_str());
  const double s = std::chrono::duration<double>(Clock::now() - start).count();
  return status == 0 ? s : -1.0;
}

// `glint post` as a user runs it (the command, backend auto: the CPU on llvmpipe) against
// FFmpeg's nearest filter on the same H.264 file, both encoding with libx264 at the same
// preset and CRF into yuv420p, every core each; alternating runs, medians.
void runAgainstFfmpeg(Recorder& recorder) {
  namespace fs = std::filesystem;
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) {
    recorder.record({.group = "end to end", .name = "ffmpeg", .value = 0, .unit = "fps", .note = "peer unavailable: no ffmpeg on PATH"});
    return;
  }
  const fs::path dir = fs::temp_directory_path() / fmt::format("glint-bench-post-ffmpeg-{}", getpid());
  fs::create_directories(dir);
  const std::string glint = fs::read_symlink("/proc/self/exe").string();
  const std::string encode = "-c:v libx264 -preset veryfast -crf 18";
  // glint's nearest FFmpeg chains (colorchannelmixer and edgedetect work on RGB: converted
  // back to yuv420p for the encoder, as glint's sink does).
  const std::vector<std::pair<std::string, std::string>> effects = {
      {"sepia", "colorchannelmixer=.393:.769:.189:0:.349:.686:.168:0:.272:.534:.131,format=yuv420p"},
      {"sobel", "sobel"},
      {"lowpass", "fftfilt=dc_Y=0:weight_Y='squish((Y+X)/100-1)'"},
      {"posterize", "edgedetect=mode=colormix,format=yuv420p"}};
  for (const auto& [size, frameCount] : {std::pair{ivec2(640, 480), 96}, std::pair{ivec2(1920, 1080), 48}}) {
    const int frames = frameCount;  // a plain local: lambdas below capture it (clang cannot capture bindings)
    const std::string group = fmt::format("{}x{} H.264 end to end", size.x, size.y);
    const fs::path clip = dir / fmt::format("clip-{}.mp4", size.y);
    {
      video::Source pattern = video::Source::open(
          fmt::format("lavfi:testsrc2=size={}x{}:rate=24:duration={}", size.x, size.y, frames / 24));
      video::Sink sink(clip, {.codec = video::Codec::H264, .size = size, .frameRate = {24, 1},
                              .timeBase = pattern.info().timeBase, .preset = "ultrafast"});
      video::Frame f;
      while (pattern.read(f)) sink.write(f);
      sink.finish();
    }
    const std::string out = (dir / "out.mp4").string();
    const auto ffmpeg = [&](const std::string& filter) {
      return fmt::format("ffmpeg -nostdin -v error -y -i {} -vf \"{}\" {} -an {}", clip.string(), filter, encode, out);
    };
    const int rounds = 3;
    const auto fpsOf = [&](double seconds) { return seconds > 0 ? double(frames) / seconds : 0.0; };
    std::vector<double> nullRuns;
    for (int i = 0; i < rounds; ++i) nullRuns.push_back(commandSeconds(ffmpeg("null")));
    recorder.record({.group = group, .name = "ffmpeg null", .value = fpsOf(median(nullRuns)), .unit = "fps",
                     .note = fmt::format("decode + encode alone ({}, {} frames)", encode, frames)});
    for (const auto& [effect, filter] : effects) {
      const std::string post = fmt::format("{} -q post {} -o {} -e {} --preset veryfast --crf 18 --no-audio", glint,
                                           clip.string(), out, effect);
      std::vector<double> glintRuns, ffmpegRuns;
      commandSeconds(post);  // warm-up (the file in the page cache, both commands' libraries)
      commandSeconds(ffmpeg(filter));
      for (int i = 0; i < rounds; ++i) {
        glintRuns.push_back(commandSeconds(post));
        ffmpegRuns.push_back(commandSeconds(ffmpeg(filter)));
      }
      const std::string peer = "ffmpeg " + effect;
      recorder.record({.group = group, .name = peer, .value = fpsOf(median(ffmpegRuns)), .unit = "fps",
                       .note = "-vf " + filter});
      recorder.record({.group = group, .name = "glint post -e " + effect, .value = fpsOf(median(glintRuns)),
                       .unit = "fps", .ratioTo = peer,
                       .note = "the command, --backend auto (the CPU on a software GL renderer); ratio ≥ 1: glint faster"});
    }
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// A part that needs the FFmpeg module (the video files it makes and reads): without the
// module (a bare GPU machine's pack) its rows are dropped, one marked row says so, and the
// suite goes on (issue 37).
void withVideo(Recorder& recorder, const char* group, void (*part)(Recorder&)) {
  if (quick()) {  // the video rows take minutes: a quick run measures the GPU's rows only
    recorder.record({.group = group, .name = "(not measured)", .value = std::nan(""), .unit = "fps",
                     .note = "GLINT_BENCH_QUICK: the video rows take minutes"});
    return;
  }
  try {
    part(recorder);
  } catch (const Error& e) {
    recorder.record({.group = group, .name = "(not measured)", .value = std::nan(""), .unit = "fps",
                     .note = fmt::format("needs the video module: {}", e.what())});
  }
}

void runPost(Recorder& recorder) {
  runEffects(recorder);
  withVideo(recorder, "end to end", runAgainstFfmpeg);
  withVideo(recorder, "1080p H.264", runEndToEnd);
}

}  // namespace

/// The "post" suite (bench/bench.cpp lists it).
void runPostSuite(Recorder& r) { runPost(r); }

}  // namespace glint::bench
