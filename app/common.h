#pragma once
// Shared pieces of the glint subcommands.
#include "glint/core/math.h"

#include <CLI/CLI.hpp>

#include <string>

namespace glint::app {

struct GlobalOptions {
  bool glDebug = false;
  bool quiet = false;
  bool verbose = false;
};

/// "640x360" → {640, 360}; Error(Usage) for anything else or sizes outside 1..16384.
ivec2 parseSize(const std::string& text);

// Each subcommand adds itself to the app and returns the function that runs it.
using Runner = std::function<int()>;
Runner addListCommand(CLI::App& app, const GlobalOptions& global);
Runner addRenderCommand(CLI::App& app, const GlobalOptions& global);
Runner addGalleryCommand(CLI::App& app, const GlobalOptions& global);
Runner addInfoCommand(CLI::App& app, const GlobalOptions& global);
Runner addViewCommand(CLI::App& app, const GlobalOptions& global);
Runner addBenchCommand(CLI::App& app, const GlobalOptions& global);
Runner addMeshInfoCommand(CLI::App& app, const GlobalOptions& global);
Runner addRasterCommand(CLI::App& app, const GlobalOptions& global);
Runner addBakeCommand(CLI::App& app, const GlobalOptions& global);
Runner addNormalMapCommand(CLI::App& app, const GlobalOptions& global);

}  // namespace glint::app
