#pragma once
// glint/core/tool.h — what every offline tool (`glint bake`, `post`, `cut`) shares.
//
// A tool is a long job over explicit inputs and outputs. Whatever it computes, a new user
// expects the same things of it, and ToolRun gives them in one place:
//
//   Ctrl-C        SIGINT/SIGTERM set a flag the work polls (cancelFlag(), pass it to the
//                 library); the tool stops, writes nothing, exits 130. A second Ctrl-C kills
//                 at once. Outputs are written atomically (core/file.h), so no partial file
//                 is left either way.
//   --threads N   caps oneTBB's worker threads for the run; tools keep their output
//                 independent of it (deterministic partitions, ordered reductions).
//   -q            no progress bars or info lines (log level Warn): Progress is silent.
//   timings       phase("load") measures a scope; addSeconds() takes phases a library timed.
//   memory        peakMemoryMiB(): the process's peak resident set. --max-memory M: the tool
//                 estimates what a job needs before it starts (checkMemory) and refuses one
//                 that would exceed M with a clear error, instead of an out-of-memory kill.
//   --json F      report(): the tool's own fields; finish() adds tool, version, threads,
//                 seconds (per phase and total), peak memory and warnings, and writes the
//                 report atomically to F, or to stdout for "-".
//   all or none   the run's outputs (every file written through core/file.h, the report
//                 included) are staged in its OutputSet and renamed into place together by
//                 finish(); a run that ends without finish() (an error, Ctrl-C, a full disk)
//                 leaves every existing output as it was.
//
/// ```cpp
/// #include <vector>
/// glint::ToolSettings settings;  // from the command line: addToolOptions in app/main.cpp
/// settings.threads = 4;
/// glint::ToolRun run("bake", settings);
/// const std::atomic<bool>* cancel = &run.cancelFlag();  // handed to the library, which polls it
/// run.checkMemory(512.0, "a 4096² bake");              // Error(Usage) over --max-memory
/// std::vector<float> texels;
/// {
///   auto timed = run.phase("load");
///   texels.assign(std::size_t(4096) * 4096, 0.0f);
/// }
/// run.throwIfInterrupted();  // Error(Interrupted) → exit 130
/// run.report()["texels"] = texels.size();
/// run.finish();  // after the outputs are written
/// ```
//
// One ToolRun at a time per process (it owns the signal handlers).

#include "glint/core/file.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace glint {

/// The options every tool takes, bound to --threads, -q/--quiet, --max-memory and --json by
/// addToolOptions (app/main.cpp, declared in app/common.h).
struct ToolSettings {
  int threads = 0;   ///< worker threads; 0 = every core
  bool quiet = false;  ///< warnings and errors only: no progress bar, no info lines
  std::string json;  ///< where to write the report: a path, "-" for stdout, empty for none
  std::string maxMemory;  ///< --max-memory ("4096" MiB, "512M", "4G"): refuse jobs estimated to need more; empty: no limit
  /// A cancel flag the caller owns (the Python module, a GUI): the run polls it instead of
  /// its own, and installs no SIGINT/SIGTERM handlers (the caller turns Ctrl-C into it).
  const std::atomic<bool>* cancel = nullptr;
};

class ToolRun {
public:
  /// Starts the run: installs the interrupt handlers, caps the thread count, lowers the
  /// log level when quiet. Error(Usage) for a negative thread count or a --max-memory that
  /// is not a size.
  ToolRun(std::string tool, const ToolSettings& settings);
  /// Restores the previous signal handlers and thread limit.
  ~ToolRun();
  ToolRun(const ToolRun&) = delete;
  ToolRun& operator=(const ToolRun&) = delete;

  // ------------------------------------------------------------------ interrupts
  /// Set by Ctrl-C (SIGINT) or SIGTERM; hand it to library code that polls.
  const std::atomic<bool>& cancelFlag() const;
  bool interrupted() const { return cancelFlag().load(); }
  /// Error(Interrupted) "<tool> interrupted" when a signal arrived.
  void throwIfInterrupted() const;

  // ------------------------------------------------------------------ settings
  const ToolSettings& settings() const { return m_settings; }
  /// Whether to draw progress bars (not quiet; Progress itself also needs a terminal).
  bool showProgress() const { return !m_settings.quiet; }
  /// The worker threads the run may use (the --threads cap, or the machine's cores).
  int threads() const;

  // ------------------------------------------------------------------ timings
  /// Adds the wall-clock seconds of its lifetime to the phase `name`.
  class Phase {
  public:
    Phase(ToolRun& run, std::string name);
    ~Phase();
    Phase(const Phase&) = delete;
    Phase& operator=(const Phase&) = delete;

  private:
    ToolRun& m_run;
    std::string m_name;
    std::chrono::steady_clock::time_point m_start;
  };
  [[nodiscard]] Phase phase(std::string name) { return Phase(*this, std::move(name)); }
  /// Adds seconds measured elsewhere (e.g. inside a library's stats) to phase `name`.
  void addSeconds(const std::string& name, double seconds);
  /// Seconds since the run started.
  double elapsed() const;

  // ------------------------------------------------------------------ report
  /// The tool's fields, in insertion order. finish() adds the common ones.
  nlohmann::ordered_json& report() { return m_report; }
  /// A warning: logged, and listed in the report.
  void warn(const std::string& message);
  /// A warning the library already logged (e.g. bake::BakeResult::warnings): report only.
  void recordWarning(const std::string& message) { m_warnings.push_back(message); }
  /// Completes the report (tool, version, threads, seconds, peak_memory_mib, warnings),
  /// writes it where --json said and commits the run's outputs together (outputs()). Call
  /// once, after the outputs are written. Returns the completed report (also without --json:
  /// `glint bake --batch` lists its jobs' reports).
  nlohmann::ordered_json finish();
  /// The run's outputs, staged until finish() (core/file.h).
  OutputSet& outputs();
  /// The report as finish() would write it now (a failed job's, in a batch report).
  nlohmann::ordered_json completedReport() const;

  /// The process's peak resident set size so far, in MiB.
  static double peakMemoryMiB();
  /// Records the job's estimated peak memory (memory_estimate_mib in the report) and throws
  /// Error(Usage) naming `what` ("a 16384² bake") and both sizes when the estimate is over
  /// --max-memory or, without it, over the machine's physical memory (--max-memory above it
  /// overrides). Call before the big allocations.
  void checkMemory(double estimateMiB, const std::string& what);
  /// glint's version, as every report gives it ("0.1.0").
  static const char* version();
  /// This machine's physical memory in MiB (GLINT_PHYSICAL_MEMORY_MIB overrides it, for tests).
  static double physicalMemoryMiB();

private:
  struct Impl;
  std::string m_tool;
  ToolSettings m_settings;
  std::unique_ptr<Impl> m_impl;
  std::chrono::steady_clock::time_point m_start;
  double m_maxMemoryMiB = 0.0;  ///< parsed --max-memory; 0: no limit
  nlohmann::ordered_json m_report = nlohmann::ordered_json::object();
  std::vector<std::pair<std::string, double>> m_phases;
  std::vector<std::string> m_warnings;
};

}  // namespace glint
