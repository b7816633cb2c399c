#pragma once
// glint/bench/bench.h — benchmark suites behind `glint bench`.
//
// Speed targets are met here, not in timed tests: each suite measures its
// subject and a peer in the same run (the unshadowed scene, plain Embree, the
// copy-to-texture path, ...) and reports ratios, so numbers stay comparable
// across machines. Results go to a table on stdout and to JSON.
//
// Adding a suite: write bench/<name>.cpp defining run<Name>Suite(Recorder&), add a row
// to the table in Suites::builtin() (bench/bench.cpp) and the file to bench/CMakeLists.txt.
//
/// ```cpp
/// glint::bench::Suites& suites = glint::bench::Suites::builtin();
/// suites.add({.name = "rtt", .description = "render-to-texture: copy vs FBO",
///             .run = [](glint::bench::Recorder& r) {
///               const auto copy = [] { /* draw, then glCopyTexSubImage2D */ };
///               const auto fbo = [] { /* draw into the texture's framebuffer */ };
///               const double copyMs = glint::bench::wallMs(copy, 10), fboMs = glint::bench::wallMs(fbo, 10);
///               r.record({.group = "512x512", .name = "copy", .value = copyMs, .unit = "ms"});
///               r.record({.group = "512x512", .name = "fbo", .value = fboMs, .unit = "ms", .ratioTo = "copy"});
///             }});
/// ```

#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace glint::bench {

struct Measurement {
  std::string group;    ///< rows are grouped, e.g. by size "1024x1024" or triangle count
  std::string name;     ///< what was measured, e.g. "fbo"
  double value = 0;
  std::string unit;     ///< "ms", "Mrays/s", "MiB", ...
  std::string ratioTo;  ///< name of a row in the same group to report value / that value
  std::string note;
};

class Recorder {
public:
  void record(Measurement m);
  const std::vector<Measurement>& measurements() const { return m_rows; }
  /// value of (group, name), or NaN.
  double find(const std::string& group, const std::string& name) const;

private:
  std::vector<Measurement> m_rows;
};

struct Suite {
  std::string name;
  std::string description;
  /// Runs with a current 4.5 core context (headless). Throws glint::Error on failure.
  std::function<void(Recorder&)> run;
};

class Suites {
public:
  static Suites& builtin();
  void add(Suite suite) { m_suites.push_back(std::move(suite)); }
  const std::vector<Suite>& all() const { return m_suites; }

private:
  std::vector<Suite> m_suites;
};

// Measuring, for the suites.

/// The middle value (the upper of the two middle ones for an even count); `values` not empty.
double median(std::vector<double> values);
/// GLINT_BENCH_QUICK=1: each GPU suite (post, pipedream, shadows, water, rtt) measures only
/// a small case, a round or two — to test the benches and scripts/gpu-check's pack on
/// llvmpipe in seconds (tests/gpu_check), not for figures.
bool quick();
/// Seconds of wall clock since `start`.
double secondsSince(std::chrono::steady_clock::time_point start);
/// CPU seconds of this process, all threads: a rate per CPU second does not depend on what
/// else the machine is running.
double processCpuSeconds();
/// The 1-minute load average (/proc/loadavg): how busy the machine was, for the notes.
double loadAverage();

/// Median wall-clock milliseconds of one run of `work`, each run followed by glFinish (what
/// an application waits for), after one untimed warm-up run (shader compilation, uploads).
/// Needs a current GL context. On a software rasterizer this is the meaningful time: its
/// GPU timer queries miss rasterization deferred to the next flush.
double wallMs(const std::function<void()>& work, int repeats);

/// Formats a recorder's rows as an aligned text table (ratios computed).
std::string formatTable(const std::string& suite, const Recorder& recorder);
/// {"suite": ..., "rows": [{"group", "name", "value", "unit", "ratio_to", "ratio", "note"}, ...]}
/// with ratios computed; non-finite values are null.
nlohmann::ordered_json toJson(const std::string& suite, const Recorder& recorder);

}  // namespace glint::bench
