#pragma once
// What the glint subcommands share: global options, the Command each one returns, the
// options every offline tool takes. The parsers for typed values (parseSize, ...) are in
// core/text.h, where the fuzzer reaches them.
//
// Adding a subcommand: write app/cmd_<name>.cpp defining
//   Command <name>Command(CLI::App& app, const GlobalOptions& global);
// (it adds its CLI11 subcommand to `app` and returns what runs it), and add <name> to
// GLINT_COMMANDS in app/CMakeLists.txt. main.cpp declares and registers every command from
// that one list (the generated commands.inc); nothing else changes.
#include "glint/core/math.h"
#include "glint/core/text.h"
#include "glint/core/tool.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace glint::app {

struct GlobalOptions {
  bool glDebug = false;
  bool quiet = false;
  bool verbose = false;
};

/// A subcommand, as its file's <name>Command() returns it.
struct Command {
  std::function<int()> run;  ///< runs the command after parsing; returns the exit status
  bool readsImages = true;   ///< start loading the image I/O module in the background at once
};

/// Binds the options every offline tool takes to `settings`: --threads, -q/--quiet and
/// --json FILE ('-' for stdout). `reportContents` completes the --json help text ("texels,
/// rays, hit ratio"); the common fields (phase times, peak memory, ...) are listed for it.
void addToolOptions(CLI::App& command, ToolSettings& settings, const std::string& reportContents);

/// One bake of a batch file (`glint bake --batch`), as `glint farm bake` plans it: where it
/// is for messages ("bake: jobs.json job 2 (crate_low.obj)"), the files it reads and writes
/// (relative paths already resolved against the batch file's folder), its memory estimate.
struct BatchBake {
  std::string where;
  std::vector<std::string> inputs, outputs;
  double memoryMiB = 0.0;
};
/// The bakes of a batch file, parsed and checked as `glint bake --batch` does (Error(Usage)
/// naming the job, Error(Input) for an unreadable file). cmd_bake.cpp.
std::vector<BatchBake> batchBakes(const std::string& file);

}  // namespace glint::app
