// glint render — one variant, headless, to an image file; or its animation, frame range by
// frame range, to a video (the frame loop is the library's: scenes/clip.h).
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/image/image.h"
#include "glint/scenes/clip.h"
#include "glint/scenes/model.h"
#include "glint/scenes/render_job.h"
#include "glint/scenes/runner.h"
#include "glint/video/source.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace glint::app {
namespace fs = std::filesystem;

Command renderCommand(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<scenes::RenderArgs>();
  auto* cmd = app.add_subcommand("render", "Render one scene variant headless to an image (PNG, EXR, TGA, JPEG, ...), "
                                           "or its animation to a video (MP4, MKV)");
  cmd->footer(scenes::helpFooter());
  std::vector<const void*> videoOnly;
  scenes::addOptions(*cmd, *args, &videoOnly);
  return Command{.run = [args, &global, videoOnly] {
    std::string name = args->scene;
    scenes::Registry model;  // a model file's own scene (scenes/model.h)
    const auto ref = scenes::registryFor(name, model).resolve(name);
    if (!args->camera.empty())
      for (std::string& setting : scenes::cameraSettings(args->camera, ref)) args->options.push_back(std::move(setting));
    std::string output = args->output;
    if (output.empty()) {
      output = scenes::isModelFile(args->scene) ? fs::path(args->scene).stem().string() + ".png" : ref.fullName() + ".png";
      std::replace(output.begin(), output.end(), '/', '-');
    }
    scenes::ContextPool contexts(global.glDebug);
    if (video::isVideoPath(output)) {
      const scenes::ClipRequest clip = scenes::clipRequest(*args);
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
    for (const void* o : videoOnly) {
      const auto* option = static_cast<const CLI::Option*>(o);
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
