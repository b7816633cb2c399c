// Height → normal on the CPU (image/normalmap.h): the formula against hand-computed
// normals, the slide's sign conventions and z, edges, odd sizes, and bad inputs.
#include "glint/core/error.h"
#include "glint/image/heightfield.h"
#include "glint/image/normalmap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace glint;

namespace {
// A height map from a function of the texel (x, y), y = image row (0 at the top).
template <typename F>
Image heights(int w, int h, F f) {
  Image img(w, h, 1, PixelType::F32);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set(x, y, 0, f(x, y));
  return img;
}

vec3 decodedAt(const Image& normalMap, int x, int y) {
  return decodeNormal({normalMap.at(x, y, 0), normalMap.at(x, y, 1), normalMap.at(x, y, 2)});
}

// One 8-bit step of the encoding, as a vector component: 2/255.
constexpr float kByte = 2.0f / 255.0f;
}  // namespace

TEST(HeightToNormal, FlatHeightGivesStraightUpEverywhere) {
  const Image n = heightToNormalMap(heights(9, 7, [](int, int) { return 0.3f; }));
  ASSERT_EQ(n.channels(), 4);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) {
      EXPECT_EQ(n.at(x, y, 0), 128.0f / 255.0f);  // (0 + 1)/2 · 255 = 127.5 rounds to 128
      EXPECT_EQ(n.at(x, y, 1), 128.0f / 255.0f);
      EXPECT_EQ(n.at(x, y, 2), 1.0f);
      EXPECT_EQ(n.at(x, y, 3), 1.0f);
    }
}

TEST(HeightToNormal, RampMatchesTheAnalyticNormal) {
  // h = a·x + b·(rows up): ∂h/∂x = a, ∂h/∂(north) = b per texel. With scale s the surface is
  // z = s·h, so the unit normal is normalize(−s·a, −s·b, 1), independent of this code.
  const float a = 0.01f, b = -0.02f, s = 10.0f;
  const Image n = heightToNormalMap(heights(16, 12, [&](int x, int y) { return 0.5f + a * float(x) + b * float(11 - y); }),
                                    {.scale = s});
  const vec3 expected = glm::normalize(vec3(-s * a, -s * b, 1.0f));
  for (int y = 1; y < 11; ++y)
    for (int x = 1; x < 15; ++x) {
      const vec3 got = decodedAt(n, x, y);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], kByte / 2 + 1e-5f) << x << "," << y << " comp " << k;
    }
}

TEST(HeightToNormal, GradientNormalsPointDownhillOnBothAxes) {
  // Rising to the east: the normal leans west (x < 0). Rising to the north (towards row 0,
  // up in the picture): the normal leans south (y < 0).
  const Image east = heightToNormalMap(heights(8, 8, [](int x, int) { return 0.05f * float(x); }));
  const Image north = heightToNormalMap(heights(8, 8, [](int, int y) { return 0.05f * float(8 - y); }));
  EXPECT_LT(decodedAt(east, 4, 4).x, -0.1f);
  EXPECT_NEAR(decodedAt(east, 4, 4).y, 0.0f, kByte);
  EXPECT_LT(decodedAt(north, 4, 4).y, -0.1f);
  EXPECT_NEAR(decodedAt(north, 4, 4).x, 0.0f, kByte);
}

TEST(HeightToNormal, SlideFormulaIsMirroredInXOnly) {
  // The slide's d = (e − w, s − n): x points uphill, y downhill (north = up in the picture).
  const NormalMapOptions slide{.scale = 2.0f, .formula = NormalFormula::Slide};
  const Image east = heightToNormalMap(heights(8, 8, [](int x, int) { return 0.02f * float(x); }), slide);
  const Image north = heightToNormalMap(heights(8, 8, [](int, int y) { return 0.02f * float(8 - y); }), slide);
  EXPECT_GT(decodedAt(east, 4, 4).x, 0.01f);   // uphill: the mirror image of the true normal
  EXPECT_LT(decodedAt(north, 4, 4).y, -0.01f); // downhill, like the true normal
  // For gentle slopes the slide equals the true normal with x negated (to first order).
  for (float slope : {0.002f, 0.01f}) {
    const vec3 s = heightNormal(0.5f + slope, 0.5f - slope, 0.5f + 2 * slope, 0.5f - 2 * slope, slide);
    const vec3 g = heightNormal(0.5f + slope, 0.5f - slope, 0.5f + 2 * slope, 0.5f - 2 * slope, {.scale = 2.0f});
    // The difference is second order: the slide's z = 1 − |d| lengthens x and y by ≈ |d|.
    EXPECT_NEAR(s.x, -g.x, 25 * slope * slope);
    EXPECT_NEAR(s.y, g.y, 25 * slope * slope);
  }
}

TEST(HeightToNormal, SlideZFallsWithSlopeAndTurnsInward) {
  // The slide literally (scale 2): d = (e − w, s − n, 0), d.z = 1 − |d|, normalize.
  const NormalMapOptions slide{.scale = 2.0f, .formula = NormalFormula::Slide};
  // |d| = 0.5: z = 0.5 before normalizing, so the tilt is atan(0.5/0.5) = 45°, where the
  // surface's slope (0.5 per texel) is atan(0.5) = 26.6°.
  const vec3 half = heightNormal(0.0f, 0.0f, 0.5f, 0.0f, slide);
  EXPECT_NEAR(std::acos(half.z), glm::radians(45.0f), 1e-5f);
  const vec3 truth = heightNormal(0.0f, 0.0f, 0.5f, 0.0f, {.scale = 2.0f});
  EXPECT_NEAR(std::acos(truth.z), std::atan(0.5f), 1e-5f);
  // |d| = 1: the normal lies in the surface plane.
  EXPECT_NEAR(heightNormal(0.0f, 0.0f, 1.0f, 0.0f, slide).z, 0.0f, 1e-6f);
  // Both differences at their maximum: |d| = √2, z = 1 − √2 < 0 — the normal points into the surface.
  const vec3 inward = heightNormal(0.0f, 1.0f, 1.0f, 0.0f, slide);
  EXPECT_NEAR(inward.z, (1.0f - std::sqrt(2.0f)) / std::sqrt(2.0f + (1 - std::sqrt(2.0f)) * (1 - std::sqrt(2.0f))), 1e-5f);
  EXPECT_LT(inward.z, 0.0f);
  EXPECT_GT(heightNormal(0.0f, 1.0f, 1.0f, 0.0f, {.scale = 2.0f}).z, 0.0f);  // the true normal never does
}

TEST(HeightToNormal, EdgesClampOrWrap) {
  // A ramp rising to the east, cut off at the tile edge.
  const Image h = heights(10, 4, [](int x, int) { return 0.1f * float(x); });
  const Image clamped = heightToNormalMap(h, {.scale = 4.0f});
  const Image wrapped = heightToNormalMap(h, {.scale = 4.0f, .wrap = true});
  // Clamp: column 0 sees w = itself, a one-sided difference (half the slope).
  EXPECT_NEAR(decodedAt(clamped, 0, 1).x, heightNormal(0, 0, 0.1f, 0.0f, {.scale = 4.0f}).x, kByte / 2 + 1e-5f);
  // Wrap: column 0's west neighbour is column 9 (0.9): a steep cliff going down to the east.
  EXPECT_NEAR(decodedAt(wrapped, 0, 1).x, heightNormal(0, 0, 0.1f, 0.9f, {.scale = 4.0f}).x, kByte / 2 + 1e-5f);
  EXPECT_GT(decodedAt(wrapped, 0, 1).x, 0.5f);
  // Inside, both agree.
  EXPECT_EQ(decodedAt(clamped, 5, 2), decodedAt(wrapped, 5, 2));
}

TEST(HeightToNormal, TileableInputGivesATileableMap) {
  const Image h = makeBrickHeight(64);
  const Image n = heightToNormalMap(h, {.wrap = true});
  // Shifting the height map by half a tile shifts the normal map by the same amount.
  Image shifted(64, 64, 1, PixelType::F32);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) shifted.set(x, y, 0, h.at((x + 32) % 64, (y + 32) % 64, 0));
  const Image ns = heightToNormalMap(shifted, {.wrap = true});
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(ns.at(x, y, c), n.at((x + 32) % 64, (y + 32) % 64, c));
}

TEST(HeightToNormal, NonPowerOfTwoSizesWork) {
  const Image n = heightToNormalMap(heights(37, 23, [](int x, int y) { return std::sin(0.3f * float(x)) * std::cos(0.2f * float(y)); }));
  EXPECT_EQ(n.width(), 37);
  EXPECT_EQ(n.height(), 23);
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) EXPECT_NEAR(glm::length(decodedAt(n, x, y)), 1.0f, 2 * kByte);
}

TEST(HeightToNormal, ColourHeightMapsUseLuminance) {
  Image rgb(6, 6, 3, PixelType::U8);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      rgb.set(x, y, 0, 0.1f * float(x));
      rgb.set(x, y, 1, 0.05f * float(x));
      rgb.set(x, y, 2, 0.5f);
    }
  bool usedLuminance = false;
  const Image gray = heightFromImage(rgb, &usedLuminance);
  EXPECT_TRUE(usedLuminance);
  ASSERT_EQ(gray.channels(), 1);
  EXPECT_NEAR(gray.at(3, 2, 0), 0.2126f * rgb.at(3, 2, 0) + 0.7152f * rgb.at(3, 2, 1) + 0.0722f * rgb.at(3, 2, 2), 1.0f / 255);
  EXPECT_EQ(heightToNormalMap(rgb), heightToNormalMap(gray));
  heightFromImage(gray, &usedLuminance);
  EXPECT_FALSE(usedLuminance);
}

// ---------------------------------------------------------------------------
// Normal maps read from files

namespace {
std::string errorOf(const Image& img, NormalSpace space = NormalSpace::Tangent) {
  try {
    prepareNormalMap(img, "map.png", space);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return {};
}
}  // namespace

TEST(PrepareNormalMap, AcceptsAGoodMapUnchanged) {
  const Image n = heightToNormalMap(makeBumpsHeight(64), {.wrap = true});
  NormalMapReport report;
  EXPECT_EQ(prepareNormalMap(n, "n.png", NormalSpace::Tangent, &report), n);
  EXPECT_NEAR(report.meanLength, 1.0, 0.01);
  EXPECT_EQ(report.outwardFraction, 1.0);
  EXPECT_TRUE(report.conversion.empty());
}

TEST(PrepareNormalMap, RejectsHeightMapsColourTexturesAndInsideOutMaps) {
  EXPECT_NE(errorOf(makeBumpsHeight(32)).find("height map"), std::string::npos);
  EXPECT_NE(errorOf(makeBrickAlbedo(32)).find("mean length"), std::string::npos);
  Image inverted = heightToNormalMap(makeBumpsHeight(32));
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) inverted.set(x, y, 2, 1.0f - inverted.at(x, y, 2));
  const std::string message = errorOf(inverted);
  EXPECT_NE(message.find("tangent-space"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_TRUE(errorOf(inverted, NormalSpace::Object).empty());  // fine as an object-space map
}

TEST(PrepareNormalMap, ConvertsTwoChannelAndSignedMaps) {
  const Image good = heightToNormalMap(makeBumpsHeight(32));
  Image rg(32, 32, 2, PixelType::U8), signedMap(32, 32, 3, PixelType::F32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      for (int c = 0; c < 2; ++c) rg.set(x, y, c, good.at(x, y, c));
      for (int c = 0; c < 3; ++c) signedMap.set(x, y, c, decodedAt(good, x, y)[c]);
    }
  NormalMapReport report;
  const Image fromRg = prepareNormalMap(rg, "rg.png", NormalSpace::Tangent, &report);
  EXPECT_NE(report.conversion.find("reconstructed"), std::string::npos);
  const Image fromSigned = prepareNormalMap(signedMap, "signed.exr", NormalSpace::Tangent, &report);
  EXPECT_NE(report.conversion.find("signed"), std::string::npos);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(fromRg.at(x, y, c), good.at(x, y, c), 2.0f / 255) << x << "," << y;
        EXPECT_NEAR(fromSigned.at(x, y, c), good.at(x, y, c), 1.0f / 255) << x << "," << y;
      }
}
