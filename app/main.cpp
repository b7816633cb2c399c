// glint — one command for every technique: render, gallery, view, tools.
// Thin: parse options, call the library, turn errors into one line + exit code.
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/core/options.h"
#include "glint/core/text.h"
#include "glint/image/image.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <map>
#include <new>
#include <string>
#include <vector>

namespace glint::app {

// Every subcommand's function, declared from the one list in app/CMakeLists.txt.
#define GLINT_COMMAND(name) Command name##Command(CLI::App& app, const GlobalOptions& global);
#include "commands.inc"
#undef GLINT_COMMAND

namespace {
// Runs the chosen command: a glint::Error becomes its one-line message and its exit status.
int run(const Command& command) {
  try {
    // OpenImageIO is a module of ~260 libraries (~0.3 s to load): commands that touch
    // images load it on the second core while they parse meshes or set up GL.
    if (command.readsImages) preloadImageIo();
    return command.run();
  } catch (const Error& e) {
    std::fprintf(stderr, "glint: %s\n", escapedLine(e.what()).c_str());  // one line, whatever a file name holds
    return exitCode(e.kind());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "glint: out of memory: the job needed more than this machine could give (a smaller job, or "
                 "--max-memory to be told before it starts)\n");
    return exitCode(ErrorKind::OutOfMemory);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: internal error: %s\n", escapedLine(e.what()).c_str());
    return 1;
  }
}
}  // namespace

}  // namespace glint::app

int main(int argc, char** argv) {
  using namespace glint;
  // Whatever way main returns, a background load of the image module ends first: exit()
  // would otherwise run handlers its libraries registered while they were still loading.
  struct FinishPreload {
    ~FinishPreload() { finishImageIoPreload(); }
  } finishPreload;
  CLI::App cli{"glint — advanced real-time rendering on OpenGL 4.5.\n"
               "Every technique is a scene with variants (`glint list`); render them headless, "
               "build a gallery, or explore them in a window.",
               "glint"};  // the usage line says `glint`, not the binary's full path
  cli.require_subcommand(1);
  cli.fallthrough();  // global flags work after the subcommand too (glint render X -q)
  cli.set_help_all_flag("--help-all", "Show help for every subcommand");
  cli.set_version_flag("--version", "glint " GLINT_VERSION);
  app::GlobalOptions global;
  cli.add_flag("--gl-debug", global.glDebug, "OpenGL debug context; GL errors are logged and counted");
  cli.add_flag("-q,--quiet", global.quiet, "Only warnings and errors");
  cli.add_flag("-v,--verbose", global.verbose, "Debug messages too");

  // Each command adds its CLI11 subcommand; remember which Command runs which.
  using AddCommand = app::Command (*)(CLI::App&, const app::GlobalOptions&);
  const std::vector<AddCommand> commands{
#define GLINT_COMMAND(name) &app::name##Command,
#include "commands.inc"
#undef GLINT_COMMAND
  };
  std::map<CLI::App*, app::Command> byName;
  for (AddCommand add : commands) {
    const auto before = cli.get_subcommands({});
    app::Command command = add(cli, global);
    for (CLI::App* sub : cli.get_subcommands({}))
      if (std::find(before.begin(), before.end(), sub) == before.end()) byName[sub] = command;
  }

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
    std::fprintf(stderr, "glint: %s (see --help)\n", escapedLine(e.what()).c_str());
    return exitCode(ErrorKind::Usage);
  }
  log::setLevel(global.verbose ? log::Level::Debug : global.quiet ? log::Level::Warn : log::Level::Info);
  for (CLI::App* sub : cli.get_subcommands()) return app::run(byName.at(sub));
  return 0;
}
