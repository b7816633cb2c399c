// Image metrics (image/metrics.h) and the procedural test images (image/pattern.h).
#include "glint/core/error.h"
#include "glint/image/metrics.h"
#include "glint/image/pattern.h"

#include <gtest/gtest.h>

#include <random>
#include <span>
#include <vector>

using namespace glint;

TEST(Metrics, BoxDownsampleAveragesBlocks) {
  const Image checks = makeCheckerboard(64, 16);  // 4-texel checks
  const Image small = boxDownsample(checks, 8);
  ASSERT_EQ(small.width(), 8);
  const float mean = 0.5f * (0.95f + 0.08f);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) EXPECT_NEAR(small.at(x, y, 0), mean, 2.0f / 255.0f);
  EXPECT_THROW(boxDownsample(checks, 7), Error);
}

TEST(Metrics, RmsErrorAndSharpness) {
  Image a(16, 16, 1, PixelType::F32), b(16, 16, 1, PixelType::F32);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      a.set(x, y, 0, 0.2f);
      b.set(x, y, 0, 0.3f);
    }
  EXPECT_NEAR(rmsError(a, a), 0.0, 1e-12);
  EXPECT_NEAR(rmsError(a, b), 0.1, 1e-6);
  EXPECT_NEAR(rmsError(a, b, {0, 0, 4, 4}), 0.1, 1e-6);
  EXPECT_THROW(rmsError(a, Image(8, 16, 1)), Error);
  // A sharp checkerboard has more gradient than its blurred (downsampled, upsampled) self.
  const Image sharp = makeCheckerboard(64, 8);
  const Image blurred = boxDownsample(boxDownsample(sharp, 2), 1);
  EXPECT_EQ(sharpness(a), 0.0);
  EXPECT_GT(sharpness(sharp), 0.0);
  EXPECT_LT(sharpness(boxDownsample(makeCheckerboard(64, 32), 4)), 0.01);  // averaged to gray
  EXPECT_GT(sharpness(blurred), 0.0);
}

TEST(Metrics, FlickerCountsOnlyChangeTheReferenceDoesNotHave) {
  std::vector<Image> truth, same, noisy;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int f = 0; f < 4; ++f) {
    Image t(8, 8, 1, PixelType::F32), n(8, 8, 1, PixelType::F32);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        t.set(x, y, 0, 0.1f * float(f));  // a uniform fade: real change, not flicker
        n.set(x, y, 0, u(rng));
      }
    truth.push_back(t);
    same.push_back(t);
    noisy.push_back(n);
  }
  EXPECT_NEAR(temporalFlicker(same, truth), 0.0, 1e-12);
  EXPECT_GT(temporalFlicker(noisy, truth), 0.2);
  EXPECT_THROW(temporalFlicker(std::span(same).first(1), std::span(truth).first(1)), Error);
}

TEST(Pattern, TextUsesTheFiveBySevenFont) {
  Image img(12, 7, 4);
  drawText(img, 0, 0, "T", 1, vec3(1.0f));
  for (int x = 0; x < 5; ++x) EXPECT_EQ(img.at(x, 0, 0), 1.0f);  // the bar of the T
  for (int y = 1; y < 7; ++y) {
    EXPECT_EQ(img.at(2, y, 0), 1.0f);  // its stem
    EXPECT_EQ(img.at(0, y, 0), 0.0f);
  }
  drawText(img, 6, 0, "t", 1, vec3(0.5f));  // lowercase draws as uppercase
  EXPECT_NEAR(img.at(8, 3, 0), 0.5f, 1.0f / 255.0f);
  const Image chart = makeTestChart(256);
  std::size_t dark = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) dark += luminance(chart, x, y) < 0.3f;
  EXPECT_GT(dark, 256u * 256u / 50u);
  EXPECT_LT(dark, 256u * 256u / 2u);
}
