#pragma once
// What the post tests share: test images (a real photograph, noise, an odd-sized crop) and
// 8-bit comparisons that report where and by how much two images differ.
#include "glint/core/locations.h"
#include "glint/image/envmap.h"
#include "glint/image/image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace glint::testing {

/// A 320×240 view of the courtyard HDR photograph (data/env, scripts/setup): real edges,
/// textures, sky and shadows. The same view as the post/* scenes' photograph, smaller.
inline const Image& photograph() {
  static const Image photo = perspectiveView(loadImage(findDataFile("env/courtyard.exr", "environment 'courtyard'")),
                                             {320, 240}, 0.0f, 0.05f, 70.0f, 0.5f);
  return photo;
}

/// Uniform 8-bit noise, opaque: the harshest input (every pixel an edge, many near-ties).
inline Image noiseImage(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  Image image(w, h, 4);
  auto px = image.pixels<std::uint8_t>();
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = std::uint8_t(i % 4 == 3 ? 255 : rng() & 0xFF);
  return image;
}

/// A w × h crop of `image` at (x0, y0).
inline Image crop(const Image& image, int x0, int y0, int w, int h) {
  Image out(w, h, image.channels(), image.type());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < image.channels(); ++c) out.set(x, y, c, image.at(x0 + x, y0 + y, c));
  return out;
}

/// The three inputs every pass is checked on: a photograph, noise, and an odd-sized crop
/// (the GPU and CPU backend tests share them).
inline std::vector<std::pair<std::string, Image>> postInputs() {
  return {{"photo", photograph()}, {"noise", noiseImage(96, 64, 11)}, {"odd", crop(photograph(), 101, 57, 37, 23)}};
}

struct ChannelDifference {
  int maxSteps = 0;        ///< largest |a − b| in 8-bit steps over RGB
  double meanSteps = 0;    ///< mean over RGB
  std::size_t over = 0;    ///< channel values differing by more than the allowed steps
  int worstX = 0, worstY = 0;
};

/// |round(255·a) − round(255·b)| over channels 0..2 (any types; b may be an unrounded F32
/// reference, which is rounded as an RGBA8 target would store it, clamped to 0..1).
inline ChannelDifference compareSteps(const Image& a, const Image& b, int allowed = 1) {
  ChannelDifference d;
  EXPECT_EQ(a.width(), b.width());
  EXPECT_EQ(a.height(), b.height());
  double sum = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        const auto step = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
        const int diff = std::abs(step(a.at(x, y, c)) - step(b.at(x, y, c)));
        sum += diff;
        if (diff > allowed) ++d.over;
        if (diff > d.maxSteps) {
          d.maxSteps = diff;
          d.worstX = x;
          d.worstY = y;
        }
      }
    }
  }
  d.meanSteps = sum / (3.0 * double(a.pixelCount()));
  return d;
}

inline std::filesystem::path outputDir(const std::string& name) {
  const auto d = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "post" / name;
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace glint::testing
