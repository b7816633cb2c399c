// glint bench pipedream — WWDC 2003 session 212's claim for Animusic's "Pipe Dream": full-scene stencil
// shadow volumes ran at about 2 frames a second, cutting the static shadows in and keeping
// volumes for the dynamic objects only made it over 30 (issue 14: ≥ 15× faster).
//
// The `pipedream` scene at its default size, polygon count and time, from its default
// camera and from the side (the talk's worst overdraw): WWDC 2003 session 212's method (Mode::Full) against the naive method (every caster's volumes
// per light, the uncut scene, multi-pass), each frame waited for (glFinish), medians over
// rounds that time a few frames of each method in turn, so that the shared machine's load
// falls on all alike; the ratios are the medians of each round's own ratios.
// Also per frame: triangles drawn (scene passes and volumes), stencil fragments (what the
// volumes rasterize, GL_SAMPLES_PASSED, depth test off) and the average volume overdraw
// per pixel; and the static-only frame (no dynamic shadows) as the floor.
// The static frame's framebuffer traffic (issue 37: a datacenter GPU's few ROPs make it
// fill-bound): the bytes each pass writes per pixel (GL_SAMPLES_PASSED × the attachments'
// bytes), and the same frame timed and counted with RGBA16F colour and weights
// (RendererOptions::floatBuffers, the layout before) by a second renderer, alternating.
//
// GLINT_BENCH_PIPEDREAM_SIZE=WxH replaces the size (1920x1080 on a GPU);
// GLINT_BENCH_PIPEDREAM_RUNS=N the alternating rounds (default 7);
// GLINT_BENCH_PIPEDREAM_DETAIL=N the stage's detail (default: the scene's).
#include "glint/bench/bench.h"
#include "glint/core/log.h"
#include "glint/gl/render_target.h"
#include "glint/scenes/pipedream.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <utility>
#include <vector>

namespace glint::bench {
namespace {

namespace rp = render::pipedream;
namespace pd = scenes::pipedream;

int envInt(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::max(1, std::atoi(v)) : fallback;
}

void runView(Recorder& recorder, rp::Renderer& renderer, rp::Renderer& floatRenderer, const gl::RenderTarget& target,
             const glint::pipedream::MachinePose& pose, const glint::Camera& camera, const std::string& group, int runs) {
  const ivec2 size = target.size();
  const auto frame = [&](rp::Mode mode) { renderer.render(pose, camera, target.target(), mode); };

  // Alternating rounds: each times a few frames of every method in turn (a warm-up frame
  // first, then the median), the order reversed every other round, so that the shared
  // machine's swings in speed, which last seconds, fall on all three alike.
  std::vector<double> full, naive, staticOnly, staticFloat;
  const double loadBefore = loadAverage();
  const struct {
    rp::Renderer* renderer;
    rp::Mode mode;
    std::vector<double>* times;
    int frames;
  } methods[] = {{&renderer, rp::Mode::Full, &full, 3},
                 {&renderer, rp::Mode::Naive, &naive, 2},
                 {&renderer, rp::Mode::StaticOnly, &staticOnly, 3},
                 {&floatRenderer, rp::Mode::StaticOnly, &staticFloat, 3}};
  constexpr int kMethods = int(std::size(methods));
  for (int run = 0; run < runs; ++run) {
    for (int k = 0; k < kMethods; ++k) {
      const auto& m = methods[run % 2 == 0 ? k : kMethods - 1 - k];
      m.times->push_back(wallMs([&] { m.renderer->render(pose, camera, target.target(), m.mode); }, m.frames));
    }
    log::info("bench pipedream {}: round {}: full {:.1f} ms, naive {:.1f} ms, static only {:.1f} ms ({:.1f} ms with "
              "RGBA16F buffers)",
              group, run + 1, full.back(), naive.back(), staticOnly.back(), staticFloat.back());
  }
  // Ratios within each round (methods timed seconds apart), then their median.
  std::vector<double> speedups, shadowRatios;
  for (int run = 0; run < runs; ++run) {
    speedups.push_back(naive[std::size_t(run)] / full[std::size_t(run)]);
    shadowRatios.push_back((naive[std::size_t(run)] - staticOnly[std::size_t(run)]) /
                           std::max(full[std::size_t(run)] - staticOnly[std::size_t(run)], 1e-3));
  }
  const double load = 0.5 * (loadBefore + loadAverage());
  const auto runsNote = [&](const std::vector<double>& v) {
    std::string s;
    for (const double x : v) s += fmt::format("{}{:.1f}", s.empty() ? "" : ", ", x);
    return fmt::format("rounds {} ms; load {:.1f}", s, load);
  };

  // What each frame draws and fills.
  struct Cost {
    std::size_t triangles = 0, volumeTriangles = 0;
    std::uint64_t fill = 0;
  };
  const auto costOf = [&](rp::Mode mode) {
    frame(mode);
    Cost c{renderer.stats().sceneTriangles, renderer.stats().volumeTriangles, 0};
    c.fill = renderer.measureVolumeFill();
    return c;
  };
  const Cost fullCost = costOf(rp::Mode::Full), naiveCost = costOf(rp::Mode::Naive);
  const double pixels = double(size.x) * double(size.y);

  const double fullMs = median(full), naiveMs = median(naive), staticMs = median(staticOnly);
  recorder.record({.group = group, .name = "full (the talk's method)", .value = fullMs, .unit = "ms",
                   .note = fmt::format("{:.1f} fps; {}", 1000.0 / fullMs, runsNote(full))});
  recorder.record({.group = group, .name = "naive (all volumes)", .value = naiveMs, .unit = "ms",
                   .ratioTo = "full (the talk's method)",
                   .note = fmt::format("{:.2f} fps; ratio = how many times faster WWDC 2003 session 212's method is; {}",
                                       1000.0 / naiveMs, runsNote(naive))});
  recorder.record({.group = group, .name = "static only (no volumes)", .value = staticMs, .unit = "ms",
                   .ratioTo = "full (the talk's method)",
                   .note = fmt::format("the cut scene alone: what the dynamic shadows cost on top; {}", runsNote(staticOnly))});
  recorder.record({.group = group, .name = "speed-up", .value = median(speedups), .unit = "x",
                   .note = fmt::format("naive / full frame time, median of each round's ratio (ratio of the medians "
                                       "{:.2f}); the talk: 2 fps -> over 30 fps; target >= 15x; on llvmpipe >= 5x",
                                       naiveMs / fullMs)});
  recorder.record({.group = group, .name = "shadows: naive cost / full cost", .value = median(shadowRatios), .unit = "x",
                   .note = fmt::format("(naive - static only) / (full - static only), median of each round's: what the "
                                       "shadows cost each way, {:.1f} against {:.1f} ms in the medians (target >= 15x)",
                                       naiveMs - staticMs, fullMs - staticMs)});
  // The static frame's framebuffer bytes, pass by pass, in both layouts.
  const auto fillOf = [&](rp::Renderer& r) {
    r.render(pose, camera, target.target(), rp::Mode::StaticOnly);
    return r.measureStaticFill(target.target());
  };
  const std::vector<rp::PassFill> fill = fillOf(renderer), fillFloat = fillOf(floatRenderer);
  // The renderer's own framebuffer (colour, weights, depth/stencil): every pass but
  // present(), whose 4 bytes a pixel into the caller's target are the same either way.
  const auto perPixel = [&](const std::vector<rp::PassFill>& passes, bool withPresent) {
    std::uint64_t bytes = 0;
    for (const rp::PassFill& p : passes)
      if (withPresent || p.pass != "present") bytes += p.bytes();
    return double(bytes) / pixels;
  };
  const auto breakdown = [&](const std::vector<rp::PassFill>& passes) {
    std::string s;
    for (const rp::PassFill& p : passes)
      s += fmt::format("{}{} {:.2f} frag/px × {} B", s.empty() ? "" : ", ", p.pass, double(p.fragments) / pixels,
                       p.bytesPerFragment);
    return s;
  };
  recorder.record({.group = group, .name = "static frame: framebuffer bytes/pixel", .value = perPixel(fill, false),
                   .unit = "B",
                   .note = fmt::format("8-bit sRGB colour + a byte a light + depth/stencil, written by clear, scene and "
                                       "balls; {:.1f} with present into the target; {}",
                                       perPixel(fill, true), breakdown(fill))});
  recorder.record({.group = group, .name = "  with RGBA16F colour and weights", .value = perPixel(fillFloat, false),
                   .unit = "B", .ratioTo = "static frame: framebuffer bytes/pixel",
                   .note = fmt::format("the layout before issue 37 (target: ratio >= 2); {:.1f} with present; {}",
                                       perPixel(fillFloat, true), breakdown(fillFloat))});
  recorder.record({.group = group, .name = "static only, RGBA16F buffers", .value = median(staticFloat), .unit = "ms",
                   .ratioTo = "static only (no volumes)",
                   .note = fmt::format("the same frame in the old layout, alternating (ratio >= 1: the new layout is not "
                                       "slower); {}",
                                       runsNote(staticFloat))});
  for (const auto& [name, cost] : {std::pair{"full", fullCost}, std::pair{"naive", naiveCost}}) {
    recorder.record({.group = group, .name = fmt::format("{}: triangles/frame", name),
                     .value = double(cost.triangles + cost.volumeTriangles), .unit = "tris",
                     .note = fmt::format("{} in scene passes + {} shadow-volume triangles", cost.triangles,
                                         cost.volumeTriangles)});
    recorder.record({.group = group, .name = fmt::format("{}: stencil fragments/frame", name),
                     .value = double(cost.fill) / 1e6, .unit = "Mfrag",
                     .note = "fragments the volumes rasterize, every light (GL_SAMPLES_PASSED, depth test off)"});
    recorder.record({.group = group, .name = fmt::format("{}: volume overdraw/pixel", name),
                     .value = double(cost.fill) / pixels, .unit = "x",
                     .note = "stencil fragments / pixels (the talk: \"near a hundred\" for full-scene volumes)"});
  }
}

void runPipeDream(Recorder& recorder) {
  const scenes::SceneDesc& desc = *scenes::Registry::builtin().resolve("pipedream").scene;
  // GLINT_BENCH_QUICK: 320×180, one round, a coarse stage (its cut takes a second).
  ivec2 size = quick() ? ivec2(320, 180) : desc.defaultSize;
  if (const char* s = std::getenv("GLINT_BENCH_PIPEDREAM_SIZE"); s && *s && !quick()) std::sscanf(s, "%dx%d", &size.x, &size.y);
  const int runs = quick() ? 1 : envInt("GLINT_BENCH_PIPEDREAM_RUNS", 7);
  const int detail = quick() ? 2 : envInt("GLINT_BENCH_PIPEDREAM_DETAIL", pd::kDefaultDetail);

  const auto stage = pd::loadStage({.detail = detail});
  rp::Renderer renderer(stage->machine, stage->geometry);
  rp::Renderer floatRenderer(stage->machine, stage->geometry, {.floatBuffers = true});
  gl::RenderTarget target(size, GL_RGBA8, "bench-pipedream");
  const double time = desc.defaultTime;
  const glint::pipedream::MachinePose pose = glint::pipedream::poseAt(stage->machine, stage->score, time);
  // The scene's own camera, and WWDC 2003 session 212's worst case: "if you look at it from the side
  // you get a lot of overdraw".
  for (const int cameraIndex : {0, 3}) {
    const glint::Camera camera = pd::namedCamera(cameraIndex, float(size.x) / float(size.y));
    const std::string group = fmt::format("{}x{} {}", size.x, size.y, pd::namedCameras()[std::size_t(cameraIndex)].name);
    runView(recorder, renderer, floatRenderer, target, pose, camera, group, runs);
  }
  recorder.record({.group = "stage", .name = "cut triangles", .value = double(stage->geometry.mesh.triangleCount()),
                   .unit = "tris",
                   .note = fmt::format("{}; renderer: {}; GL: {}", stage->describe(), renderer.describe(),
                                       reinterpret_cast<const char*>(glGetString(GL_RENDERER)))});
}

}  // namespace

/// The "pipedream" suite (bench/bench.cpp lists it).
void runPipeDreamSuite(Recorder& r) { runPipeDream(r); }

}  // namespace glint::bench
