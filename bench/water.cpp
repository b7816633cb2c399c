// bench water — the VGP353 lecture's wave simulation step and height → normal pass on the GPU at
// 256², 1024² and 4096², each against its CPU reference (sim::WaveField::step and
// heightToNormalMap) measured in the same run: the peer the ratios are taken to.
#include "glint/bench/bench.h"
#include "glint/gl/timer.h"
#include "glint/image/normalmap.h"
#include "glint/render/bump/height_to_normal.h"
#include "glint/render/water/wave_simulation.h"
#include "glint/sim/water.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

namespace glint::bench {
namespace {

void runWater(Recorder& recorder) {
  for (int size : {256, 1024, 4096}) {
    if (quick() && size > 256) break;
    const std::string group = fmt::format("{0}x{0}", size);
    const double texels = double(size) * double(size);
    const int repeats = quick() ? 2 : size >= 4096 ? 3 : size >= 1024 ? 5 : 15;
    const sim::WaveParams params{};

    // The GPU: a field with waves in it (what a frame steps), and its normal map.
    render::water::WaveSimulation waves({size, size}, params, {.interval = 0.0f});
    for (int i = 0; i < 8; ++i) waves.addDrop({.centre = vec2(float(size) * (0.1f + 0.1f * float(i))), .radius = 5.0f});
    render::bump::HeightToNormalPass normals;
    gl::Texture normalMap(GL_TEXTURE_2D, "bench-normal-map");
    normalMap.storage(GL_RGBA8, size, size);
    const auto stepWork = [&] { waves.step(); };
    const auto normalWork = [&] { normals.run(waves.state(), normalMap, {.scale = 8.0f}); };
    const double stepGpu = gl::GpuTimer::measureMs(stepWork, repeats, 1);
    const double stepWall = wallMs(stepWork, repeats);
    const double normalGpu = gl::GpuTimer::measureMs(normalWork, repeats, 1);
    const double normalWall = wallMs(normalWork, repeats);

    // The CPU references, on the same data.
    sim::WaveField field = waves.download();
    const double stepCpu = wallMs([&] { field.step(params); }, std::max(1, repeats / 2));
    Image heights(size, size, 1, PixelType::F32);
    auto h = heights.pixels<float>();
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = field.data()[i].x;
    const double normalCpu = wallMs([&] { (void)heightToNormalMap(heights, {.scale = 8.0f}); }, std::max(1, repeats / 2));

    const auto mtex = [&](double ms) { return fmt::format("{:.0f} Mtexels/s", texels / (ms * 1e3)); };
    recorder.record({.group = group, .name = "step cpu", .value = stepCpu, .unit = "ms", .note = "sim::WaveField::step, one core"});
    recorder.record({.group = group, .name = "step wall", .value = stepWall, .unit = "ms", .ratioTo = "step cpu",
                     .note = "one GPU step incl. glFinish, " + mtex(stepWall)});
    recorder.record({.group = group, .name = "step gpu", .value = stepGpu, .unit = "ms", .ratioTo = "step cpu",
                     .note = "GL_TIME_ELAPSED"});
    recorder.record({.group = group, .name = "normals cpu", .value = normalCpu, .unit = "ms", .note = "heightToNormalMap, one core"});
    recorder.record({.group = group, .name = "normals wall", .value = normalWall, .unit = "ms", .ratioTo = "normals cpu",
                     .note = "full-screen pass incl. glFinish, " + mtex(normalWall)});
    recorder.record({.group = group, .name = "normals gpu", .value = normalGpu, .unit = "ms", .ratioTo = "normals cpu",
                     .note = "GL_TIME_ELAPSED"});
  }
}

}  // namespace

/// The "water" suite (bench/bench.cpp lists it).
void runWaterSuite(Recorder& r) { runWater(r); }

}  // namespace glint::bench
