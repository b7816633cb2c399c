// glint — one command for every technique: render, gallery, view, tools.
// Thin: parse options, call the library, turn errors into one line + exit code.
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/image/image.h"

#include <csignal>
#include <cstdio>
#include <map>
#include <set>
#include <string>

namespace glint::app {

ivec2 parseSize(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X')) {
    fail(ErrorKind::Usage, "size must be WIDTHxHEIGHT (e.g. 640x360), got '{}'", text);
  }
  if (w < 1 || h < 1 || w > 16384 || h > 16384) {
    fail(ErrorKind::Usage, "size {}x{} is out of range (1..16384 per side)", w, h);
  }
  return {w, h};
}

}  // namespace glint::app

int main(int argc, char** argv) {
  using namespace glint;
  CLI::App cli{"glint — advanced real-time rendering on OpenGL 4.5.\n"
               "Every technique is a scene with variants (`glint list`); render them headless, "
               "build a gallery, or explore them in a window."};
  cli.require_subcommand(1);
  cli.fallthrough();  // global flags work after the subcommand too (glint render X -q)
  cli.set_help_all_flag("--help-all", "Show help for every subcommand");
  cli.set_version_flag("--version", "glint " GLINT_VERSION);
  app::GlobalOptions global;
  cli.add_flag("--gl-debug", global.glDebug, "OpenGL debug context; GL errors are logged and counted");
  cli.add_flag("-q,--quiet", global.quiet, "Only warnings and errors");
  cli.add_flag("-v,--verbose", global.verbose, "Debug messages too");

  std::map<CLI::App*, app::Runner> runners;
  auto add = [&](app::Runner (*fn)(CLI::App&, const app::GlobalOptions&)) {
    const auto before = cli.get_subcommands({});
    app::Runner r = fn(cli, global);
    for (CLI::App* sub : cli.get_subcommands({}))
      if (std::find(before.begin(), before.end(), sub) == before.end()) runners[sub] = r;
  };
  add(app::addListCommand);
  add(app::addRenderCommand);
  add(app::addGalleryCommand);
  add(app::addViewCommand);
  add(app::addInfoCommand);
  add(app::addBenchCommand);
  add(app::addMeshInfoCommand);
  add(app::addRasterCommand);
  add(app::addBakeCommand);
  add(app::addNormalMapCommand);

  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line and the usage exit code, like every other glint error.
    std::fprintf(stderr, "glint: %s (see --help)\n", e.what());
    return exitCode(ErrorKind::Usage);
  }
  log::setLevel(global.verbose ? log::Level::Debug : global.quiet ? log::Level::Warn : log::Level::Info);
  // OpenImageIO is a module of ~260 libraries (~0.3 s to load): commands that touch
  // images load it on the second core while they parse meshes or set up GL.
  // (`bake` starts it itself, only when it reads an image or writes one that is not PNG:
  // PNG goes through libspng, and the load would take the second core from the mesh parser.)
  static const std::set<std::string> kNoImages{"list", "info", "mesh-info", "bake"};
  for (CLI::App* sub : cli.get_subcommands())
    if (!kNoImages.contains(sub->get_name())) preloadImageIo();
  try {
    for (CLI::App* sub : cli.get_subcommands()) return runners.at(sub)();
  } catch (const Error& e) {
    std::fprintf(stderr, "glint: %s\n", e.what());
    return exitCode(e.kind());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
