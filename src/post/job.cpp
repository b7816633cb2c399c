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

#include <CLI/CLI.hpp>
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

PostStats runVideo(const PostJob& job, ToolRun& run, Gpu& gpu) {
  const InputKind kind = inputKind(job);
  const std::string& name = kind == InputKind::Camera ? job.camera : !job.lavfi.empty() ? job.lavfi : job.input;
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
  const bool still = imageOutput(job);
  const Backend backend = chooseBackend(job, gpu);
  // The CPU's luma effects take the decoder's YUV planes as they are and hand them to an
  // H.264 encoder, itself 4:2:0 (cpu.h); FFV1 (lossless RGB) gets the exact RGB path.
  options.yuv420 = backend == Backend::Cpu && !still && job.codec == video::Codec::H264 && cpuWorksOnYuv(job.effects);

  std::optional<ToolRun::Phase> opening(std::in_place, run, "open");
  video::Source source = video::Source::open(name, options);
  const video::SourceInfo& info = source.info();
  if (info.rotationApplied && !job.applyRotation) {
    log::info("post: '{}' is shown turned {}° (its display matrix): its frames are turned upright, as {} cannot hold "
              "the rotation", name, info.rotation, imageOutput(job) ? "an image" : "a " + std::filesystem::path(job.output).extension().string() + " file");
  } else if (info.rotation != 0 && !info.rotationApplied) {
    log::info("post: '{}' is shown turned {}° (its display matrix): kept on '{}' (--apply-rotation turns the frames "
              "upright instead)", name, info.rotation, job.output);
  }
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
  Progress progress("post", std::uint64_t(std::max<std::int64_t>(total, 0)));
  const auto start = std::chrono::steady_clock::now();
  auto lastDetail = start;
  std::optional<CpuProcessor> cpuProcessor;
  if (cpuChain) cpuProcessor.emplace(*cpuChain);
  video::FrameProcessor& processor = cpuChain ? static_cast<video::FrameProcessor&>(*cpuProcessor) : *gpuProcessor;
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

  PostStats stats{.kind = kind,
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
  if (job.frames && job.frames->end >= 0 && !stats.partial() &&
      t.framesWritten < job.frames->end - job.frames->first) {
    run.warn(fmt::format("--frames {} runs past the end of '{}' ({}): {} frame(s) written ({}..{})",
                         rangeText(*job.frames), name, countOf(info), t.framesWritten, job.frames->first,
                         job.frames->first + t.framesWritten - 1));
  }
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

nlohmann::ordered_json PostStats::toJson() const {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  if (kind == InputKind::Parts) {
    j["parts"] = parts;
    j["output"] = output;
    j["frames"] = framesWritten;
    return j;
  }
  if (kind == InputKind::Image) {
    j["effects"] = effects;
    j["input"] = input;
    j["output"] = output;
    j["width"] = size.x;
    j["height"] = size.y;
    j["frames"] = framesWritten;
    return j;
  }
  if (still) {
    j["input"] = input;
    j["output"] = output;
    j["frame"] = frame;
    j["effects"] = effects;
    j["rotation"] = rotation;
    j["rotation_applied"] = rotationApplied;
    return j;
  }
  j["input"] = input;
  j["output"] = output;
  j["width"] = size.x;
  j["height"] = size.y;
  j["frame_rate"] = frameRate;
  j["codec"] = codec;
  j["effects"] = effects;
  j["live"] = live;
  j["first_frame"] = firstFrame;
  j["frames_read"] = framesRead;
  j["frames_written"] = framesWritten;
  j["frames_expected"] = framesExpected;
  j["dropped_frames"] = droppedFrames;
  j["corrupt_packets"] = corruptPackets;
  j["decoder_errors"] = decoderErrors;
  j["audio"] = audio;
  j["audio_packets"] = audioPackets;
  j["rotation"] = rotation;
  j["rotation_applied"] = rotationApplied;
  j["fps"] = fps;
  j["partial"] = partial();
  j["interrupted"] = interrupted;
  if (inputError) j["input_error"] = *inputError;
  return j;
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

namespace {
/// Where a partial video goes when the output already exists: beside it, never over it
/// ("graded.mkv" → "graded.partial.mkv", or the first of "graded.partial-2.mkv", ... that is free).
std::filesystem::path partialName(const std::filesystem::path& output) {
  for (int n = 1;; ++n) {
    const std::filesystem::path candidate =
        output.parent_path() / fitFileName(output.parent_path(), output.stem().string(),
                                           ".partial" + (n == 1 ? std::string() : fmt::format("-{}", n)) + output.extension().string());
    std::error_code ec;
    if (!std::filesystem::exists(candidate, ec)) return candidate;
  }
}
}  // namespace

int finishJob(const PostStats& stats, ToolRun& run) {
  // A partial video (Ctrl-C, an input that broke off) never replaces a file that was there:
  // a complete video is worth more than a part of one. The part goes beside it.
  std::string output = stats.output;
  bool keptExisting = false;
  std::error_code ec;
  if (stats.partial() && output != "-" && std::filesystem::exists(output, ec) && run.outputs().staged(output)) {
    const std::filesystem::path beside = partialName(output);
    run.outputs().redirect(output, beside);
    output = beside.string();
    keptExisting = true;
  }
  run.report().update(stats.toJson());
  if (keptExisting) run.report()["output"] = output;
  run.finish();
  const std::string kept = keptExisting ? fmt::format("'{}' was left as it was; ", stats.output) : "";
  if (stats.inputError) {
    fail(ErrorKind::Input, "{}; {}'{}' holds the {} frame(s) before it (a complete, playable video)", *stats.inputError,
         kept, output, stats.framesWritten);
  }
  if (stats.interrupted) {
    log::warn("post: interrupted after {} frame(s): {}'{}' is a complete, playable partial video", stats.framesWritten,
              kept, output);
    return exitCode(ErrorKind::Interrupted);
  }
  if (stats.kind != InputKind::Image && stats.kind != InputKind::Parts && !stats.still) {
    log::info("post: {} frame(s) in {:.2f} s ({:.1f} fps){}", stats.framesWritten, stats.seconds, stats.fps,
              stats.droppedFrames ? fmt::format(", {} dropped", stats.droppedFrames) : "");
  }
  return 0;
}

// ---------------------------------------------------------------------------- options

namespace {
constexpr const char* kFooter = R"(Examples:
  glint post photo.jpg -o sepia.png -e sepia
  glint post street.png -o npr.png -e posterize --set size=4
  glint post clip.mp4 -o clip-edges.mp4 -e kuwahara -e edges
  glint post clip.mp4 -o part2.mkv --codec ffv1 --frames 250:500 -e sepia:i=0.25
  glint post clip.mp4 -o sepia.mp4 -e sepia --backend cpu
  glint post --concat part1.mkv part2.mkv -o whole.mkv
  glint post --camera /dev/video0 --size 640x480 -o live.mp4 -e sobel
  glint post --input lavfi:testsrc2=size=1280x720:duration=5 -o test.mp4 -e spectrum
  glint post - -o - -e sobel < photo.png > edges.png
  ffmpeg -i clip.mp4 -f nut - | glint post - -o - --format nut -e sepia | ffplay -

Inputs: an image (.png .jpg .tga .tif .exr .hdr .bmp .webp, through OpenImageIO), any video
file FFmpeg reads, a V4L2 camera (--camera), or a lavfi filter graph (--input lavfi:GRAPH, or
as IN). Frames are processed as 8-bit RGB (sRGB-encoded values, like WWDC 2003 session 212's camera); a
float image (EXR, HDR: linear light) is processed in float on the GPU and a float output
holds linear values again. A video's rotation (a phone's display matrix) is kept on the
output and named in the report; --apply-rotation turns the frames upright instead.
Outputs: an image for an image (for a video: its first frame, or the first of --frames);
a video for a video: H.264 (--crf, --preset; .mp4 .mkv .mov)
or FFV1, lossless (.mkv .avi .nut). Audio is copied when the output container holds its
codec, else dropped with a warning. Timestamps are kept: parts made with --frames join
losslessly with --concat (FFV1 parts at any frame; H.264 parts are written without B-frames).

Frames are decoded, processed on the GPU (pixel buffer objects, a few frames in flight) and
encoded on three overlapped threads. --backend auto (the default) runs the effects on the CPU
instead (threaded, FFTW, OpenCV) when the GL renderer is a software one (llvmpipe: no GPU),
as --backend cpu always does (every effect has a CPU version); --backend gpu keeps OpenGL. On
the CPU, sepia, sobel and the FFT filters (one effect) work on a video's YUV planes directly,
skipping the RGB round trip; glint -v post says which backend ran. No frame of a file is ever dropped; a live source
(camera, --realtime) drops what the GPU cannot keep up with and the report counts it.

Exit status: 0 done, 2 bad option or effect, 3 unreadable input (or an input that broke off:
the video written so far is complete), 4 output not writable (a full disk: "no space left on
device"), 5 no OpenGL 4.5, 6 out of memory, 130 interrupted (Ctrl-C: a video is finished and
playable up to the last frame processed, reported as partial; when -o already existed it is
left as it was and the partial video is written beside it, OUT.partial.EXT; an image is not
written).)";
}  // namespace

void addOptions(CLI::App& cmd, PostArgs& a) {
  cmd.add_option("file", a.input, "Image or video file to read (or lavfi:GRAPH; '-': stdin, an image when the "
                                  "output is one, else a video stream)");
  cmd.add_option("-o,--output", a.output, "Image or video to write; format from the extension ('-': stdout, see --format)");
  cmd.add_option("--format", a.format, "The format of -o - (stdout): an image (png, the default; jpg, tga, tif, exr) "
                                       "or a video container that streams (mkv, nut, ts)");
  cmd.add_option("-e,--effect", a.effects, "An effect, in chain order: NAME or NAME:param=value,... (list below)");
  cmd.add_option("--set", a.settings, "param=value (every effect that has it) or effect.param=value");
  cmd.add_option("--camera", a.camera, "Read a V4L2 camera, e.g. /dev/video0 (a live source)");
  cmd.add_option("--input", a.lavfi, "An FFmpeg source: lavfi:GRAPH, e.g. lavfi:testsrc2=size=1280x720:duration=5");
  cmd.add_option("--size", a.size, "Camera: the size to ask for, WIDTHxHEIGHT (WWDC 2003 session 212's camera: 640x480)");
  cmd.add_option("--fps", a.rate, "Camera: the frame rate to ask for");
  cmd.add_flag("--realtime", a.realtime, "Pace a file or lavfi source at its frame rate and treat it as live "
                                         "(frames the GPU cannot keep up with are dropped and counted)");
  cmd.add_option("--backend", a.backend, "Where the effects run: auto (the CPU on a software GL renderer such as "
                 "llvmpipe, else the GPU), gpu (OpenGL) or cpu (threads, FFTW, OpenCV)")->capture_default_str();
  cmd.add_option("--codec", a.codec, "h264 (libx264, yuv420p) or ffv1 (lossless RGB)")->capture_default_str();
  cmd.add_option("--crf", a.crf, "H.264 quality: 0 (lossless) .. 51; 18 is visually lossless")->capture_default_str();
  cmd.add_option("--preset", a.preset, "H.264 speed/size trade-off: ultrafast .. placebo")->capture_default_str();
  cmd.add_option("--frames", a.frames, "Only frames FIRST:END (END excluded; 250: = to the end): split a long video "
                                       "over machines, join the parts with --concat");
  cmd.add_option("--concat", a.concat, "Join parts made with --frames (in order) into -o, copying packets");
  cmd.add_flag("--no-audio", a.noAudio, "Do not copy the input's audio");
  cmd.add_flag("--apply-rotation", a.applyRotation, "A rotated video (a phone's portrait clip): turn its frames upright "
               "instead of keeping its display matrix on the output (done anyway for an image or a container other "
               "than MP4/MOV)");
  cmd.add_option("--channels", a.channels, "Image output: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA (default: the "
                                           "input's; colour when an effect colours a grey input)");
  cmd.add_flag("--effects", a.listEffects, "List the effects and their parameters, and exit");
}

std::string helpFooter() { return std::string(kFooter) + "\n\n" + effectHelp(); }

PostJob makeJob(const PostArgs& a, bool glDebug) {
  PostJob job{.input = a.input, .camera = a.camera, .lavfi = a.lavfi, .parts = a.concat, .output = a.output,
              .crf = a.crf, .preset = a.preset, .realtime = a.realtime, .keepAudio = !a.noAudio,
              .applyRotation = a.applyRotation, .channels = a.channels, .glDebug = glDebug};
  job.format = a.format;
  job.effects = parseEffects(a.effects, a.settings);
  job.codec = video::parseCodec(a.codec);
  job.backend = parseBackend(a.backend);
  if (!a.frames.empty()) job.frames = parseFrameRange(a.frames, "--frames");
  if (!a.size.empty()) job.cameraSize = parseSize(a.size);
  if (!a.rate.empty()) job.cameraRate = parseFloat(a.rate, "--fps");
  return job;
}

std::vector<std::string> arguments(const PostJob& job) {
  std::vector<std::string> argv;
  if (!job.parts.empty()) {
    argv.push_back("--concat");
    argv.insert(argv.end(), job.parts.begin(), job.parts.end());
  }
  if (!job.input.empty()) argv.push_back(job.input);
  if (!job.camera.empty()) argv.insert(argv.end(), {"--camera", job.camera});
  if (!job.lavfi.empty()) argv.insert(argv.end(), {"--input", job.lavfi});
  argv.insert(argv.end(), {"-o", job.output});
  if (!job.format.empty()) argv.insert(argv.end(), {"--format", job.format});
  for (const Effect& e : job.effects) argv.insert(argv.end(), {"-e", e.spec()});
  if (job.parts.empty()) {
    argv.insert(argv.end(), {"--codec", video::codecName(job.codec)});
    if (job.codec == video::Codec::H264) argv.insert(argv.end(), {"--crf", std::to_string(job.crf), "--preset", job.preset});
    argv.insert(argv.end(), {"--backend", backendName(job.backend)});
  }
  if (job.frames) {
    argv.insert(argv.end(), {"--frames", job.frames->end >= 0 ? fmt::format("{}:{}", job.frames->first, job.frames->end)
                                                              : fmt::format("{}:", job.frames->first)});
  }
  if (job.cameraSize) argv.insert(argv.end(), {"--size", fmt::format("{}x{}", job.cameraSize->x, job.cameraSize->y)});
  if (job.cameraRate) argv.insert(argv.end(), {"--fps", fmt::format("{}", *job.cameraRate)});
  if (job.realtime) argv.push_back("--realtime");
  if (!job.keepAudio) argv.push_back("--no-audio");
  if (job.applyRotation) argv.push_back("--apply-rotation");
  if (job.channels > 0) argv.insert(argv.end(), {"--channels", std::to_string(job.channels)});
  return argv;
}

farm::Plan farmPlan(const PostJob& given, const ToolSettings& settings, const farm::Split& split) {
  if (!given.camera.empty() || !given.lavfi.empty() || given.input.starts_with("lavfi:"))
    fail(ErrorKind::Usage, "farm post: a camera or lavfi source cannot be split over machines; farm a video file");
  if (!given.parts.empty()) fail(ErrorKind::Usage, "farm post: --concat is what the farm's join runs; farm a video file");
  if (given.realtime) fail(ErrorKind::Usage, "farm post: --realtime cannot be split over machines; farm a video file");
  if (given.input.empty() || given.input == "-") fail(ErrorKind::Usage, "farm post: give a video file every node can read");
  if (given.output.empty() || given.output == "-") fail(ErrorKind::Usage, "farm post: give -o, a video file");
  checkJob(given, settings);  // the command's own checks, before anything is submitted
  if (inputKind(given) == InputKind::Image) fail(ErrorKind::Usage, "farm post: '{}' is an image; farm a video", given.input);
  if (imageOutput(given)) fail(ErrorKind::Usage, "farm post: -o '{}' is an image; farm a video into a video", given.output);
  PostJob job = given;
  job.input = farm::absolutePath(job.input);
  job.output = farm::absolutePath(job.output);
  const video::FrameIndex index = video::indexFrames(job.input);
  std::int64_t first = job.frames ? job.frames->first : 0;
  std::int64_t end = job.frames ? job.frames->end : -1;
  if (end < 0 || end > index.frameCount) end = index.frameCount;
  if (first >= end)
    fail(ErrorKind::Usage, "farm post: frames {}:{} of '{}' ({} frames) select none", first, end, given.input, index.frameCount);
  const auto ranges = farm::splitAtKeyframes(index.keyframes, first, end, split.pieces);
  if (int(ranges.size()) < split.pieces)
    log::warn("farm post: '{}' has keyframes for only {} chunk{} of frames {}:{} (asked for {})", given.input,
              ranges.size(), ranges.size() == 1 ? "" : "s", first, end, split.pieces);
  farm::Plan plan{.tool = "post"};
  {
    const video::Source source = video::Source::open(job.input);
    plan.memoryMiB = farm::taskMemoryMiB(split, estimatePeakMemoryMiB(source.info().size, false));
  }
  plan.title = fmt::format("{} → {}", std::filesystem::path(job.input).filename().string(),
                           std::filesystem::path(job.output).filename().string());
  plan.outputs = {job.output};
  const std::vector<std::string> limits = farm::pieceSettings(settings, split, plan.memoryMiB);
  const std::string extension = std::filesystem::path(job.output).extension().string();
  for (const auto& [a, b] : ranges) {
    PostJob piece = job;
    piece.output = farm::kPieceOutput;
    piece.frames = FrameRange{a, b};
    farm::Piece p{.label = fmt::format("frames {}:{}", a, b), .command = {"post"}, .extension = extension};
    const auto args = arguments(piece);
    p.command.insert(p.command.end(), args.begin(), args.end());
    p.command.insert(p.command.end(), limits.begin(), limits.end());
    p.inputs = {job.input};
    plan.pieces.push_back(std::move(p));
  }
  plan.join = {"post", "--concat", farm::kAllPieceOutputs, "-o", job.output};
  if (settings.quiet) plan.join.push_back("-q");
  if (!settings.json.empty()) {
    plan.join.insert(plan.join.end(), {"--json", farm::absolutePath(settings.json)});
    if (settings.json != "-") plan.outputs.push_back(farm::absolutePath(settings.json));
  }
  return plan;
}

}  // namespace glint::post
