// bake::dilate against the definition in its header, computed the slow way: every pass
// looks at every texel of the previous pass's state. The frontier bookkeeping (where the
// speed is) must give the same texels, bit for bit, and the same count.
#include "glint/bake/dilate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

using namespace glint;

namespace {

struct Grid {
  int width, height, channels;
  std::vector<float> texels;
  std::vector<std::uint8_t> filled;
};

/// One pass at a time over the whole image: an empty texel with filled 8-neighbours takes
/// their average (neighbours in row order, as dilate() sums them), renormalized for unit
/// vectors. Returns the texels filled.
std::uint64_t dilateByDefinition(Grid& g, int passes, bool unitVectors) {
  const std::size_t c = std::size_t(g.channels);
  std::uint64_t grown = 0;
  for (int pass = 0; passes < 0 || pass < passes; ++pass) {
    std::vector<float> texels = g.texels;
    std::vector<std::uint8_t> filled = g.filled;
    bool any = false;
    for (int y = 0; y < g.height; ++y) {
      for (int x = 0; x < g.width; ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(g.width) + std::size_t(x);
        if (g.filled[i]) continue;
        std::vector<float> sum(c, 0.0f);
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || nx >= g.width || ny < 0 || ny >= g.height) continue;
            const std::size_t j = std::size_t(ny) * std::size_t(g.width) + std::size_t(nx);
            if (!g.filled[j]) continue;
            for (std::size_t k = 0; k < c; ++k) sum[k] += g.texels[j * c + k];
            ++n;
          }
        }
        if (n == 0) continue;
        for (float& v : sum) v /= float(n);
        if (unitVectors) {
          const float len = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
          if (len > 0.0f) {
            for (std::size_t k = 0; k < 3; ++k) sum[k] /= len;
          }
        }
        for (std::size_t k = 0; k < c; ++k) texels[i * c + k] = sum[k];
        filled[i] = 1;
        any = true;
        ++grown;
      }
    }
    if (!any) break;
    g.texels = std::move(texels);
    g.filled = std::move(filled);
  }
  return grown;
}

/// A width × height grid with the given fraction of texels filled (in blobs, like UV
/// islands, or scattered), random values.
Grid randomGrid(int width, int height, int channels, double coverage, bool blobs, std::uint32_t seed) {
  Grid g{width, height, channels, std::vector<float>(std::size_t(width * height * channels), 0.0f),
         std::vector<std::uint8_t>(std::size_t(width * height), 0)};
  std::uint32_t state = seed;
  const auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1 << 24);
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool on = blobs ? std::sin(0.7 * x + 3.0 * next() * 0.1) * std::cos(0.5 * y) > 1.0 - 2.0 * coverage
                            : next() < coverage;
      const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
      g.filled[i] = on ? 1 : 0;
      if (on) {
        for (int k = 0; k < channels; ++k) g.texels[i * std::size_t(channels) + std::size_t(k)] = float(next()) - 0.3f;
      }
    }
  }
  return g;
}

}  // namespace

TEST(Dilate, MatchesThePassByPassDefinition) {
  struct Case {
    int width, height, channels;
    double coverage;
    bool blobs;
    int passes;
  };
  for (const Case& k : {Case{37, 23, 3, 0.3, true, 16}, Case{64, 64, 4, 0.6, true, 3}, Case{50, 31, 3, 0.02, false, -1},
                        Case{40, 40, 1, 0.95, false, 2}, Case{33, 17, 3, 1.0, false, 16}, Case{20, 20, 3, 0.0, false, 5},
                        Case{1, 30, 3, 0.1, false, -1}, Case{45, 45, 5, 0.5, false, 1}}) {
    for (bool unit : {false, true}) {
      if (unit && k.channels < 3) continue;
      Grid fast = randomGrid(k.width, k.height, k.channels, k.coverage, k.blobs, std::uint32_t(k.width * 131 + k.height));
      Grid slow = fast;
      const std::uint64_t grown = bake::dilate(fast.texels, k.channels, k.width, k.height, fast.filled,
                                               {.passes = k.passes, .unitVectorChannels = unit ? 3 : 0});
      const std::uint64_t expected = dilateByDefinition(slow, k.passes, unit);
      SCOPED_TRACE(testing::Message() << k.width << "x" << k.height << "x" << k.channels << " coverage " << k.coverage
                                      << " passes " << k.passes << (unit ? " unit" : ""));
      EXPECT_EQ(grown, expected);
      EXPECT_EQ(fast.filled, slow.filled);
      ASSERT_EQ(fast.texels.size(), slow.texels.size());
      for (std::size_t i = 0; i < fast.texels.size(); ++i) ASSERT_EQ(fast.texels[i], slow.texels[i]) << "value " << i;
    }
  }
}
