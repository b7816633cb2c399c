// The spring-network wave model on the CPU (sim/water.h): rest, energy, stability limit,
// the drop schedule. The GPU simulation is compared with this in wave_gpu_test.cpp.
#include "glint/core/error.h"
#include "glint/sim/water.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace glint;
using namespace glint::sim;

namespace {
float maxAbsHeight(const WaveField& f) {
  float m = 0;
  for (vec2 s : f.data()) {
    if (!std::isfinite(s.x)) return INFINITY;  // blown up
    m = std::max(m, std::abs(s.x));
  }
  return m;
}

WaveField splashed(ivec2 size, float radius = 3.0f) {
  WaveField f(size);
  f.addDrop({.centre = vec2(size) * 0.5f, .radius = radius, .amplitude = 1.0f});
  return f;
}
}  // namespace

TEST(WaveCpu, RestStaysAtRest) {
  WaveField f({16, 9});
  for (int i = 0; i < 50; ++i) f.step({});
  EXPECT_EQ(maxAbsHeight(f), 0.0f);
  EXPECT_EQ(f.energy({}), 0.0);
}

TEST(WaveCpu, OneStepByHand) {
  // 3×1 grid, clamped edges; middle texel raised. F_mid = k(h_l + h_r + 2·h_mid − 4·h_mid) − k_r·h_mid
  // (its north and south neighbours are missing: they read as itself).
  const WaveParams p{.mass = 2.0f, .springConstant = 10.0f, .restoringConstant = 1.0f, .damping = 0.5f, .timeStep = 0.1f};
  WaveField f({3, 1});
  f.at(1, 0) = {1.0f, 0.0f};
  f.step(p);
  const float damp = std::exp(-0.5f * 0.1f);
  const float vMid = (0.0f + 0.1f / 2.0f * (10.0f * (0 + 0 + 2 - 4) - 1.0f)) * damp;
  const float vSide = (0.1f / 2.0f * (10.0f * (1.0f + 0 + 0 + 0 - 0) - 0.0f)) * damp;  // side: self×3 + mid − 4·0
  EXPECT_FLOAT_EQ(f.at(1, 0).y, vMid);
  EXPECT_FLOAT_EQ(f.at(1, 0).x, 1.0f + 0.1f * vMid);
  EXPECT_FLOAT_EQ(f.at(0, 0).y, vSide);
  EXPECT_FLOAT_EQ(f.at(2, 0).x, 0.1f * vSide);
}

TEST(WaveCpu, EnergyIsKeptWithoutDampingAndDecaysWithIt) {
  const WaveParams conservative{.damping = 0.0f};
  WaveField f = splashed({64, 64});
  const double e0 = f.energy(conservative);
  double lo = e0, hi = e0;
  for (int i = 0; i < 1200; ++i) {  // 10 simulated seconds
    f.step(conservative);
    const double e = f.energy(conservative);
    lo = std::min(lo, e);
    hi = std::max(hi, e);
  }
  // Semi-implicit Euler keeps a nearby "shadow" energy exactly; the true energy wobbles a little.
  EXPECT_GT(lo, 0.85 * e0);
  EXPECT_LT(hi, 1.15 * e0);

  const WaveParams damped{.damping = 0.3f};
  WaveField g = splashed({64, 64});
  const double g0 = g.energy(damped);
  double previousWindow = g0;
  for (int window = 0; window < 5; ++window) {  // 5 × 1 s
    for (int i = 0; i < 120; ++i) g.step(damped);
    const double e = g.energy(damped);
    EXPECT_LT(e, previousWindow) << "window " << window;
    previousWindow = e;
  }
  // Velocity is damped at rate d (v' = −d·v), so an oscillation's amplitude decays by
  // exp(−d·t/2) and its energy by exp(−d·t) = exp(−1.5) after 5 s.
  EXPECT_NEAR(previousWindow / g0, std::exp(-1.5), 0.15 * std::exp(-1.5));
}

TEST(WaveCpu, StableInsideTheDocumentedLimitUnstableBeyond) {
  for (const WaveParams base : {WaveParams{}, WaveParams{.mass = 0.5f, .springConstant = 100.0f, .restoringConstant = 50.0f},
                                WaveParams{.mass = 3.0f, .springConstant = 20000.0f, .restoringConstant = 0.0f, .wrap = true}}) {
    const float limit = stabilityLimit(base);
    WaveParams inside = base, outside = base;
    inside.damping = outside.damping = 0.0f;
    inside.timeStep = 0.98f * limit;
    outside.timeStep = 1.02f * limit;
    EXPECT_NO_THROW(inside.validate());
    EXPECT_THROW(outside.validate(), Error);
    WaveField a = splashed({48, 40}, 1.0f), b = a;  // a narrow drop excites the stiff modes
    for (int i = 0; i < 3000; ++i) a.step(inside);
    for (int i = 0; i < 3000; ++i) b.step(outside);
    EXPECT_LT(maxAbsHeight(a), 2.0f) << "k " << base.springConstant;
    EXPECT_GT(maxAbsHeight(b), 1e3f) << "k " << base.springConstant;
  }
}

TEST(WaveCpu, ParametersAreValidatedWithClearMessages) {
  auto message = [](WaveParams p) {
    try {
      p.validate();
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage);
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({.mass = 0.0f}).find("mass"), std::string::npos);
  EXPECT_NE(message({.damping = -1.0f}).find("damping"), std::string::npos);
  EXPECT_NE(message({.timeStep = 0.02f}).find("unstable"), std::string::npos);
  EXPECT_TRUE(message({}).empty());
}

TEST(WaveCpu, DropsFallOncePerInterval) {
  const WaveParams p{};  // Δt = 1/120
  const RainOptions rain{.interval = 0.25f};
  int drops = 0;
  long last = -1;
  for (long s = 0; s < 1200; ++s) {  // 10 s
    if (auto d = rainDrop(s, p, rain, {256, 256})) {
      ++drops;
      if (last >= 0) {
        EXPECT_EQ(s - last, 30);  // 0.25 s / (1/120 s)
      }
      last = s;
      EXPECT_GT(d->centre.x, 0.0f);
      EXPECT_LT(d->centre.x, 256.0f);
      EXPECT_GT(d->radius, 0.0f);
    }
  }
  EXPECT_EQ(drops, 40);
  EXPECT_TRUE(rainDrop(0, p, rain, {256, 256}).has_value());
  EXPECT_FALSE(rainDrop(5, p, {.interval = 0.0f}, {256, 256}).has_value());
  // Deterministic.
  EXPECT_EQ(rainDrop(30, p, rain, {64, 64})->centre, rainDrop(30, p, rain, {64, 64})->centre);
}
