// bench shadows — what each shadow technique costs, as a ratio to the same scene drawn
// without shadows, at about 10k, 100k and 1M scene triangles (a field of 64 spheres
// over a ground, bench world of shadows/world.h). Also: stencil fill (fragments
// the volumes rasterize per stencil pass, GL_SAMPLES_PASSED) and the CPU time of
// silhouette extraction against GPU extrusion, which has none but draws every face
// and a degenerate quad per edge.
//
// Frame times are wall times including glFinish (median): a software rasterizer's GPU
// timer queries miss most of its work, and the wall time is what an application waits for.
#include "glint/bench/bench.h"
#include "glint/gl/render_target.h"
#include "glint/render/shadows/planar.h"
#include "glint/render/shadows/shadow_map.h"
#include "glint/render/shadows/stencil_shadows.h"
#include "glint/render/state.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <vector>

namespace glint::bench {
namespace {

namespace sh = render::shadows;
constexpr ivec2 kSize{640, 360};

void runShadows(Recorder& recorder) {
  for (std::size_t triangles : {10'000u, 100'000u, 1'000'000u}) {
    if (quick() && triangles > 10'000u) break;
    const glint::shadows::World world = glint::shadows::makeBenchWorld(triangles);
    const std::string group = fmt::format("{}k tris", (world.triangleCount() + 500) / 1000);
    const int repeats = quick() ? 2 : triangles >= 1'000'000 ? 3 : 7;
    gl::RenderTarget target(kSize, GL_RGBA8, "bench-shadows");
    const float aspect = float(kSize.x) / float(kSize.y);
    const glint::Camera camera =
        glint::Camera::lookAt({0.0f, 9.0f, 12.0f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 45.0f, aspect, 0.5f, 80.0f);
    glint::Camera infinite = camera;
    infinite.projection = sh::infiniteFarProjection(camera.projection);

    sh::WorldRenderer plain(world);
    recorder.record({.group = group,
                     .name = "no shadows",
                     .value = wallMs(
                         [&] {
                           target.target().bind();
                           render::PipelineState{.depthTest = true}.apply();
                           // The techniques' clear (render/shadows/*): same buffers, same colour.
                           render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT,
                                         vec4(0.52f, 0.6f, 0.7f, 1.0f));
                           plain.draw(world, camera, sh::LightTerms::Full);
                         },
                         repeats),
                     .unit = "ms",
                     .note = fmt::format("{} triangles", world.triangleCount())});

    struct Volume {
      const char* name;
      sh::StencilShadowOptions options;
      bool rebuild;  // a moving light: CPU volumes rebuilt every frame
    };
    const Volume volumes[] = {
        {"z-pass", {.counting = sh::StencilCounting::ZPass}, false},
        {"z-fail", {.counting = sh::StencilCounting::ZFail}, false},
        {"z-fail two-sided", {.counting = sh::StencilCounting::TwoSidedZFail}, false},
        {"z-fail rebuilt/frame", {.counting = sh::StencilCounting::TwoSidedZFail}, true},
        {"z-fail GPU extrusion",
         {.counting = sh::StencilCounting::TwoSidedZFail, .construction = sh::VolumeConstruction::Gpu},
         false},
    };
    for (const Volume& v : volumes) {
      const auto setupStart = std::chrono::steady_clock::now();
      sh::StencilShadows shadows(world, v.options);
      const double setupMs =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - setupStart).count();
      const glint::Camera& cam = sh::StencilShadows::needsInfiniteFar(v.options) ? infinite : camera;
      const double ms = wallMs(
          [&] {
            if (v.rebuild) shadows.invalidate();
            shadows.render(world, cam, target.target());
          },
          repeats);
      recorder.record({.group = group, .name = v.name, .value = ms, .unit = "ms", .ratioTo = "no shadows",
                       .note = shadows.describe()});
      if (v.rebuild) {
        recorder.record({.group = group, .name = "CPU volume build", .value = shadows.stats().buildMs, .unit = "ms",
                         .note = fmt::format("silhouettes + caps of {} casters and upload, per light move (edge maps "
                                             "built once: {:.0f} ms)",
                                             shadows.stats().casters, setupMs)});
      }
      if (v.options.construction == sh::VolumeConstruction::Gpu) {
        recorder.record({.group = group, .name = "GPU extrusion build", .value = 0.0, .unit = "ms",
                         .note = fmt::format("no per-frame CPU work; static mesh of {} triangles built once in "
                                             "{:.0f} ms", shadows.stats().volumeTriangles, setupMs)});
      }
      if (!v.rebuild) {
        target.target().bind();
        recorder.record({.group = group, .name = std::string(v.name) + " fill",
                         .value = double(shadows.measureFill(world, cam)) / 1e6, .unit = "Mfrag",
                         .note = fmt::format("volume fragments per stencil pass, {}x{} (GL_SAMPLES_PASSED)", kSize.x,
                                             kSize.y)});
      }
    }

    for (int pcf : {0, 1}) {
      sh::ShadowMap map(world, {.pcfRadius = pcf});
      recorder.record({.group = group, .name = pcf ? "shadow map PCF 3x3" : "shadow map 1 tap",
                       .value = wallMs([&] { map.render(world, camera, target.target()); }, repeats), .unit = "ms",
                       .ratioTo = "no shadows", .note = map.describe()});
    }
    sh::PlanarShadow planar(world, {});
    recorder.record({.group = group, .name = "planar texture",
                     .value = wallMs([&] { planar.render(world, camera, target.target()); }, repeats), .unit = "ms",
                     .ratioTo = "no shadows", .note = planar.describe()});
  }
}

}  // namespace

/// The "shadows" suite (bench/bench.cpp lists it).
void runShadowsSuite(Recorder& r) { runShadows(r); }

}  // namespace glint::bench
