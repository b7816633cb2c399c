#include "glint/core/options.h"

#include "glint/core/tool.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <charconv>

namespace glint {

void addToolOptions(CLI::App& command, ToolSettings& settings, const std::string& reportContents) {
  command.add_option("--threads", settings.threads, "Worker threads (default: all cores); the output does not depend on it")
      ->check(CLI::Validator(
          [](const std::string& text) {
            int value = -1;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
            if (ec != std::errc() || end != text.data() + text.size() || value < 0)
              return fmt::format("'{}' is not 0 (every core) or a number of threads", text);
            return std::string();
          },
          "N"));
  command.add_flag("-q,--quiet", settings.quiet, "No progress bar or info messages, only warnings and errors");
  command.add_option("--max-memory", settings.maxMemory,
                     "Refuse a job estimated to need more memory than this (MiB, or 512M, 4G) with a clear error, "
                     "before it starts (default: the machine's physical memory)");
  command.add_option("--json", settings.json,
                     "Write a JSON report (" + reportContents + "; phase times, peak memory, threads, warnings) to "
                     "this file, '-' for stdout");
}

std::vector<std::string> toolArguments(const ToolSettings& settings) {
  std::vector<std::string> argv;
  if (settings.threads > 0) argv.insert(argv.end(), {"--threads", std::to_string(settings.threads)});
  if (settings.quiet) argv.push_back("-q");
  if (!settings.maxMemory.empty()) argv.insert(argv.end(), {"--max-memory", settings.maxMemory});
  if (!settings.json.empty()) argv.insert(argv.end(), {"--json", settings.json});
  return argv;
}

}  // namespace glint
