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
#include "glint/core/options.h"
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


}  // namespace glint::app
