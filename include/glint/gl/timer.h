#pragma once
// glint/gl/timer.h — GPU time of a block of commands (GL_TIME_ELAPSED queries).
//
// A GpuTimer keeps a small ring of queries so reading a result never stalls the
// pipeline in the viewer: begin()/end() around the work each frame, and
// latestMs() returns the most recent finished measurement. For offline
// measurement (gallery, bench) use measureMs(), which waits.

#include "glint/gl/objects.h"

#include <array>
#include <functional>

namespace glint::gl {

class GpuTimer {
public:
  GpuTimer();
  void begin();
  void end();
  /// Milliseconds of the newest finished measurement; negative before the first.
  double latestMs();

  /// Runs `work` `repeats` times after `warmup` untimed runs and returns the median GPU
  /// milliseconds of one run (waits for results).
  static double measureMs(const std::function<void()>& work, int repeats = 5, int warmup = 1);

private:
  static constexpr int kRing = 4;
  std::array<Query, kRing> m_queries;
  std::array<bool, kRing> m_pending{};
  int m_next = 0;
  double m_latest = -1.0;
};

}  // namespace glint::gl
