// glint render — one variant, headless, to an image file; or its animation, frame range by
// frame range, to a video (the frame loop is the library's: scenes/clip.h).
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/image/image.h"
#include "glint/scenes/clip.h"
#include "glint/scenes/runner.h"
#include "glint/video/source.h"

#include <algorithm>

namespace glint::app {

namespace {
struct RenderArgs {
  std::string name;
  std::string output;
  std::string size;
  double time = 0;
  bool timeSet = false;
  std::vector<std::string> options;
  std::string frames, codec = "h264", preset = "medium";
  int fps = 30, crf = 18;
};

constexpr const char* kRenderFooter = R"(Examples:
  glint render basics/triangle/depth -o depth.png
  glint render basics/depth/greater --size 1024x1024 -o greater.png
  glint render pipedream -o clip.mp4 --frames 0:600 --fps 30 --size 640x360
  glint render pipedream -o part1.mkv --codec ffv1 --frames 150:300 --fps 30
  glint post --concat part0.mkv part1.mkv -o whole.mkv

Rendering is deterministic: animation follows --time, never the clock. A video (-o .mp4
.mkv .mov .avi .nut) holds frames FIRST..END-1 of --frames, frame i rendered at time
i / --fps (exactly what --time i/fps gives) with timestamp i: parts rendered on several
machines join losslessly with `glint post --concat` (FFV1 parts into the very bytes of one
run; H.264 is written without B-frames, so its parts join too). The video is written
atomically: Ctrl-C (exit 130) or an error leaves no file, and an existing one as it was.)";
}  // namespace

Command renderCommand(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand("render", "Render one scene variant headless to an image (PNG, EXR, TGA, JPEG, ...), "
                                           "or its animation to a video (MP4, MKV)");
  cmd->footer(kRenderFooter);
  cmd->add_option("scene", args->name, "scene/variant, or scene for its first variant (see `glint list`)")->required();
  cmd->add_option("-o,--output", args->output, "Output image or video; the format follows the extension "
                                               "(default: SCENE-VARIANT.png)");
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT in pixels (default: the scene's own size)");
  cmd->add_option("--time", args->time, "Image: scene time in seconds for animated scenes (default: the scene's own)")
      ->each([args](const std::string&) { args->timeSet = true; });
  cmd->add_option("--set", args->options, "Scene option as name=value (repeatable; the viewer lists them)");
  auto* frames = cmd->add_option("--frames", args->frames, "Video: frames FIRST:END (END excluded; required), "
                                                           "frame i at time i / fps");
  auto* fps = cmd->add_option("--fps", args->fps, "Video: frames per second")->capture_default_str();
  auto* codec = cmd->add_option("--codec", args->codec, "Video: h264 (libx264, yuv420p) or ffv1 (lossless RGB)")
                    ->capture_default_str();
  auto* crf = cmd->add_option("--crf", args->crf, "H.264 quality: 0 (lossless) .. 51; 18 is visually lossless")
                  ->capture_default_str();
  auto* preset = cmd->add_option("--preset", args->preset, "H.264 speed/size trade-off: ultrafast .. placebo")
                     ->capture_default_str();
  return Command{.run = [args, &global, videoOnly = std::vector{frames, fps, codec, crf, preset}] {
    const auto ref = scenes::Registry::builtin().resolve(args->name);
    std::string output = args->output;
    if (output.empty()) {
      output = ref.fullName() + ".png";
      std::replace(output.begin(), output.end(), '/', '-');
    }
    scenes::ContextPool contexts(global.glDebug);
    if (video::isVideoPath(output)) {
      if (args->frames.empty()) fail(ErrorKind::Usage, "a video output needs --frames FIRST:END (e.g. --frames 0:300)");
      if (args->timeSet) fail(ErrorKind::Usage, "--time is for an image; in a video frame i is at time i / --fps");
      scenes::ClipRequest clip{.frames = parseFrameRange(args->frames, "--frames"), .fps = args->fps,
                               .options = args->options, .codec = video::parseCodec(args->codec),
                               .crf = args->crf, .preset = args->preset};
      if (!args->size.empty()) clip.size = parseSize(args->size);
      if (clip.codec == video::Codec::H264) video::checkPreset(clip.preset);
      ToolRun run("render", {.quiet = global.quiet});
      contexts.use(ref.scene->profile);
      const scenes::ClipStats s = scenes::renderClip(ref, clip, output, run);
      const double n = double(s.framesWritten);
      log::info("render: {} frames ({}..{}) → {}: {}x{}, {} fps, {}, {:.2f} s ({:.1f} frames/s; a frame: render {:.0f} ms, "
                "encode {:.0f} ms)", s.framesWritten, s.frames.first, s.frames.end - 1, s.output, s.size.x, s.size.y,
                s.fps, s.codec, s.seconds, n / s.seconds, 1000 * s.renderSeconds / n, 1000 * s.encodeSeconds / n);
      run.finish();
      return 0;
    }
    for (const CLI::Option* option : videoOnly) {
      if (option->count() > 0) fail(ErrorKind::Usage, "{} is for a video output (-o .mp4 .mkv .mov .avi .nut)", option->get_name());
    }
    checkImageOutput(output);  // fail before rendering, not after
    scenes::RenderRequest request;
    if (!args->size.empty()) request.size = parseSize(args->size);
    if (args->timeSet) request.time = args->time;
    request.options = args->options;
    contexts.use(ref.scene->profile);
    const auto result = scenes::renderVariant(ref, request);
    saveImage(result.image, output);
    log::info("{} → {} ({}x{})", ref.fullName(), output, result.image.width(), result.image.height());
    if (!result.notes.empty()) log::info("{}", result.notes);
    return 0;
  }};
}

}  // namespace glint::app
