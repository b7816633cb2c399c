// The GPU wave simulation (render/water/wave_simulation.h) against the CPU reference
// (sim/water.h): equal within float tolerance over 100 steps, energy decay, stability, and
// the deterministic time-driven stepping the scenes rely on.
#include "support/gl_test.h"

#include "glint/core/error.h"
#include "glint/render/water/wave_simulation.h"
#include "glint/sim/water.h"

#include <algorithm>
#include <cmath>

using namespace glint;
using glint::testing::GlTest;

namespace {
struct Difference {
  float maxHeight = 0, maxVelocity = 0, maxAbsHeight = 0;
};
Difference compare(const sim::WaveField& gpu, const sim::WaveField& cpu) {
  Difference d;
  for (std::size_t i = 0; i < cpu.data().size(); ++i) {
    d.maxHeight = std::max(d.maxHeight, std::abs(gpu.data()[i].x - cpu.data()[i].x));
    d.maxVelocity = std::max(d.maxVelocity, std::abs(gpu.data()[i].y - cpu.data()[i].y));
    d.maxAbsHeight = std::max(d.maxAbsHeight, std::abs(cpu.data()[i].x));
  }
  return d;
}
}  // namespace

TEST_F(GlTest, WaveGpuMatchesCpuOver100Steps) {
  // Clamped and wrapped edges, an odd size, drops (rain every 10 steps) falling during the run.
  for (const sim::WaveParams& params : {sim::WaveParams{}, sim::WaveParams{.springConstant = 900.0f, .damping = 1.0f, .wrap = true}}) {
    const sim::RainOptions rain{.interval = 10 * params.timeStep, .radius = 2.5f};
    render::water::WaveSimulation gpu({67, 45}, params, rain);
    sim::WaveField cpu({67, 45});
    for (int i = 0; i < 100; ++i) gpu.step();
    sim::simulate(cpu, 0, 100, params, rain);
    EXPECT_EQ(gpu.steps(), 100);
    const Difference d = compare(gpu.download(), cpu);
    // Float tolerance: both evaluate the same expression in IEEE single precision (`precise`
    // forbids fused multiply-adds); exp() in the drop shape may differ by an ulp or two, and
    // 100 steps of a stable linear scheme do not amplify that.
    EXPECT_GT(d.maxAbsHeight, 0.05f);
    EXPECT_LT(d.maxHeight, 1e-5f * std::max(1.0f, d.maxAbsHeight)) << "wrap " << params.wrap;
    EXPECT_LT(d.maxVelocity, 1e-3f) << "wrap " << params.wrap;
  }
}

TEST_F(GlTest, WaveGpuUploadDownloadRoundTrip) {
  sim::WaveField field({9, 7});
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) field.at(x, y) = {float(x) * 0.1f, float(y) * -0.2f};
  render::water::WaveSimulation gpu({9, 7});
  gpu.upload(field);
  EXPECT_EQ(gpu.download().data(), field.data());
  EXPECT_THROW(gpu.upload(sim::WaveField({3, 3})), Error);
}

TEST_F(GlTest, WaveGpuEnergyDecaysWithDamping) {
  const sim::WaveParams params{.damping = 0.5f};
  render::water::WaveSimulation gpu({64, 64}, params, {.interval = 0.0f});
  gpu.addDrop({.centre = {32, 32}, .radius = 4, .amplitude = 1});
  const double e0 = gpu.download().energy(params);
  double previous = e0;
  for (int window = 0; window < 4; ++window) {
    for (int i = 0; i < 60; ++i) gpu.step();  // 0.5 s
    const double e = gpu.download().energy(params);
    EXPECT_LT(e, previous) << "window " << window;
    previous = e;
  }
  EXPECT_NEAR(previous / e0, std::exp(-0.5 * 2.0), 0.2 * std::exp(-1.0));  // exp(−damping·t), t = 2 s
}

TEST_F(GlTest, WaveGpuStableOverTheDocumentedRange) {
  // Corners of the documented range: Δt at 95% of the limit, no damping, soft and stiff springs.
  for (float k : {10.0f, 3600.0f, 40000.0f}) {
    sim::WaveParams params{.springConstant = k, .restoringConstant = 4.0f, .damping = 0.0f};
    params.timeStep = 0.95f * sim::stabilityLimit(params);
    render::water::WaveSimulation gpu({48, 48}, params, {.interval = 0.0f});
    gpu.addDrop({.centre = {24, 24}, .radius = 1.0f, .amplitude = 1.0f});  // narrow: excites stiff modes
    const double e0 = gpu.download().energy(params);
    for (int i = 0; i < 2000; ++i) gpu.step();
    const double e = gpu.download().energy(params);
    EXPECT_TRUE(std::isfinite(e)) << "k " << k;
    EXPECT_LT(e, 1.5 * e0) << "k " << k;
    EXPECT_GT(e, 0.5 * e0) << "k " << k;
  }
}

TEST_F(GlTest, WaveGpuAdvanceToIsDeterministic) {
  // Reaching t = 0.5 s in one call or in uneven "frames" gives the same state.
  render::water::WaveSimulation a({32, 32}, {}, {.interval = 0.1f}), b({32, 32}, {}, {.interval = 0.1f});
  a.advanceTo(0.5);
  for (double t : {0.013, 0.2, 0.21, 0.37, 0.5}) b.advanceTo(t);
  EXPECT_EQ(a.steps(), 60);
  EXPECT_EQ(b.steps(), 60);
  EXPECT_EQ(a.download().data(), b.download().data());
  // Going back in time restarts from rest and re-simulates.
  b.advanceTo(0.25);
  a.reset();
  a.advanceTo(0.25);
  EXPECT_EQ(a.download().data(), b.download().data());
}

TEST_F(GlTest, WaveGpuTimeStepChangesKeepTheWaterMoving) {
  // The viewer may change Δt while the water moves: the time reached is kept, later steps use
  // the new Δt, nothing restarts.
  render::water::WaveSimulation w({32, 32}, {}, {.interval = 0.1f});
  w.advanceTo(0.5);
  EXPECT_EQ(w.steps(), 60);
  const sim::WaveField before = w.download();
  w.params().timeStep = 1.0f / 240.0f;
  w.advanceTo(0.75);
  EXPECT_EQ(w.steps(), 60 + 60);
  EXPECT_NEAR(w.time(), 0.75, 1e-6);
  EXPECT_NE(w.download().data(), before.data());
}

TEST_F(GlTest, WaveGpuRejectsUnstableParameters) {
  EXPECT_THROW(render::water::WaveSimulation({8, 8}, {.timeStep = 0.05f}), Error);
  EXPECT_THROW(render::water::WaveSimulation({0, 8}), Error);
}
