// Frontier-based dilation: each pass only visits empty texels next to filled ones,
// so the cost is proportional to the texels filled, not passes × image size (fill-all
// on a 4k map with small islands takes thousands of passes).
#include "glint/bake/dilate.h"

#include "glint/core/error.h"

#include <cmath>
#include <vector>

namespace glint::bake {

std::uint64_t dilate(std::span<float> texels, int channels, int width, int height, std::span<std::uint8_t> filled,
                     const DilateOptions& options) {
  const std::size_t count = std::size_t(width) * std::size_t(height);
  if (width <= 0 || height <= 0 || channels <= 0 || texels.size() != count * std::size_t(channels) ||
      filled.size() != count) {
    fail(ErrorKind::Internal, "dilate: buffer sizes do not match {}x{}x{}", width, height, channels);
  }
  const auto neighbours = [&](std::size_t i, auto&& visit) {
    const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || x + dx < 0 || x + dx >= width || y + dy < 0 || y + dy >= height) continue;
        visit(std::size_t(y + dy) * std::size_t(width) + std::size_t(x + dx));
      }
    }
  };

  // Frontier: empty texels with a filled neighbour, each listed once (in scan order at
  // first, then in the order they were discovered; the order never affects values). Found
  // from the empty side: a bake that covers most of its map has few empty texels to look at.
  std::vector<std::uint8_t> queued(count, 0);
  std::vector<std::size_t> frontier;
  for (std::size_t i = 0; i < count; ++i) {
    if (filled[i]) continue;
    bool touches = false;
    neighbours(i, [&](std::size_t n) { touches = touches || filled[n] != 0; });
    if (touches) {
      queued[i] = 1;
      frontier.push_back(i);
    }
  }

  const std::size_t c = std::size_t(channels);
  std::vector<float> values;
  std::uint64_t grown = 0;
  for (int pass = 0; (options.passes < 0 || pass < options.passes) && !frontier.empty(); ++pass) {
    values.assign(frontier.size() * c, 0.0f);
    for (std::size_t f = 0; f < frontier.size(); ++f) {
      float* out = &values[f * c];
      int n = 0;
      neighbours(frontier[f], [&](std::size_t j) {
        if (!filled[j]) return;
        for (std::size_t k = 0; k < c; ++k) out[k] += texels[j * c + k];
        ++n;
      });
      for (std::size_t k = 0; k < c; ++k) out[k] /= float(n);
      if (options.unitVectorChannels == 3 && c >= 3) {
        const float len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
        if (len > 0.0f) {
          for (std::size_t k = 0; k < 3; ++k) out[k] /= len;
        }
      }
    }
    std::vector<std::size_t> next;
    for (std::size_t f = 0; f < frontier.size(); ++f) {
      const std::size_t i = frontier[f];
      for (std::size_t k = 0; k < c; ++k) texels[i * c + k] = values[f * c + k];
      filled[i] = 1;
      ++grown;
    }
    for (std::size_t i : frontier) {
      neighbours(i, [&](std::size_t n) {
        if (!filled[n] && !queued[n]) {
          queued[n] = 1;
          next.push_back(n);
        }
      });
    }
    frontier.swap(next);
  }
  return grown;
}

}  // namespace glint::bake
