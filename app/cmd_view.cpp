// glint view — the interactive viewer (viewer/viewer.h): its options, and the shader
// directory it hot-reloads from (the source tree's shaders/ when it exists).
#include "common.h"

#include "glint/bake/asset.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/text.h"
#include "glint/gl/shader.h"
#include "glint/scenes/model.h"
#include "glint/viewer/viewer.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace glint::app {
namespace fs = std::filesystem;

namespace {
struct ViewArgs {
  std::string size = "1280x800";
  std::string shaderDir;
  std::string exportWeb;
  viewer::ViewerOptions options;
};
/// `glint view FILE --export-web DIR`: the model in the page `glint bake --preview` writes.
int exportWeb(const std::string& file, const std::string& dir) {
  if (!scenes::isModelFile(file))
    fail(ErrorKind::Usage, "--export-web needs a model file (.glb .gltf .obj .ply .fbx), got '{}'", file);
  // Before any work: the folder is new, empty or a page glint wrote, and no file of the page
  // is the model itself (`--export-web .` beside a model.glb).
  const fs::path folder = bake::checkPageFolder(dir, "--export-web");
  std::vector<FileUse> outputs;
  for (const std::string& f : bake::previewFiles()) outputs.push_back({folder / f, "--export-web"});
  checkDistinctFiles({{file, "the model"}}, outputs);
  // The page holds only what glint read and wrote again: never the file's own bytes, so
  // a texture glint does not read (an emissive map with an http: uri) is not fetched by a
  // browser opening the page. What is left out is said.
  const scenes::ModelFile model = scenes::loadModelFile(file);
  for (const std::string& what : model.dropped) log::warn("--export-web: {} is left out of the page (glint does not read it)", what);
  const std::vector<unsigned char> glb = scenes::modelGlb(model);
  OutputSet outputSet;  // the page's files together, or none (and no folder) when a write fails
  bake::savePreviewPage(glb, fs::path(file).filename().string(), folder);
  outputSet.commit();
  log::info("view: {} → {}", file, (folder / "index.html").string());
  return 0;
}
}  // namespace

Command viewCommand(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<ViewArgs>();
  auto* cmd = app.add_subcommand("view", "Open the interactive viewer (a window with a panel of variants and options)");
  cmd->footer("Keys: left/right variant, up/down scene, space pause, R reload shaders, F12 screenshot, Tab panel,\n"
              "Esc quit. Mouse, in 3D scenes: left drag orbits, right or middle drag pans, the wheel zooms,\n"
              "C or Home returns to the scene's camera (kept across variants, reset on another scene).\n"
              "Without a display, run it under Xvfb: xvfb-run -s '-screen 0 1280x800x24' glint view");
  cmd->add_option("scene", args->options.scene, "scene or scene/variant to start with (default: the first), or a model "
                  "file to look at: .glb .gltf .obj .ply .fbx (a bake's asset shows its maps, misses and hard edges)");
  cmd->add_option("--export-web", args->exportWeb, "With a model file: write a web page that shows it into this folder "
                  "(opens offline, from disk or any web server; as glint bake --preview) instead of opening a window")
      ->type_name("DIR");
  cmd->add_option("--size", args->size, "Window size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--shaders", args->shaderDir,
                  "Directory to hot-reload shaders from (default: the source tree's shaders/ when it exists)");
  cmd->add_option("--screenshot", args->options.screenshot, "Save the window (scene + panel) to this image after --frames frames and exit");
  cmd->add_option("--frames", args->options.frames, "Frames to draw before --screenshot (default 2)");
  cmd->add_option("--shot-dir", args->options.shotDir, "Directory F12 saves screenshots into (glint-view-1.png, -2, ...)")
      ->capture_default_str();
  cmd->add_option("--set", args->options.settings, "name=value: set a scene option (as glint render --set), in every scene "
                                           "that has it, e.g. --set input=/dev/video0 for post/camera");
  return Command{.run = [args, &global] {
    if (!args->exportWeb.empty()) return exportWeb(args->options.scene, args->exportWeb);
    viewer::ViewerOptions options = args->options;
    options.size = parseSize(args->size);
    options.glDebug = global.glDebug;
    const fs::path dir = args->shaderDir.empty() ? fs::path(GLINT_SOURCE_SHADER_DIR) : fs::path(args->shaderDir);
    if (std::error_code ec; fs::is_directory(dir, ec)) {
      gl::ShaderSources::setDirectory(dir);
    } else if (!args->shaderDir.empty()) {
      fail(ErrorKind::Usage, "--shaders: '{}' is not a directory", args->shaderDir);
    }
    scenes::Registry model;  // a model file's own scene (scenes/model.h)
    const scenes::Registry& registry = scenes::registryFor(options.scene, model);
    return viewer::run(options, registry);
  }};
}

}  // namespace glint::app
