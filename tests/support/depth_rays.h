#pragma once
// The ray-traced shadow oracles' first step (tests/shadows/oracle_test.cpp,
// tests/pipedream/pipedream_gl_test.cpp): every pixel of a rendered depth image that shows
// a surface, as the world point it shows and a primary ray from the eye through it.
#include "glint/core/math.h"
#include "glint/image/image.h"
#include "glint/raytrace/raytracer.h"

#include <cstddef>
#include <vector>

namespace glint::testing {

struct DepthSamples {
  std::vector<vec3> positions;         ///< the pixel centre's depth, unprojected to world space
  std::vector<std::size_t> pixels;     ///< y·width + x, image row 0 at the top
  std::vector<raytrace::Ray> primary;  ///< eye → position with tfar 2: a hit at t ≈ 1 is that surface
};

/// The samples of `depth` (GL depth in [0, 1], 1 = background, image row 0 = GL's top row)
/// seen through `viewProjection` from `eye`.
inline DepthSamples depthSamples(const Image& depth, const mat4& viewProjection, vec3 eye) {
  const mat4 inverse = glm::inverse(viewProjection);
  const int w = depth.width(), h = depth.height();
  DepthSamples s;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float d = depth.at(x, y, 0);
      if (d >= 1.0f) continue;  // background
      // Pixel centre in NDC; image row 0 is the top, GL's window row h − 1.
      const vec4 ndc{(float(x) + 0.5f) / float(w) * 2.0f - 1.0f, (float(h - 1 - y) + 0.5f) / float(h) * 2.0f - 1.0f,
                     2.0f * d - 1.0f, 1.0f};
      const vec4 p = inverse * ndc;
      s.positions.push_back(vec3(p) / p.w);
      s.pixels.push_back(std::size_t(y * w + x));
      s.primary.push_back({.origin = eye, .direction = s.positions.back() - eye, .tfar = 2.0f});
    }
  }
  return s;
}

}  // namespace glint::testing
