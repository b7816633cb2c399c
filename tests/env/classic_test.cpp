// The classic path (env/classic: glTexGen in a compatibility-profile context) and the
// shader path (env/cube, env/sphere) draw the same pictures. Skipped, not failed, where
// the driver offers no compatibility profile or the environment data is not installed.
#include "glint/core/error.h"
#include "glint/gl/debug.h"
#include "glint/render/env/environment.h"
#include "glint/scenes/runner.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace glint;

namespace {
constexpr ivec2 kSize{320, 180};

struct Agreement {
  double meanAbs = 0;        ///< mean absolute channel difference
  double outlierFraction = 0;  ///< pixels with a channel off by more than 16/255
};

Agreement agreement(const Image& a, const Image& b) {
  const ImageDifference d = compareImages(a, b);
  std::size_t outliers = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      bool off = false;
      for (int c = 0; c < 3; ++c) off = off || std::abs(a.at(x, y, c) - b.at(x, y, c)) > 16.0f / 255.0f;
      outliers += off;
    }
  const Agreement result{d.meanAbs, double(outliers) / double(a.pixelCount())};
  std::printf("  mean |difference| %.3f/255, %.3f%% of pixels off by more than 16/255\n", 255.0 * result.meanAbs,
              100.0 * result.outlierFraction);
  return result;
}

class Classic : public ::testing::Test {
protected:
  static void SetUpTestSuite() { s_pool = std::make_unique<scenes::ContextPool>(true); }
  static void TearDownTestSuite() { s_pool.reset(); }

  void SetUp() override {
    if (!s_pool->available(gl::Profile::Compatibility)) {
      GTEST_SKIP() << "no compatibility-profile context: " << s_pool->unavailableReason(gl::Profile::Compatibility);
    }
    try {
      render::env::findEnvironment("courtyard");
    } catch (const Error& e) {
      GTEST_SKIP() << e.what();
    }
    m_errors = gl::debugErrorCount();
  }
  void TearDown() override { EXPECT_EQ(gl::debugErrorCount(), m_errors) << "GL debug errors"; }

  static Image render(const std::string& name, std::vector<std::string> options = {}) {
    const auto ref = scenes::Registry::builtin().resolve(name);
    s_pool->use(ref.scene->profile);
    return scenes::renderVariant(ref, {.size = kSize, .options = std::move(options)}).image;
  }

  static inline std::unique_ptr<scenes::ContextPool> s_pool;
  std::uint64_t m_errors = 0;
};
}  // namespace

TEST_F(Classic, ReflectionMapTexgenAgreesWithTheShaderPath) {
  for (const auto& [classic, shader] : {std::pair{"env/classic/cube", "env/cube/front"}, {"env/classic/cube-back", "env/cube/back"}}) {
    const Image fixedFunction = render(classic);
    // The shader doing exactly what texgen does (per vertex): the same picture up to
    // rounding (llvmpipe: identical, 0/255). The tolerance leaves room for drivers whose
    // fixed-function interpolation rounds differently.
    const Agreement perVertex = agreement(fixedFunction, render(shader, {"per-vertex=1"}));
    EXPECT_LT(perVertex.meanAbs, 0.5 / 255.0) << classic;
    EXPECT_LT(perVertex.outlierFraction, 0.001) << classic;
    // Per pixel differs only where r turns fastest (silhouettes). llvmpipe: mean 0.07/255
    // and 0.02% of pixels front, 0.08/255 and 0.04% back.
    const Agreement perPixel = agreement(fixedFunction, render(shader));
    EXPECT_LT(perPixel.meanAbs, 0.5 / 255.0) << classic;
    EXPECT_LT(perPixel.outlierFraction, 0.005) << classic;
  }
}

TEST_F(Classic, SphereMapTexgenAgreesWithTheShaderPath) {
  const Image fixedFunction = render("env/classic/sphere");
  const Agreement perVertex = agreement(fixedFunction, render("env/sphere/front", {"per-vertex=1"}));
  EXPECT_LT(perVertex.meanAbs, 0.5 / 255.0);
  EXPECT_LT(perVertex.outlierFraction, 0.001);
  // Per-vertex (s, t) interpolated across the singular rim smears silhouettes: the
  // per-pixel shader is better there, so more pixels differ than for cube maps
  // (llvmpipe: mean 0.29/255, 0.56% of pixels).
  const Agreement perPixel = agreement(fixedFunction, render("env/sphere/front"));
  EXPECT_LT(perPixel.meanAbs, 1.0 / 255.0);
  EXPECT_LT(perPixel.outlierFraction, 0.02);
}
