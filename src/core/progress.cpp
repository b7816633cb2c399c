#include "glint/core/progress.h"

#include "glint/core/log.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glint {

namespace {
std::mutex g_listenerMutex;
std::shared_ptr<const ProgressListener> g_listener;

std::shared_ptr<const ProgressListener> currentListener() {
  std::lock_guard lock(g_listenerMutex);
  return g_listener;
}
}  // namespace

void setProgressListener(ProgressListener listener) {
  std::lock_guard lock(g_listenerMutex);
  g_listener = listener ? std::make_shared<const ProgressListener>(std::move(listener)) : nullptr;
}

Progress::Progress(std::string label, std::uint64_t total)
    : m_label(std::move(label)),
      m_total(total),
      m_start(std::chrono::steady_clock::now()),
      m_listener(currentListener()),
      m_enabled(isatty(STDERR_FILENO) && log::level() <= log::Level::Info) {
  draw(true);
}

Progress::~Progress() { finish(); }

void Progress::advance(std::uint64_t steps) {
  m_done.fetch_add(steps);
  draw(false);
}

void Progress::setDetail(std::string detail) {
  {
    std::lock_guard lock(m_drawMutex);
    m_detail = std::move(detail);
  }
  draw(true);
}

void Progress::finish() {
  if (m_finished) return;
  draw(true);
  m_finished = true;
  if (m_enabled) std::fputc('\n', stderr);
}

std::string etaText(std::uint64_t done, std::uint64_t total, double elapsedSeconds) {
  if (total == 0 || done == 0 || done >= total || !(elapsedSeconds >= 0.0)) return {};
  const double left = elapsedSeconds / double(done) * double(total - done);
  const auto seconds = static_cast<std::int64_t>(std::ceil(left));
  if (seconds < 60) return fmt::format("ETA {} s", seconds);
  if (seconds < 3600) return fmt::format("ETA {}:{:02}", seconds / 60, seconds % 60);
  return fmt::format("ETA {}:{:02}:{:02}", seconds / 3600, seconds / 60 % 60, seconds % 60);
}

void Progress::draw(bool force) {
  if ((!m_enabled && !m_listener) || m_finished) return;
  using namespace std::chrono;
  const auto elapsed = duration<double>(steady_clock::now() - m_start).count();
  const auto ms = static_cast<std::int64_t>(elapsed * 1000.0);
  // Rate-limit redraws to ~10 per second; the atomic exchange lets exactly one
  // thread draw when several advance at once.
  auto last = m_lastDrawMs.load();
  if (!force && ms - last < 100) return;
  if (!m_lastDrawMs.compare_exchange_strong(last, ms) && !force) return;
  std::unique_lock lock(m_drawMutex, std::try_to_lock);
  if (!lock.owns_lock()) return;
  if (m_listener) (*m_listener)(m_label, std::min(m_done.load(), m_total ? m_total : m_done.load()), m_total);
  if (!m_enabled) return;

  constexpr int kWidth = 30;
  const auto done = std::min(m_done.load(), m_total);
  const double fraction = m_total ? double(done) / double(m_total) : 1.0;
  const int filled = static_cast<int>(fraction * kWidth);
  std::string bar(filled, '#');
  bar.append(kWidth - filled, '.');
  // An unknown total (a camera, an endless generator): the count alone.
  const std::string eta = etaText(done, m_total, elapsed);
  auto line = m_total ? fmt::format("\r{} [{}] {}/{} {:5.1f} s{}", m_label, bar, done, m_total, elapsed,
                                    eta.empty() ? "" : "  " + eta)
                      : fmt::format("\r{} {} {:5.1f} s", m_label, m_done.load(), elapsed);
  if (!m_detail.empty()) line += "  " + m_detail;
  // Pad so a shorter line fully overwrites a longer previous one.
  std::fprintf(stderr, "%-100s", line.c_str());
  std::fflush(stderr);
}

}  // namespace glint
