// glint post IN -o OUT -e EFFECT... — seed 001's post-processing on an image, every frame of
// a video, a camera or an FFmpeg lavfi source. Thin: options → video::Source/Sink and a
// render::post::FrameStream, joined by video::transcode; the report.
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"
#include "glint/gl/context.h"
#include "glint/image/image.h"
#include "glint/render/post/chain.h"
#include "glint/video/sink.h"
#include "glint/video/source.h"
#include "glint/video/transcode.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>

namespace glint::app {

namespace {

struct PostArgs {
  std::string input, output, camera, lavfi, codec = "h264", preset = "medium", frames, size, rate;
  std::vector<std::string> effects, settings, concat;
  int crf = 18;
  bool realtime = false, noAudio = false, listEffects = false;
  ToolSettings tool;
};

/// "a:b", "a:" or ":b" → [first, last) (last −1 = to the end).
std::pair<std::int64_t, std::int64_t> parseFrames(const std::string& text) {
  const auto colon = text.find(':');
  const auto number = [&](const std::string& s, std::int64_t empty) -> std::int64_t {
    if (s.empty()) return empty;
    std::size_t used = 0;
    long long v = -1;
    try {
      v = std::stoll(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || v < 0) fail(ErrorKind::Usage, "--frames must be FIRST:END (frame numbers, END excluded), got '{}'", text);
    return v;
  };
  if (colon == std::string::npos) fail(ErrorKind::Usage, "--frames must be FIRST:END (e.g. 0:250 or 250:), got '{}'", text);
  const std::int64_t first = number(text.substr(0, colon), 0), last = number(text.substr(colon + 1), -1);
  if (last >= 0 && last <= first) fail(ErrorKind::Usage, "--frames {} selects no frames", text);
  return {first, last};
}

/// The frame as glint post processes it: U8 RGBA. 16-bit images are rounded; float images
/// (EXR, HDR) hold linear light and are sRGB-encoded, clamped, with a warning.
Image toFrame(const Image& image, const std::string& name, ToolRun& run) {
  Image rgba = image.channels() == 4 ? image : image.withChannels(4);
  if (rgba.type() == PixelType::F32) {
    run.warn(fmt::format("{} holds linear float values: encoded to 8-bit sRGB (clamped to 0..1) before the effects", name));
    for (int y = 0; y < rgba.height(); ++y)
      for (int x = 0; x < rgba.width(); ++x)
        for (int c = 0; c < 3; ++c) {
          const float v = std::clamp(rgba.at(x, y, c), 0.0f, 1.0f);
          rgba.set(x, y, c, v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f);
        }
  }
  return rgba.type() == PixelType::U8 ? rgba : rgba.converted(PixelType::U8);
}

std::unique_ptr<gl::HeadlessContext> makeContext(const GlobalOptions& global, ivec2 size) {
  auto context = gl::HeadlessContext::create({.profile = gl::Profile::Core, .debug = global.glDebug});
  const int largest = gl::queryContextInfo().maxTextureSize;
  if (size.x > largest || size.y > largest) {
    fail(ErrorKind::Input, "the frames are {}x{}: larger than this GPU's largest texture ({}x{})", size.x, size.y,
         largest, largest);
  }
  return context;
}

constexpr const char* kFooter = R"(Examples:
  glint post photo.jpg -o sepia.png -e sepia
  glint post street.png -o npr.png -e posterize --set size=4
  glint post clip.mp4 -o clip-edges.mp4 -e kuwahara -e edges
  glint post clip.mp4 -o part2.mkv --codec ffv1 --frames 250:500 -e sepia:i=0.25
  glint post --concat part1.mkv part2.mkv -o whole.mkv
  glint post --camera /dev/video0 --size 640x480 -o live.mp4 -e sobel
  glint post --input lavfi:testsrc2=size=1280x720:duration=5 -o test.mp4 -e spectrum

Inputs: an image (.png .jpg .tga .tif .exr .hdr .bmp .webp, through OpenImageIO), any video
file FFmpeg reads, a V4L2 camera (--camera), or a lavfi filter graph (--input lavfi:GRAPH, or
as IN). Frames are processed as 8-bit RGB (sRGB-encoded values, like the seed's camera).
Outputs: an image for an image (for a video: its first frame, or the first of --frames);
a video for a video: H.264 (--crf, --preset; .mp4 .mkv .mov)
or FFV1, lossless (.mkv .avi .nut). Audio is copied when the output container holds its
codec, else dropped with a warning. Timestamps are kept: parts made with --frames join
losslessly with --concat (FFV1 parts at any frame; H.264 parts are written without B-frames).

Frames are decoded, processed on the GPU (pixel buffer objects, a few frames in flight) and
encoded on three overlapped threads. No frame of a file is ever dropped; a live source
(camera, --realtime) drops what the GPU cannot keep up with and the report counts it.

Exit status: 0 done, 2 bad option or effect, 3 unreadable input (or an input that broke off:
the video written so far is complete), 4 output not writable, 5 no OpenGL 4.5,
130 interrupted (Ctrl-C: a video is finished and playable up to the last frame processed,
reported as partial; an image is not written).)";

int runConcat(const PostArgs& a, ToolRun& run) {
  if (a.output.empty()) fail(ErrorKind::Usage, "--concat needs -o OUTPUT");
  if (!a.effects.empty() || !a.input.empty()) fail(ErrorKind::Usage, "--concat joins finished parts: no input or effects");
  checkWritable(a.output);
  std::vector<std::filesystem::path> parts(a.concat.begin(), a.concat.end());
  std::int64_t frames = 0;
  {
    auto timed = run.phase("concat");
    frames = video::concatenate(parts, a.output);
  }
  log::info("post: {} parts → {} ({} frames, packets copied: no re-encoding)", parts.size(), a.output, frames);
  run.report()["parts"] = a.concat;
  run.report()["output"] = a.output;
  run.report()["frames"] = frames;
  run.finish();
  return 0;
}

int runImage(const PostArgs& a, const std::vector<render::post::Effect>& effects, ToolRun& run,
             const GlobalOptions& global) {
  if (!video::isImagePath(a.output)) {
    fail(ErrorKind::Usage, "'{}' is an image: write an image too (-o result.png), not '{}'", a.input, a.output);
  }
  requireImageIo();
  Image frame;
  {
    auto timed = run.phase("load");
    frame = toFrame(loadImage(a.input), a.input, run);
  }
  const ivec2 size(frame.width(), frame.height());
  run.checkMemory(150.0 + double(size.x) * double(size.y) * 45.0 / (1 << 20),
                  fmt::format("processing a {}x{} image", size.x, size.y));
  const auto context = makeContext(global, size);
  Image result;
  {
    auto timed = run.phase("process");
    render::post::Chain chain(size, effects);
    result = chain.run(frame);
    run.report()["effects"] = chain.describe();
  }
  run.throwIfInterrupted();
  {
    auto timed = run.phase("write");
    saveImage(result, a.output);
  }
  log::info("post: {} ({}x{}) → {}: {}", a.input, size.x, size.y, a.output, run.report()["effects"].get<std::string>());
  run.report()["input"] = a.input;
  run.report()["output"] = a.output;
  run.report()["width"] = size.x;
  run.report()["height"] = size.y;
  run.report()["frames"] = 1;
  run.finish();
  return 0;
}

// A video in, an image out: one frame (the first of --frames), processed.
int runStill(const PostArgs& a, const std::vector<render::post::Effect>& effects, video::Source& source, ToolRun& run) {
  requireImageIo();
  video::Frame frame;
  if (!source.read(frame)) fail(ErrorKind::Input, "{} has no frame to take a still from", source.info().name);
  render::post::Chain chain(source.info().size, effects);
  const Image result = chain.run(frame.image);
  run.throwIfInterrupted();
  saveImage(result, a.output);
  log::info("post: frame {} ({:.3f} s) of {} → {}", frame.index, frame.seconds, source.info().name, a.output);
  run.report()["input"] = source.info().name;
  run.report()["output"] = a.output;
  run.report()["frame"] = frame.index;
  run.report()["effects"] = chain.describe();
  run.finish();
  return 0;
}

int runVideo(const PostArgs& a, const std::vector<render::post::Effect>& effects, ToolRun& run,
             const GlobalOptions& global) {
  const std::string name = !a.camera.empty() ? a.camera : !a.lavfi.empty() ? a.lavfi : a.input;
  video::SourceOptions options{.camera = !a.camera.empty(), .realtime = a.realtime, .keepAudio = !a.noAudio,
                               .threads = a.tool.threads};
  if (!a.size.empty()) {
    if (a.camera.empty()) fail(ErrorKind::Usage, "--size is for cameras (a file or lavfi graph has its own size)");
    options.size = parseSize(a.size);
  }
  if (!a.rate.empty()) {
    if (a.camera.empty()) fail(ErrorKind::Usage, "--fps is for cameras");
    options.frameRate = parseFloat(a.rate, "--fps");
    if (options.frameRate <= 0.0) fail(ErrorKind::Usage, "--fps must be positive, got '{}'", a.rate);
  }
  const bool split = !a.frames.empty();
  if (split) std::tie(options.firstFrame, options.lastFrame) = parseFrames(a.frames);
  const video::Codec codec = video::parseCodec(a.codec);

  std::optional<ToolRun::Phase> opening(std::in_place, run, "open");
  video::Source source = video::Source::open(name, options);
  const video::SourceInfo& info = source.info();
  // Peak memory, measured with posterize on llvmpipe (GL textures are process memory there):
  // ~150 MiB, and ~280 bytes per pixel for a video (frames in flight, float targets, the
  // encoder), ~45 for one image.
  const double pixels = double(info.size.x) * double(info.size.y);
  run.checkMemory(150.0 + pixels * (video::isImagePath(a.output) ? 45.0 : 280.0) / (1 << 20),
                  fmt::format("processing {}x{} video", info.size.x, info.size.y));
  const auto context = makeContext(global, info.size);
  if (video::isImagePath(a.output)) return runStill(a, effects, source, run);
  render::post::FrameStream stream(info.size, effects);
  video::Sink sink(a.output, {.codec = codec, .size = info.size, .frameRate = info.frameRate, .timeBase = info.timeBase,
                              .crf = a.crf, .preset = a.preset, .threads = a.tool.threads, .noReordering = split,
                              .audio = a.noAudio ? nullptr : source.audio()});
  opening.reset();
  if (!sink.audioNote().empty()) run.warn(sink.audioNote());
  log::info("post: {} ({}x{}, {:.3g} fps, {}{}) → {} ({}): {}", name, info.size.x, info.size.y, info.frameRate.value(),
            info.codec, info.live ? ", live" : "", a.output, video::codecName(codec), stream.chain().describe());

  std::int64_t total = info.frameCount >= 0 ? info.frameCount - options.firstFrame : 0;
  if (options.lastFrame >= 0) total = options.lastFrame - options.firstFrame;
  Progress progress("post", std::uint64_t(std::max<std::int64_t>(total, 0)));
  const auto start = std::chrono::steady_clock::now();
  auto lastDetail = start;
  video::StreamProcessor<render::post::FrameStream> processor(stream);
  const video::TranscodeStats stats = video::transcode(
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
  run.addSeconds("read", stats.readSeconds);
  run.addSeconds("process", stats.processSeconds);
  run.addSeconds("write", stats.writeSeconds);
  const double fps = stats.seconds > 0 ? double(stats.framesWritten) / stats.seconds : 0.0;
  if (stats.droppedFrames > 0) {
    run.warn(fmt::format("{} live frame(s) dropped: the source delivered faster than glint could process", stats.droppedFrames));
  }
  // A file that ends before the frames its container announces (truncated, damaged): said, not
  // silent. Frames lost to corrupt packets are warned about already; one frame of slack for
  // containers that only know a rounded duration.
  const std::int64_t expected = info.frameCount >= 0 && options.lastFrame < 0 ? info.frameCount - options.firstFrame : -1;
  if (!stats.interrupted && !stats.inputError && expected > 0 &&
      stats.framesRead + source.corruptPackets() + 1 < expected) {
    run.warn(fmt::format("'{}' ended after {} of the {} frames its container announces (truncated or damaged?)", name,
                         stats.framesRead, expected));
  }
  if (source.corruptPackets() > 0) {
    run.recordWarning(fmt::format("{} corrupt packet(s) could not be decoded; those frames are missing", source.corruptPackets()));
  }
  // Damage the decoder concealed: the frames are there, some possibly wrong.
  const video::DecoderErrors decoderErrors = source.decoderErrors();
  if (decoderErrors.count > 0) {
    run.warn(fmt::format("'{}': the decoder reported {} error(s), the first '{}': some frames were damaged and "
                         "concealed by the decoder", name, decoderErrors.count, decoderErrors.first));
  }

  auto& report = run.report();
  report["input"] = name;
  report["output"] = a.output;
  report["width"] = info.size.x;
  report["height"] = info.size.y;
  report["frame_rate"] = info.frameRate.value();
  report["codec"] = video::codecName(codec);
  report["effects"] = stream.chain().describe();
  report["live"] = info.live;
  report["first_frame"] = options.firstFrame;
  report["frames_read"] = stats.framesRead;
  report["frames_written"] = stats.framesWritten;
  report["frames_expected"] = expected;
  report["dropped_frames"] = stats.droppedFrames;
  report["corrupt_packets"] = source.corruptPackets();
  report["decoder_errors"] = decoderErrors.count;
  report["audio"] = !info.hasAudio ? "none" : a.noAudio ? "dropped (--no-audio)" : sink.audioNote().empty() ? "copied" : "dropped";
  report["audio_packets"] = stats.audioPackets;
  report["fps"] = fps;
  report["partial"] = stats.interrupted || stats.inputError.has_value();
  report["interrupted"] = stats.interrupted;
  if (stats.inputError) report["input_error"] = *stats.inputError;

  if (stats.inputError) {
    run.finish();
    fail(ErrorKind::Input, "{}; '{}' was finished with the {} frame(s) before it (a complete, playable video)",
         *stats.inputError, a.output, stats.framesWritten);
  }
  if (stats.interrupted) {
    log::warn("post: interrupted after {} frame(s): '{}' is a complete, playable partial video", stats.framesWritten,
              a.output);
    run.finish();
    return exitCode(ErrorKind::Interrupted);
  }
  log::info("post: {} frame(s) in {:.2f} s ({:.1f} fps){}", stats.framesWritten, stats.seconds, fps,
            stats.droppedFrames ? fmt::format(", {} dropped", stats.droppedFrames) : "");
  run.finish();
  return 0;
}

}  // namespace

Command postCommand(CLI::App& app, const GlobalOptions& global) {
  auto a = std::make_shared<PostArgs>();
  auto* cmd = app.add_subcommand("post", "Post-process an image, a video, a camera or a lavfi source on the GPU "
                                         "(sepia, Sobel, Kuwahara, FFT filters)");
  cmd->footer(std::string(kFooter) + "\n\n" + render::post::effectHelp());
  cmd->add_option("file", a->input, "Image or video file to read (or lavfi:GRAPH)");
  cmd->add_option("-o,--output", a->output, "Image or video to write; format from the extension");
  cmd->add_option("-e,--effect", a->effects, "An effect, in chain order: NAME or NAME:param=value,... (list below)");
  cmd->add_option("--set", a->settings, "param=value (every effect that has it) or effect.param=value");
  cmd->add_option("--camera", a->camera, "Read a V4L2 camera, e.g. /dev/video0 (a live source)");
  cmd->add_option("--input", a->lavfi, "An FFmpeg source: lavfi:GRAPH, e.g. lavfi:testsrc2=size=1280x720:duration=5");
  cmd->add_option("--size", a->size, "Camera: the size to ask for, WIDTHxHEIGHT (the seed's camera: 640x480)");
  cmd->add_option("--fps", a->rate, "Camera: the frame rate to ask for");
  cmd->add_flag("--realtime", a->realtime, "Pace a file or lavfi source at its frame rate and treat it as live "
                                           "(frames the GPU cannot keep up with are dropped and counted)");
  cmd->add_option("--codec", a->codec, "h264 (libx264, yuv420p) or ffv1 (lossless RGB)")->capture_default_str();
  cmd->add_option("--crf", a->crf, "H.264 quality: 0 (lossless) .. 51; 18 is visually lossless")->capture_default_str();
  cmd->add_option("--preset", a->preset, "H.264 speed/size trade-off: ultrafast .. placebo")->capture_default_str();
  cmd->add_option("--frames", a->frames, "Only frames FIRST:END (END excluded; 250: = to the end): split a long video "
                                         "over machines, join the parts with --concat");
  cmd->add_option("--concat", a->concat, "Join parts made with --frames (in order) into -o, copying packets");
  cmd->add_flag("--no-audio", a->noAudio, "Do not copy the input's audio");
  cmd->add_flag("--effects", a->listEffects, "List the effects and their parameters, and exit");
  addToolOptions(*cmd, a->tool, "input, output, effects, frames read/written/dropped, fps, audio, partial");

  return Command{.run = [a, &global] {
                   if (a->listEffects) {
                     fmt::print("{}", render::post::effectHelp());
                     return 0;
                   }
                   ToolRun run("post", a->tool);
                   if (!a->concat.empty()) return runConcat(*a, run);
                   // Usage errors first: fail in a millisecond, before opening anything.
                   const int sources = int(!a->input.empty()) + int(!a->camera.empty()) + int(!a->lavfi.empty());
                   if (sources == 0) fail(ErrorKind::Usage, "post needs an input: a file, --camera DEVICE or --input lavfi:GRAPH");
                   if (sources > 1) fail(ErrorKind::Usage, "post takes one input: a file, --camera or --input, not several");
                   if (!a->lavfi.empty() && !a->lavfi.starts_with("lavfi:")) {
                     fail(ErrorKind::Usage, "--input takes lavfi:GRAPH (files are given as the first argument), got '{}'", a->lavfi);
                   }
                   if (a->output.empty()) fail(ErrorKind::Usage, "post needs -o OUTPUT");
                   const auto effects = render::post::parseEffects(a->effects, a->settings);
                   checkWritable(a->output);
                   if (!a->tool.json.empty() && a->tool.json != "-") checkWritable(a->tool.json);
                   const bool image = !a->input.empty() && !a->input.starts_with("lavfi:") && video::isImagePath(a->input);
                   if (image || video::isImagePath(a->output)) preloadImageIo();  // while the GPU starts
                   if (!image && a->input.starts_with("lavfi:")) a->lavfi = std::exchange(a->input, {});
                   return image ? runImage(*a, effects, run, global) : runVideo(*a, effects, run, global);
                 },
                 .readsImages = false};  // images load OpenImageIO themselves (runImage, runStill)
}

}  // namespace glint::app
