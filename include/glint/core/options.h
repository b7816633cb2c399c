#pragma once
// glint/core/options.h — the command-line options the tools share, defined once (CLI11).
//
// Each tool's library defines its options (cut/job.h, bake/job.h, post/job.h,
// scenes/clip.h): `glint TOOL`, `glint farm TOOL`, batch files and the Python module parse
// with those very definitions, so a name, a default or a check cannot differ between them.
// This header holds what every tool has: ToolSettings (core/tool.h) as --threads, -q,
// --max-memory and --json, and the way back from settings to arguments for a farm's pieces.
//
/// ```cpp
/// #include <CLI/CLI.hpp>
/// CLI::App app{"demo"};
/// glint::ToolSettings settings;
/// glint::addToolOptions(app, settings, "texels, rays");
/// app.parse(std::vector<std::string>{"4", "--threads", "-q"});  // CLI11 takes them last first
/// const std::vector<std::string> again = glint::toolArguments(settings);  // {"--threads", "4", "-q"}
/// ```
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace glint {

struct ToolSettings;

/// Binds the options every offline tool takes to `settings`: --threads, -q/--quiet,
/// --max-memory and --json FILE ('-' for stdout). `reportContents` completes the --json help
/// text ("texels, rays, hit ratio"); the common fields (phase times, peak memory, ...) are
/// listed for it.
void addToolOptions(CLI::App& command, ToolSettings& settings, const std::string& reportContents);

/// `settings` as the arguments that give them: --threads N (when not 0), -q, --max-memory M
/// and --json F (when set), in that order.
std::vector<std::string> toolArguments(const ToolSettings& settings);

}  // namespace glint
