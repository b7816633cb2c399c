#pragma once
// glint/core/log.h — leveled logging to stderr.
//
// Messages go to stderr so that stdout stays clean for machine-readable output
// (`glint list`, `--json` reports). The level is global; `--quiet` sets Warn,
// `--verbose` sets Debug.
//
/// ```cpp
/// const int n = 12;
/// const double seconds = 3.25;
/// glint::log::info("rendered {} variants in {:.1f} s", n, seconds);
/// glint::log::setLevel(glint::log::Level::Warn);  // what --quiet does
/// ```

#include <fmt/format.h>

#include <string>
#include <string_view>
#include <vector>

namespace glint::log {

enum class Level {
  Debug,  ///< details for developers (`--verbose`)
  Info,   ///< what a command is doing (default)
  Warn,   ///< something the user should know, work goes on
  Error,  ///< the command failed
  Off     ///< nothing at all
};

void setLevel(Level level);
Level level();
void write(Level level, std::string_view message);

/// The warnings printed while it lives, from any thread, kept as well as printed: a tool
/// runs library code that logs its own warnings (the mesh loader's) under one, and lists
/// them in its report (ToolRun::recordWarning). Captures may nest; each sees every warning.
///
/// ```cpp
/// glint::log::WarningCapture printed;
/// glint::log::warn("'{}': no normals", "room.obj");
/// const std::vector<std::string> warnings = printed.take();  // {"'room.obj': no normals"}
/// ```
class WarningCapture {
public:
  WarningCapture();
  ~WarningCapture();
  WarningCapture(const WarningCapture&) = delete;
  WarningCapture& operator=(const WarningCapture&) = delete;
  /// The warnings printed since construction or the last take(), in order; clears them.
  std::vector<std::string> take();

private:
  std::vector<std::string> m_warnings;
  friend void write(Level level, std::string_view message);
};

template <typename... Args>
void debug(fmt::format_string<Args...> f, Args&&... a) {
  if (level() <= Level::Debug) write(Level::Debug, fmt::format(f, std::forward<Args>(a)...));
}
template <typename... Args>
void info(fmt::format_string<Args...> f, Args&&... a) {
  if (level() <= Level::Info) write(Level::Info, fmt::format(f, std::forward<Args>(a)...));
}
template <typename... Args>
void warn(fmt::format_string<Args...> f, Args&&... a) {
  if (level() <= Level::Warn) write(Level::Warn, fmt::format(f, std::forward<Args>(a)...));
}
template <typename... Args>
void error(fmt::format_string<Args...> f, Args&&... a) {
  if (level() <= Level::Error) write(Level::Error, fmt::format(f, std::forward<Args>(a)...));
}

}  // namespace glint::log
