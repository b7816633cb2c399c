#include "glint/post/job.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"
#include "glint/image/image.h"
#include "glint/image/srgb.h"
#include "glint/video/source.h"
#include "glint/core/options.h"
#include "glint/video/transcode.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>

namespace glint::post {

namespace {

/// The frame as glint post processes it: RGBA, its values sRGB-encoded (WWDC 2003 session 212's camera
/// values). U8 for 8- and 16-bit images (16-bit rounded). A float image (EXR, HDR: linear
/// light) stays F32 for the GPU's float chain, encoded without clamping so the result
/// decodes back to linear light (`floatChain`); for the CPU backend (8-bit frames) it is
/// encoded, clamped to 0..1 and rounded, with a warning.
Image toFrame(const Image& image, const std::string& name, bool floatChain, ToolRun& run) {
  Image rgba = image.channels() == 4 ? image : image.withChannels(4);
  if (rgba.type() == PixelType::F32) {
    if (floatChain) return srgbEncodedExtended(std::move(rgba));
    run.warn(fmt::format("{} holds linear float values: the CPU backend encodes them to 8-bit sRGB (clamped to 0..1) "
                         "before the effects (--backend gpu keeps them in float)", name));
    rgba = srgbEncoded(std::move(rgba));
  }
  return rgba.type() == PixelType::U8 ? rgba : rgba.converted(PixelType::U8);
}

/// Whether an image written to `output` (or stdout in `format`) holds float values: they are
/// then linear light, as EXR and Radiance HDR files are read.
bool floatImageOutput(const std::string& output, const std::string& format) {
  const std::string ext = lowerExtension(output == "-" ? "stdout." + format : output);
  return ext == ".exr" || ext == ".hdr";
}

/// The processed RGBA frame with the channels the output keeps: `asked` (--channels), else
/// the input's (RGB stays RGB, grey stays grey), except that a grey input whose effects
/// made colour (sepia) is written in colour, with a line that says so.
Image withOutputChannels(const Image& rgba, int inputChannels, int asked, const std::string& effects) {
  if (asked > 0) return rgba.withChannels(asked);
  int channels = inputChannels;
  if (channels <= 2) {
    bool grey = true;
    for (int y = 0; grey && y < rgba.height(); ++y)
      for (int x = 0; grey && x < rgba.width(); ++x) grey = rgba.at(x, y, 0) == rgba.at(x, y, 1) && rgba.at(x, y, 0) == rgba.at(x, y, 2);
    if (!grey) {
      channels += 2;
      log::info("post: the input is grey but {} gives colour: written as {}", effects, channels == 3 ? "RGB" : "RGBA");
    }
  }
  return rgba.withChannels(channels);
}

// The GPU, started (its context made) when the job first needs it.
class Gpu {
public:
  explicit Gpu(GpuBackend* backend, bool debug) : m_backend(backend), m_debug(debug) {}
  bool available() const { return m_backend != nullptr; }
  GpuBackend& backend() { return *m_backend; }
  /// Starts the backend (once) and returns the renderer's name.
  const std::string& start() {
    if (!m_started) {
      m_renderer = m_backend->start(m_debug);
      m_started = true;
    }
    return m_renderer;
  }
  /// Starts it and checks that frames of `size` fit its textures.
  void startFor(ivec2 size) {
    start();
    const int largest = m_backend->maxTextureSize();
    if (size.x > largest || size.y > largest) {
      fail(ErrorKind::Input, "the frames are {}x{}: larger than this GPU's largest texture ({}x{})", size.x, size.y,
           largest, largest);
    }
  }

private:
  GpuBackend* m_backend;
  bool m_debug;
  bool m_started = false;
  std::string m_renderer;
};

// Where the effects run. Auto picks the CPU at once when EGL has only software devices (or
// no GPU backend was given); otherwise it makes the GL context to read its renderer: kept
// for the GPU, and the CPU for a software renderer when the CPU has every effect of the chain.
Backend chooseBackend(const PostJob& job, Gpu& gpu, bool floatFrames = false) {
  if (job.backend == Backend::Gpu && !gpu.available())
    fail(ErrorKind::Usage, "--backend gpu: this program was built without glint post's GPU backend");
  if (job.backend != Backend::Auto) return job.backend;
  if (!gpu.available()) return Backend::Cpu;
  if (floatFrames) {  // the CPU backend works on 8-bit frames: a float image keeps its range on the GPU
    log::debug("post: a float image: the effects run on the GPU in float (the CPU backend is 8-bit)");
    return Backend::Gpu;
  }
  // Cheap first: when EGL has only software devices, no context is needed to know (a
  // context costs ~50 ms of a short video's run).
  if (gpu.backend().onlySoftwareDevices() && cpuMissing(job.effects).empty()) {
    log::debug("post: EGL lists only software devices (no GPU): the effects run on the CPU");
    return Backend::Cpu;
  }
  const std::string renderer = gpu.start();
  if (!isSoftwareRenderer(renderer)) return Backend::Gpu;
  if (const std::string missing = cpuMissing(job.effects); !missing.empty()) {
    log::info("post: {} is a software renderer, but {} has no CPU version: on the GPU", renderer, missing);
    return Backend::Gpu;
  }
  log::debug("post: {} is a software renderer: the effects run on the CPU", renderer);
  return Backend::Cpu;
}

// The CPU backend as transcode's middle stage: frames processed in place, on this thread
// (the effects spread over the cores themselves).
class CpuProcessor final : public video::FrameProcessor {
public:
  explicit CpuProcessor(CpuChain& chain) : m_chain(chain) {}
  void process(video::Frame&& frame, const Emit& emit) override {
    m_chain.run(frame);
    emit(std::move(frame));
  }
  void flush(const Emit&) override {}

private:
  CpuChain& m_chain;
};

}  // namespace

void checkJob(const PostJob& job, const ToolSettings& settings) {
  if (!job.parts.empty()) {
    if (job.output.empty()) fail(ErrorKind::Usage, "--concat needs -o OUTPUT");
    if (!job.effects.empty() || !job.input.empty() || !job.camera.empty() || !job.lavfi.empty()) {
      fail(ErrorKind::Usage, "--concat joins finished parts: no input or effects");
    }
  } else {
    const int sources = int(!job.input.empty()) + int(!job.camera.empty()) + int(!job.lavfi.empty());
    if (sources == 0) fail(ErrorKind::Usage, "post needs an input: a file, --camera DEVICE or --input lavfi:GRAPH");
    if (sources > 1) fail(ErrorKind::Usage, "post takes one input: a file, --camera or --input, not several");
    if (!job.lavfi.empty() && !job.lavfi.starts_with("lavfi:")) {
      fail(ErrorKind::Usage, "--input takes lavfi:GRAPH (files are given as the first argument), got '{}'", job.lavfi);
    }
    if (job.output.empty()) fail(ErrorKind::Usage, "post needs -o OUTPUT");
    const InputKind kind = inputKind(job);
    if (kind != InputKind::Camera && job.cameraSize) {
      fail(ErrorKind::Usage, "--size is for cameras (a file or lavfi graph has its own size)");
    }
    if (kind != InputKind::Camera && job.cameraRate) fail(ErrorKind::Usage, "--fps is for cameras");
    if (job.cameraRate && !(*job.cameraRate > 0.0)) fail(ErrorKind::Usage, "--fps must be positive, got {}", *job.cameraRate);
    if (job.frames && (job.frames->first < 0 || (job.frames->end >= 0 && job.frames->end <= job.frames->first))) {
      fail(ErrorKind::Usage, "--frames {}:{} selects no frames", job.frames->first, job.frames->end);
    }
    if (job.channels < 0 || job.channels > 4) fail(ErrorKind::Usage, "--channels must be 1 (grey), 2 (grey + alpha), 3 (RGB) or 4 (RGBA), got {}", job.channels);
    if (job.channels > 0 && !imageOutput(job)) fail(ErrorKind::Usage, "--channels is for image outputs (a video is RGB)");
    if (job.codec == video::Codec::H264) video::checkPreset(job.preset);
    if (job.crf < 0 || job.crf > 51) fail(ErrorKind::Usage, "--crf must be 0..51, got {}", job.crf);
    if (kind == InputKind::Image && !imageOutput(job)) {
      fail(ErrorKind::Usage, "'{}' is an image: write an image too (-o result.png), not '{}'", job.input, job.output);
    }
  }
  // No output may be an input or another output (by file identity), and all must be writable.
  std::vector<FileUse> inputs;
  if (inputKind(job) == InputKind::Image || inputKind(job) == InputKind::Video) inputs.push_back({job.input, "the input"});
  if (!job.camera.empty()) inputs.push_back({job.camera, "the camera"});
  for (const std::string& part : job.parts) inputs.push_back({part, "the part"});
  const std::string& json = settings.json;
  checkDistinctFiles(inputs, {{job.output, "-o"}, {json, "--json"}});
  if (!job.format.empty() && job.output != "-") fail(ErrorKind::Usage, "--format is for -o - (stdout); a file's format follows its extension");
  if (imageOutput(job)) checkImageOutput(job.output, job.format);
  else if (job.output != "-") checkWritable(job.output);
  if (!json.empty() && json != "-") checkWritable(json);
}

namespace {

PostStats runParts(const PostJob& job, ToolRun& run) {
  const std::vector<std::filesystem::path> parts(job.parts.begin(), job.parts.end());
  PostStats stats{.kind = InputKind::Parts, .output = job.output, .parts = job.parts};
  {
    auto timed = run.phase("concat");
    stats.framesWritten = video::concatenate(parts, job.output);
  }
  log::info("post: {} parts → {} ({} frames, packets copied: no re-encoding)", parts.size(), job.output,
            stats.framesWritten);
  return stats;
}

PostStats runImage(const PostJob& job, ToolRun& run, GpuBackend* gpu) {
  requireImageIo();
  Image input;
  {
    auto timed = run.phase("load");
    input = loadImage(job.input);
  }
  PostStats stats;
  const Image result = processImage(job, std::move(input), run, gpu, stats);
  {
    auto timed = run.phase("write");
    saveImage(result, job.output, job.format);
  }
  log::info("post: {} ({}x{}) → {}: {} ({})", job.input, stats.size.x, stats.size.y, job.output, stats.effects, stats.backend);
  return stats;
}

// A video in, an image out: one frame (the first of --frames), processed.
PostStats runStill(const PostJob& job, video::Source& source, Backend backend, ToolRun& run, Gpu& gpu) {
  requireImageIo();
  video::Frame frame;
  if (!source.read(frame)) fail(ErrorKind::Input, "{} has no frame to take a still from", source.info().name);
  Image result;
  std::string effects;
  if (backend == Backend::Cpu) {
    CpuChain chain(source.info().size, job.effects);
    result = chain.run(frame.image);
    effects = chain.describe();
  } else {
    result = gpu.backend().runImage(job.effects, frame.image, effects);
  }
  run.throwIfInterrupted();
  if (floatImageOutput(job.output, job.format)) result = srgbDecoded(result);  // a float file holds linear light
  saveImage(withOutputChannels(result, 3, job.channels, effects), job.output, job.format);  // video: RGB
  log::info("post: frame {} ({:.3f} s) of {} → {}", frame.index, frame.seconds, source.info().name, job.output);
  return {.kind = inputKind(job), .still = true, .input = source.info().name, .output = job.output,
          .size = source.info().size, .effects = effects, .backend = backendName(backend), .frame = frame.index,
          .framesRead = 1, .framesWritten = 1, .rotation = source.info().rotation,
          .rotationApplied = source.info().rotationApplied};
}

// Warnings about frames the source lost or damaged: said, not silent.
void warnAboutSource(const PostStats& stats, const video::Source& source, const std::string& name, ToolRun& run) {
  if (stats.droppedFrames > 0) {
    run.warn(fmt::format("{} live frame(s) dropped: the source delivered faster than glint could process", stats.droppedFrames));
  }
  // A file that ends before the frames its container announces (truncated, damaged). Frames
  // lost to corrupt packets are warned about already; one frame of slack for containers that
  // only know a rounded duration.
  // A container's own frame count (MP4) is compared as it is; one estimated from the
  // duration and the average rate (Matroska) is not, since a variable-rate file has fewer
  // frames than that and is whole: there the last frame must reach the duration.
  const video::SourceInfo& info = source.info();
  const double interval = info.frameRate.valid() ? 1.0 / info.frameRate.value() : 0.04;
  const bool toEnd = stats.framesExpected == info.frameCount - stats.firstFrame;
  const bool endsEarly = info.frameCountExact || (toEnd && info.durationSeconds > 0 && source.lastFrameSeconds() >= 0 &&
                                                  source.lastFrameSeconds() + 2.5 * interval < info.durationSeconds);
  if (!stats.partial() && stats.framesExpected > 0 && stats.framesRead + stats.corruptPackets + 1 < stats.framesExpected &&
      endsEarly) {
    run.warn(fmt::format("'{}' ended after {} of the {} frames its container announces (truncated or damaged?)", name,
                         stats.framesRead, stats.framesExpected));
  }
  if (stats.corruptPackets > 0) {
    run.recordWarning(fmt::format("{} corrupt packet(s) could not be decoded; those frames are missing", stats.corruptPackets));
  }
  // Damage the decoder concealed: the frames are there, some possibly wrong.
  const video::DecoderErrors errors = source.decoderErrors();
  if (errors.count > 0) {
    run.warn(fmt::format("'{}': the decoder reported {} error(s), the first '{}': some frames were damaged and "
                         "concealed by the decoder", name, errors.count, errors.first));
  }
}

/// The frames of [first, last) the container announces; −1 when it does not say.
std::int64_t expectedFrames(const video::SourceInfo& info, const video::SourceOptions& options) {
  if (info.frameCount < 0) return -1;
  const std::int64_t end = options.lastFrame >= 0 ? std::min(options.lastFrame, info.frameCount) : info.frameCount;
  return std::max<std::int64_t>(0, end - options.firstFrame);
}

/// "100:200" or "100:".
std::string rangeText(const FrameRange& range) {
  return range.end >= 0 ? fmt::format("{}:{}", range.first, range.end) : fmt::format("{}:", range.first);
}

/// "50 frames, 0..49", or "an unknown number of frames" when the container does not say.
std::string countOf(const video::SourceInfo& info) {
  if (info.frameCount <= 0) return "its container does not give its length";
  return fmt::format("it has {} frames, 0..{}", info.frameCount, info.frameCount - 1);
}

/// Where a video job's frames come from and how they are decoded (`backend`: the CPU's luma
/// effects take the decoder's YUV planes as they are and hand them to an H.264 encoder,
/// itself 4:2:0 (cpu.h); FFV1, lossless RGB, gets the exact RGB path).
video::SourceOptions sourceOptions(const PostJob& job, const ToolRun& run, Backend backend) {
  const InputKind kind = inputKind(job);
  video::SourceOptions options{.camera = kind == InputKind::Camera, .realtime = job.realtime,
                               .size = job.cameraSize.value_or(ivec2(0)), .frameRate = job.cameraRate.value_or(0.0),
                               .keepAudio = job.keepAudio, .threads = run.settings().threads};
  // A rotated video (a phone's portrait clip) keeps its rotation as the output's display
  // matrix where the container holds one; else (an image, a .mkv) its frames are turned.
  options.applyRotation = job.applyRotation || imageOutput(job) || !video::holdsDisplayMatrix(job.output, job.format);
  if (job.frames) {
    options.firstFrame = job.frames->first;
    options.lastFrame = job.frames->end;
  }
  options.yuv420 = backend == Backend::Cpu && !imageOutput(job) && job.codec == video::Codec::H264 && cpuWorksOnYuv(job.effects);
  return options;
}

/// Says what happens to a rotated input: turned upright, or its rotation kept on the output.
void sayRotation(const PostJob& job, const std::string& name, const video::SourceInfo& info) {
  if (info.rotationApplied && !job.applyRotation) {
    log::info("post: '{}' is shown turned {}° (its display matrix): its frames are turned upright, as {} cannot hold "
              "the rotation", name, info.rotation, imageOutput(job) ? "an image" : "a " + std::filesystem::path(job.output).extension().string() + " file");
  } else if (info.rotation != 0 && !info.rotationApplied) {
    log::info("post: '{}' is shown turned {}° (its display matrix): kept on '{}' (--apply-rotation turns the frames "
              "upright instead)", name, info.rotation, job.output);
  }
}

/// The three-stage pipeline with a progress bar (frames per second as its detail).
video::TranscodeStats transcodeWithProgress(video::Source& source, video::Sink& sink, video::FrameProcessor& processor,
                                            std::int64_t total, ToolRun& run) {
  Progress progress("post", std::uint64_t(std::max<std::int64_t>(total, 0)));
  const auto start = std::chrono::steady_clock::now();
  auto lastDetail = start;
  const video::TranscodeStats t = video::transcode(
      source, sink, processor,
      {.cancel = &run.cancelFlag(), .progress = [&](std::int64_t done) {
         progress.advance();
         const auto now = std::chrono::steady_clock::now();
         if (now - lastDetail > std::chrono::milliseconds(250)) {
           lastDetail = now;
           progress.setDetail(fmt::format("{:.1f} fps", double(done) / std::chrono::duration<double>(now - start).count()));
         }
       }});
  progress.finish();
  run.addSeconds("read", t.readSeconds);
  run.addSeconds("process", t.processSeconds);
  run.addSeconds("write", t.writeSeconds);
  return t;
}

/// A video job's fields once the pipeline has run.
PostStats videoStats(const PostJob& job, const std::string& name, const video::Source& source,
                     const video::SourceOptions& options, const video::Sink& sink, const video::TranscodeStats& t,
                     const std::string& described, Backend backend, std::int64_t expected) {
  const video::SourceInfo& info = source.info();
  return PostStats{.kind = inputKind(job),
                   .input = name,
                   .output = job.output,
                   .size = info.size,
                   .frameRate = info.frameRate.value(),
                   .codec = video::codecName(job.codec),
                   .effects = described,
                   .backend = backendName(backend),
                   .live = info.live,
                   .firstFrame = options.firstFrame,
                   .framesRead = t.framesRead,
                   .framesWritten = t.framesWritten,
                   .framesExpected = expected,
                   .droppedFrames = t.droppedFrames,
                   .corruptPackets = source.corruptPackets(),
                   .decoderErrors = source.decoderErrors().count,
                   .audio = !info.hasAudio       ? "none"
                            : !job.keepAudio     ? "dropped (--no-audio)"
                            : sink.audioNote().empty() ? "copied"
                                                       : "dropped",
                   .audioPackets = t.audioPackets,
                   .rotation = info.rotation,
                   .rotationApplied = info.rotationApplied,
                   .fps = t.seconds > 0 ? double(t.framesWritten) / t.seconds : 0.0,
                   .seconds = t.seconds,
                   .interrupted = t.interrupted,
                   .inputError = t.inputError};
}

/// A run that wrote no frame is an error (an existing output left as it was); a --frames
/// range that ran past the end is a warning.
void checkWritten(const PostJob& job, const std::string& name, const video::SourceInfo& info,
                  const video::TranscodeStats& t, bool partial, ToolRun& run) {
  if (!t.finished) {  // no frame: nothing written, an existing file left as it was
    const std::string kept = std::filesystem::exists(job.output) ? fmt::format("'{}' was left as it was", job.output)
                                                                 : fmt::format("'{}' was not written", job.output);
    if (t.interrupted) fail(ErrorKind::Interrupted, "post: interrupted before the first frame; {}", kept);
    if (t.inputError) fail(ErrorKind::Input, "{} (before the first frame); {}", *t.inputError, kept);
    if (job.frames) {
      fail(ErrorKind::Input, "--frames {} selects no frame of '{}' ({}); {}", rangeText(*job.frames), name,
           countOf(info), kept);
    }
    fail(ErrorKind::Input, "'{}' has no video frame to process; {}", name, kept);
  }
  if (job.frames && job.frames->end >= 0 && !partial && t.framesWritten < job.frames->end - job.frames->first) {
    run.warn(fmt::format("--frames {} runs past the end of '{}' ({}): {} frame(s) written ({}..{})",
                         rangeText(*job.frames), name, countOf(info), t.framesWritten, job.frames->first,
                         job.frames->first + t.framesWritten - 1));
  }
}

PostStats runVideo(const PostJob& job, ToolRun& run, Gpu& gpu) {
  const InputKind kind = inputKind(job);
  const std::string& name = kind == InputKind::Camera ? job.camera : !job.lavfi.empty() ? job.lavfi : job.input;
  const bool still = imageOutput(job);
  const Backend backend = chooseBackend(job, gpu);
  const video::SourceOptions options = sourceOptions(job, run, backend);

  std::optional<ToolRun::Phase> opening(std::in_place, run, "open");
  video::Source source = video::Source::open(name, options);
  const video::SourceInfo& info = source.info();
  sayRotation(job, name, info);
  if (job.frames && info.frameCount > 0 && job.frames->first > info.frameCount) {  // plainly past the end
    fail(ErrorKind::Input, "--frames {} selects no frame of '{}' ({})", rangeText(*job.frames), name, countOf(info));
  }
  run.checkMemory(estimatePeakMemoryMiB(info.size, still), fmt::format("processing {}x{} video", info.size.x, info.size.y));
  if (backend == Backend::Gpu) gpu.startFor(info.size);
  if (still) return runStill(job, source, backend, run, gpu);
  std::optional<CpuChain> cpuChain;
  std::unique_ptr<video::FrameProcessor> gpuProcessor;
  std::string described;
  if (backend == Backend::Cpu) {
    cpuChain.emplace(info.size, job.effects);
    described = cpuChain->describe();
  } else {
    gpuProcessor = gpu.backend().videoProcessor(info.size, job.effects, described);
  }
  video::Sink sink(job.output, {.codec = job.codec, .size = info.size, .frameRate = info.frameRate,
                                .timeBase = info.timeBase, .crf = job.crf, .preset = job.preset,
                                .threads = run.settings().threads, .noReordering = job.frames.has_value(),
                                .audio = job.keepAudio ? source.audio() : nullptr, .format = job.format,
                                .displayMatrix = info.displayMatrix});
  opening.reset();
  if (!sink.audioNote().empty()) run.warn(sink.audioNote());
  log::info("post: {} ({}x{}, {:.3g} fps, {}{}) → {} ({}): {} on the {}{}", name, info.size.x, info.size.y,
            info.frameRate.value(), info.codec, info.live ? ", live" : "", job.output, video::codecName(job.codec),
            described, backendName(backend), options.yuv420 ? " (in YUV)" : "");

  // The frames the container announces for the range (−1: it does not say).
  const std::int64_t expected = expectedFrames(info, options);
  std::int64_t total = expected >= 0 ? expected : 0;
  if (expected < 0 && options.lastFrame >= 0) total = options.lastFrame - options.firstFrame;
  std::optional<CpuProcessor> cpuProcessor;
  if (cpuChain) cpuProcessor.emplace(*cpuChain);
  video::FrameProcessor& processor = cpuChain ? static_cast<video::FrameProcessor&>(*cpuProcessor) : *gpuProcessor;
  const video::TranscodeStats t = transcodeWithProgress(source, sink, processor, total, run);
  const PostStats stats = videoStats(job, name, source, options, sink, t, described, backend, expected);
  checkWritten(job, name, info, t, stats.partial(), run);
  warnAboutSource(stats, source, name, run);
  return stats;
}

}  // namespace

bool imageOutput(const PostJob& job) {
  if (job.output == "-") return job.format.empty() || video::isImagePath("stdout." + job.format);
  return video::isImagePath(job.output);
}

InputKind inputKind(const PostJob& job) {
  if (!job.parts.empty()) return InputKind::Parts;
  if (!job.camera.empty()) return InputKind::Camera;
  if (!job.lavfi.empty() || job.input.starts_with("lavfi:")) return InputKind::Lavfi;
  if (job.input == "-") return imageOutput(job) ? InputKind::Image : InputKind::Video;  // stdin: see job.h
  return video::isImagePath(job.input) ? InputKind::Image : InputKind::Video;
}

double estimatePeakMemoryMiB(ivec2 size, bool singleFrame) {
  return 150.0 + double(size.x) * double(size.y) * (singleFrame ? 45.0 : 280.0) / (1 << 20);
}

Image processImage(const PostJob& job, Image input, ToolRun& run, GpuBackend* gpuBackend, PostStats& stats) {
  Gpu gpu(gpuBackend, job.glDebug);
  const int inputChannels = input.channels();
  const bool linear = input.type() == PixelType::F32;  // EXR, HDR: linear light
  const ivec2 size(input.width(), input.height());
  run.checkMemory(estimatePeakMemoryMiB(size, true) * (linear ? 4.0 : 1.0),
                  fmt::format("processing a {}x{} image", size.x, size.y));
  const Backend backend = chooseBackend(job, gpu, linear);
  if (backend == Backend::Gpu) gpu.startFor(size);
  const Image frame = toFrame(input, job.input, backend == Backend::Gpu, run);
  input = Image();
  stats = PostStats{.kind = InputKind::Image, .input = job.input, .output = job.output, .size = size, .framesRead = 1,
                    .framesWritten = 1};
  stats.backend = backendName(backend);
  Image result;
  {
    auto timed = run.phase("process");
    if (backend == Backend::Cpu) {
      CpuChain chain(size, job.effects);
      result = chain.run(frame);
      stats.effects = chain.describe();
    } else {
      result = gpu.backend().runImage(job.effects, frame, stats.effects);
    }
  }
  run.throwIfInterrupted();
  // A float file holds linear light, as the input was read: the encoded result decoded.
  if (!job.output.empty() && floatImageOutput(job.output, job.format)) result = srgbDecoded(result);
  return withOutputChannels(result, inputChannels, job.channels, stats.effects);
}

PostStats runJob(const PostJob& job, ToolRun& run, GpuBackend* gpuBackend) {
  // Usage errors first: fail in a millisecond, before opening anything.
  checkJob(job, run.settings());
  const InputKind kind = inputKind(job);
  if (kind == InputKind::Parts) return runParts(job, run);
  if (kind == InputKind::Image || imageOutput(job)) preloadImageIo();  // while the GPU starts
  if (kind == InputKind::Image) return runImage(job, run, gpuBackend);
  Gpu gpu(gpuBackend, job.glDebug);
  return runVideo(job, run, gpu);
}

}  // namespace glint::post
