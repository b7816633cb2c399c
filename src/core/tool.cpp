#include "glint/core/tool.h"

#include "glint/core/json.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/text.h"

#include <sys/resource.h>
#include <unistd.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>

#ifndef GLINT_VERSION
#error "GLINT_VERSION must be defined by the build"
#endif

namespace glint {

namespace {
// The flag the handlers set. Signal handlers may only touch lock-free atomics.
std::atomic<bool> g_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void onInterrupt(int signal) {
  g_cancel.store(true);
  // A second signal is the user insisting: the default action (terminate) at once.
  std::signal(signal, SIG_DFL);
}
}  // namespace

struct ToolRun::Impl {
  OutputSet outputs;  ///< opened with the run: its outputs stage here until finish()
  void (*previousInt)(int) = SIG_DFL;
  void (*previousTerm)(int) = SIG_DFL;
  std::unique_ptr<tbb::global_control> threadLimit;
  log::Level previousLevel = log::Level::Info;
};

ToolRun::ToolRun(std::string tool, const ToolSettings& settings)
    : m_tool(std::move(tool)), m_settings(settings), m_impl(std::make_unique<Impl>()),
      m_start(std::chrono::steady_clock::now()) {
  if (settings.threads < 0) fail(ErrorKind::Usage, "--threads must be positive, got {}", settings.threads);
  if (!settings.maxMemory.empty()) m_maxMemoryMiB = parseMemorySize(settings.maxMemory, "--max-memory");
  if (settings.threads > 0) {
    m_impl->threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                std::size_t(settings.threads));
  }
  m_impl->previousLevel = log::level();
  if (settings.quiet && log::level() < log::Level::Warn) log::setLevel(log::Level::Warn);
  if (settings.cancel) return;  // the caller's flag, the caller's signals
  g_cancel.store(false);
  m_impl->previousInt = std::signal(SIGINT, onInterrupt);
  m_impl->previousTerm = std::signal(SIGTERM, onInterrupt);
}

ToolRun::~ToolRun() {
  if (!m_settings.cancel) {
    std::signal(SIGINT, m_impl->previousInt);
    std::signal(SIGTERM, m_impl->previousTerm);
  }
  log::setLevel(m_impl->previousLevel);
}

const std::atomic<bool>& ToolRun::cancelFlag() const { return m_settings.cancel ? *m_settings.cancel : g_cancel; }

void ToolRun::throwIfInterrupted() const {
  if (interrupted()) fail(ErrorKind::Interrupted, "{} interrupted; no output was written", m_tool);
}

int ToolRun::threads() const {
  return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

ToolRun::Phase::Phase(ToolRun& run, std::string name)
    : m_run(run), m_name(std::move(name)), m_start(std::chrono::steady_clock::now()) {}

ToolRun::Phase::~Phase() {
  m_run.addSeconds(m_name, std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count());
}

void ToolRun::addSeconds(const std::string& name, double seconds) {
  for (auto& [phase, total] : m_phases) {
    if (phase == name) {
      total += seconds;
      return;
    }
  }
  m_phases.emplace_back(name, seconds);
}

double ToolRun::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

void ToolRun::warn(const std::string& message) {
  log::warn("{}", message);
  m_warnings.push_back(message);
}

const char* ToolRun::version() { return GLINT_VERSION; }

double ToolRun::physicalMemoryMiB() {
  if (const char* fake = std::getenv("GLINT_PHYSICAL_MEMORY_MIB")) {  // tests: a machine of another size
    try {
      return parseMemorySize(fake, "GLINT_PHYSICAL_MEMORY_MIB");
    } catch (const Error&) {
    }
  }
  return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)) / (1024.0 * 1024.0);
}

void ToolRun::checkMemory(double estimateMiB, const std::string& what) {
  m_report["memory_estimate_mib"] = std::round(estimateMiB);
  const auto size = [](double mib) {
    return mib >= 10240.0 ? fmt::format("{:.1f} GiB", mib / 1024.0)
           : mib >= 1.0   ? fmt::format("{:.0f} MiB", mib)
                          : fmt::format("{:.0f} KiB", mib * 1024.0);
  };
  if (m_maxMemoryMiB > 0.0 && estimateMiB > m_maxMemoryMiB) {
    fail(ErrorKind::Usage, "{}: {} needs about {}, more than --max-memory {} ({}) allows", m_tool, what,
         size(estimateMiB), m_settings.maxMemory, size(m_maxMemoryMiB));
  }
  // Without --max-memory, the machine itself is the limit: a job it cannot hold is refused
  // now rather than killed (or swapping) hours in. --max-memory above it overrides.
  const double physical = physicalMemoryMiB();
  if (m_maxMemoryMiB <= 0.0 && physical > 0.0 && estimateMiB > physical) {
    fail(ErrorKind::Usage, "{}: {} needs about {}, more than this machine's {} of memory; a smaller job, or "
         "--max-memory {:.0f} to try anyway", m_tool, what, size(estimateMiB), size(physical), std::ceil(estimateMiB));
  }
}

double ToolRun::peakMemoryMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

nlohmann::ordered_json ToolRun::completedReport() const {
  nlohmann::ordered_json out;
  out["tool"] = m_tool;
  out["version"] = GLINT_VERSION;
  out["threads"] = threads();
  for (auto& [key, value] : m_report.items()) out[key] = value;
  nlohmann::ordered_json seconds = nlohmann::ordered_json::object();
  for (const auto& [phase, total] : m_phases) seconds[phase] = total;
  seconds["total"] = elapsed();
  out["seconds"] = seconds;
  out["peak_memory_mib"] = peakMemoryMiB();
  out["warnings"] = m_warnings;
  return out;
}

OutputSet& ToolRun::outputs() { return m_impl->outputs; }

nlohmann::ordered_json ToolRun::finish() {
  nlohmann::ordered_json out = completedReport();
  // Non-finite numbers have no JSON spelling: nlohmann writes them as null.
  const std::string text = jsonText(out);
  if (!m_settings.json.empty() && m_settings.json != "-") writeTextAtomically(m_settings.json, text);
  m_impl->outputs.commit();  // every output of the run, the report included, or none
  if (m_settings.json == "-") {
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
  }
  return out;
}

}  // namespace glint
