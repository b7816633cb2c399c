#include "glint/core/log.h"

#include "glint/core/text.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <utility>

namespace glint::log {
namespace {
std::atomic<Level> g_level{Level::Info};
std::mutex g_mutex;
std::vector<WarningCapture*> g_captures;  ///< guarded by g_mutex
}  // namespace

void setLevel(Level l) { g_level = l; }
Level level() { return g_level; }

void write(Level l, std::string_view message) {
  static constexpr const char* kPrefix[] = {"debug: ", "", "warning: ", "error: ", ""};
  const std::string line = escapedLine(message);  // one line, whatever a file name holds
  std::lock_guard lock(g_mutex);
  std::fprintf(stderr, "%s%.*s\n", kPrefix[static_cast<int>(l)], static_cast<int>(line.size()), line.data());
  if (l == Level::Warn)
    for (WarningCapture* c : g_captures) c->m_warnings.emplace_back(message);
}

WarningCapture::WarningCapture() {
  std::lock_guard lock(g_mutex);
  g_captures.push_back(this);
}

WarningCapture::~WarningCapture() {
  std::lock_guard lock(g_mutex);
  g_captures.erase(std::find(g_captures.begin(), g_captures.end(), this));
}

std::vector<std::string> WarningCapture::take() {
  std::lock_guard lock(g_mutex);
  return std::exchange(m_warnings, {});
}

}  // namespace glint::log
