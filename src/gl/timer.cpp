#include "glint/gl/timer.h"

#include <algorithm>
#include <vector>

namespace glint::gl {

GpuTimer::GpuTimer() {
  for (auto& q : m_queries) q = Query(GL_TIME_ELAPSED, "gpu-timer");
}

void GpuTimer::begin() {
  // A query still in flight in this slot is dropped rather than waited for.
  if (m_pending[m_next] && m_queries[m_next].available()) {
    m_latest = double(m_queries[m_next].result()) * 1e-6;
  }
  m_queries[m_next].begin();
}

void GpuTimer::end() {
  m_queries[m_next].end();
  m_pending[m_next] = true;
  m_next = (m_next + 1) % kRing;
}

double GpuTimer::latestMs() {
  for (int i = 0; i < kRing; ++i) {
    const int slot = (m_next + i) % kRing;
    if (m_pending[slot] && m_queries[slot].available()) {
      m_latest = double(m_queries[slot].result()) * 1e-6;
      m_pending[slot] = false;
    }
  }
  return m_latest;
}

double GpuTimer::measureMs(const std::function<void()>& work, int repeats, int warmup) {
  for (int i = 0; i < warmup; ++i) work();
  Query query(GL_TIME_ELAPSED, "measure");
  std::vector<double> times;
  for (int i = 0; i < std::max(repeats, 1); ++i) {
    query.begin();
    work();
    query.end();
    times.push_back(double(query.result()) * 1e-6);
  }
  std::nth_element(times.begin(), times.begin() + long(times.size() / 2), times.end());
  return times[times.size() / 2];
}

}  // namespace glint::gl
