// glint gallery — every variant rendered, timed, and laid out in index.html: the command's
// options for the library's job (scenes/gallery.h).
#include "common.h"

#include "glint/core/text.h"
#include "glint/scenes/gallery.h"

#include <memory>
#include <string>

namespace glint::app {

namespace {
struct GalleryArgs {
  std::string output = "out/gallery";
  std::string filter;
  std::string size;
  std::string references;
  int repeats = 5;
};
}  // namespace

Command galleryCommand(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<GalleryArgs>();
  auto* cmd = app.add_subcommand("gallery", "Render every variant and write an HTML page of pictures and frame times");
  cmd->footer("Writes DIR/index.html, DIR/gallery.json and DIR/<scene>/<variant>.png.\n"
              "Variants that need a compatibility-profile context are skipped (and marked) where none exists, and so\n"
              "are those that read their frames through the video module (post/camera) where it cannot load.");
  cmd->add_option("-o,--output", args->output, "Gallery directory (created if missing)")->capture_default_str();
  cmd->add_option("--filter", args->filter, "Only variants whose name contains this text");
  cmd->add_option("--size", args->size, "Render every variant at WIDTHxHEIGHT instead of its own size");
  cmd->add_option("--references", args->references,
                  "Compare every variant with DIR/<scene>/<variant>.png (glint's tests/golden) at the reference tests' "
                  "tolerance (mean ≤ 0.5/255, ≤ 0.2 % of pixels off by more than 1/255): figures in gallery.json, "
                  "differences as <variant>.diff.png, exit 1 when one differs beyond it or has no reference")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--repeats", args->repeats, "Frames timed per variant (0: no timing)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  return Command{.run = [args, &global] {
    scenes::GalleryJob job{.output = args->output, .filter = args->filter, .references = args->references,
                           .repeats = args->repeats, .glDebug = global.glDebug};
    if (!args->size.empty()) job.size = parseSize(args->size);
    return scenes::runGallery(job);
  }};
}

}  // namespace glint::app
