#pragma once
// glint/core/progress.h — a terminal progress bar for long work.
//
// Draws `label [#####.....] 42/100  3.1 s  ETA 4 s` on stderr, redrawn in place, only
// when stderr is a terminal and logging is at Info or below; otherwise silent,
// so logs and CI output stay clean. advance() is thread-safe and cheap (an
// atomic add; redraws are rate-limited), so it may be called from TBB workers.
//
// A total of 0 means unknown (a live source): the count is drawn without a bar.
//
// A program that shows progress its own way (the Python module's callback, a GUI) sets a
// listener: every bar of the process then reports to it, at the same rate as it redraws
// (~10 times a second, and once when it finishes), terminal or not.
//
/// ```cpp
/// #include <vector>
/// const std::vector<int> variants(40);
/// glint::Progress progress("gallery", variants.size());
/// for (int variant : variants) {
///   progress.setDetail(std::to_string(variant));
///   progress.advance();
/// }
/// progress.finish();  // also called by the destructor
/// ```

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include <functional>
#include <string_view>

namespace glint {

/// Hears every Progress of the process: its label, steps done and total (0: unknown).
/// Called on the thread that advanced the bar, so it must be quick and thread-safe.
using ProgressListener = std::function<void(std::string_view label, std::uint64_t done, std::uint64_t total)>;
/// Sets the process's listener (an empty function removes it). Bars made before keep the
/// listener they were made with.
void setProgressListener(ProgressListener listener);

/// The estimated time left, as the bar shows it after the elapsed time: "ETA 42 s",
/// "ETA 3:05" (minutes), "ETA 1:02:05" (hours); empty while nothing is done yet, when the
/// total is unknown (0) or when the work is complete. A linear estimate: elapsed / done
/// steps × the steps left.
std::string etaText(std::uint64_t done, std::uint64_t total, double elapsedSeconds);

class Progress {
public:
  Progress(std::string label, std::uint64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::uint64_t steps = 1);
  /// Sets the text shown after the counter (e.g. the item being worked on).
  void setDetail(std::string detail);
  /// Draws the final state and ends the line. Idempotent.
  void finish();

  std::uint64_t done() const { return m_done.load(); }
  bool enabled() const { return m_enabled; }

private:
  void draw(bool force);

  std::string m_label;
  std::string m_detail;
  std::uint64_t m_total;
  std::atomic<std::uint64_t> m_done{0};
  std::atomic<std::int64_t> m_lastDrawMs{-1000};
  std::chrono::steady_clock::time_point m_start;
  std::mutex m_drawMutex;
  std::shared_ptr<const ProgressListener> m_listener;  ///< the process's listener when the bar was made
  bool m_enabled;
  bool m_finished = false;
};

}  // namespace glint
