// glint render — one variant, headless, to an image file.
#include "common.h"

#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/image/image.h"
#include "glint/scenes/runner.h"

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
};
}  // namespace

Command renderCommand(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand("render", "Render one scene variant headless to an image (PNG, EXR, TGA, JPEG, ...)");
  cmd->footer("Examples:\n  glint render basics/triangle/depth -o depth.png\n"
              "  glint render basics/depth/greater --size 1024x1024 -o greater.png\n"
              "Rendering is deterministic: animation follows --time, never the clock.");
  cmd->add_option("scene", args->name, "scene/variant, or scene for its first variant (see `glint list`)")->required();
  cmd->add_option("-o,--output", args->output, "Output image; the format follows the extension (default: SCENE-VARIANT.png)");
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT in pixels (default: the scene's own size)");
  cmd->add_option("--time", args->time, "Scene time in seconds for animated scenes (default: the scene's own)")
      ->each([args](const std::string&) { args->timeSet = true; });
  cmd->add_option("--set", args->options, "Scene option as name=value (repeatable; the viewer lists them)");
  return Command{.run = [args, &global] {
    const auto ref = scenes::Registry::builtin().resolve(args->name);
    std::string output = args->output;
    if (output.empty()) {
      output = ref.fullName() + ".png";
      std::replace(output.begin(), output.end(), '/', '-');
    }
    checkImageOutput(output);  // fail before rendering, not after
    scenes::RenderRequest request;
    if (!args->size.empty()) request.size = parseSize(args->size);
    if (args->timeSet) request.time = args->time;
    request.options = args->options;
    scenes::ContextPool contexts(global.glDebug);
    contexts.use(ref.scene->profile);
    const auto result = scenes::renderVariant(ref, request);
    saveImage(result.image, output);
    log::info("{} → {} ({}x{})", ref.fullName(), output, result.image.width(), result.image.height());
    if (!result.notes.empty()) log::info("{}", result.notes);
    return 0;
  }};
}

}  // namespace glint::app
