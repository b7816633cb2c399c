#include "glint/bench/bench.h"


#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include <cmath>
#include <ctime>
#include <fstream>
#include <initializer_list>
#include <limits>

namespace glint::bench {

// The suites, one row each: adding a suite is its file, bench/<name>.cpp defining
// run<Name>Suite(Recorder&), and a row here (and the file in bench/CMakeLists.txt).
void runBakeSuite(Recorder& r);
void runCutSuite(Recorder& r);
void runPipeDreamSuite(Recorder& r);
void runRttSuite(Recorder& r);
void runShadowsSuite(Recorder& r);
void runWaterSuite(Recorder& r);
void runPostSuite(Recorder& r);

Suites& Suites::builtin() {
  static Suites suites = [] {
    Suites s;
    for (Suite suite : std::initializer_list<Suite>{
        {.name = "bake",
         .description = "normal mapper: vs Blender Cycles, 2048² 36 spp on 1M triangles, vs plain Embree, scaling, mesh loading",
         .run = runBakeSuite},
        {.name = "cut",
         .description = "shadow cutter: 550k-triangle Pipe Dream stand-in, growth 10k → 1M, pairs/s",
         .run = runCutSuite},
        {.name = "pipedream",
         .description = "the Pipe Dream frame: cut static + dynamic volumes vs full-scene volumes (WWDC 2003 session 212: 15x), "
                         "triangles, stencil fill and overdraw per frame",
         .run = runPipeDreamSuite},
        {.name = "rtt",
         .description = "render to texture: copy from the window vs framebuffer object, 256² to 2048²",
         .run = runRttSuite},
        {.name = "shadows",
         .description = "shadow techniques vs no shadows at 10k/100k/1M triangles; stencil fill; CPU volume "
                         "build vs GPU extrusion",
         .run = runShadowsSuite},
        {.name = "water",
         .description = "wave simulation step and height → normal pass, GPU vs CPU reference, 256² to 4096²",
         .run = runWaterSuite},
        {.name = "post",
         .description = "post effects per frame at 640×480, 1080p and 4K (GPU and CPU backend) vs OpenCV / FFTW; "
                         "glint post end to end vs FFmpeg's nearest filters at 640×480 and 1080p H.264",
         .run = runPostSuite}}) {
      s.add(std::move(suite));
    }
    return s;
  }();
  return suites;
}

bool quick() {
  const char* v = std::getenv("GLINT_BENCH_QUICK");
  return v && *v && std::string_view(v) != "0";
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
  return values[values.size() / 2];
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double loadAverage() {
  std::ifstream in("/proc/loadavg");
  double load = 0.0;
  in >> load;
  return load;
}

double wallMs(const std::function<void()>& work, int repeats) {
  work();
  glFinish();
  std::vector<double> times;
  for (int i = 0; i < std::max(repeats, 1); ++i) {
    const auto start = std::chrono::steady_clock::now();
    work();
    glFinish();
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return median(std::move(times));
}

void Recorder::record(Measurement m) { m_rows.push_back(std::move(m)); }

double Recorder::find(const std::string& group, const std::string& name) const {
  for (const auto& r : m_rows)
    if (r.group == group && r.name == name) return r.value;
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {
double ratioOf(const Recorder& rec, const Measurement& m) {
  if (m.ratioTo.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double peer = rec.find(m.group, m.ratioTo);
  return peer > 0 ? m.value / peer : std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

std::string formatTable(const std::string& suite, const Recorder& rec) {
  std::string out = fmt::format("{}\n{:<18} {:<28} {:>12} {:<8} {:>12}  {}\n", suite, "group", "measurement", "value",
                                "unit", "ratio", "note");
  for (const auto& m : rec.measurements()) {
    const double ratio = ratioOf(rec, m);
    out += fmt::format("{:<18} {:<28} {:>12.4g} {:<8} {:>12}  {}\n", m.group, m.name, m.value, m.unit,
                       std::isnan(ratio) ? std::string() : fmt::format("{:.3f}× {}", ratio, m.ratioTo), m.note);
  }
  return out;
}

nlohmann::ordered_json toJson(const std::string& suite, const Recorder& rec) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const auto& m : rec.measurements()) {
    rows.push_back({{"group", m.group},
                    {"name", m.name},
                    {"value", number(m.value)},
                    {"unit", m.unit},
                    {"ratio_to", m.ratioTo},
                    {"ratio", number(ratioOf(rec, m))},
                    {"note", m.note}});
  }
  return {{"suite", suite}, {"rows", rows}};
}

}  // namespace glint::bench
