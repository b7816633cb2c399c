#pragma once
// What the ray-traced oracle tests share when they compare a GPU picture with a per-pixel
// classification (lit, shadowed, not compared).
#include <cstddef>
#include <vector>

namespace glint::testing {

/// Whether each pixel of a w×h classification (row by row) is compared: classified
/// (`classified(t)`) and not within `band` pixels of a classified pixel of another class —
/// pixels at an edge may fall either way on two pipelines.
template <class Class, class Classified>
std::vector<bool> awayFromEdges(const std::vector<Class>& truth, int w, int h, int band, Classified classified) {
  std::vector<bool> out(truth.size(), false);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Class t = truth[std::size_t(y * w + x)];
      if (!classified(t)) continue;
      bool nearEdge = false;
      for (int dy = -band; dy <= band && !nearEdge; ++dy)
        for (int dx = -band; dx <= band && !nearEdge; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          const Class n = truth[std::size_t(yy * w + xx)];
          nearEdge = classified(n) && n != t;
        }
      out[std::size_t(y * w + x)] = !nearEdge;
    }
  }
  return out;
}

}  // namespace glint::testing
