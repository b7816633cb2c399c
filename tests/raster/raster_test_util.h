#pragma once
// Small helpers shared by the raster tests.

#include "glint/raster/raster.h"

#include <cstdint>
#include <vector>

namespace glint::raster::test {

/// A vertex at clip position p with one varying (colour) c.
inline Vertex vtx(const vec4& p, const vec4& c = vec4(1.0f)) { return Vertex{p, {c}}; }

/// A vertex at NDC (x, y, z) with w = 1 and a colour.
inline Vertex ndc(float x, float y, float z = 0.0f, const vec4& c = vec4(1.0f)) { return vtx(vec4(x, y, z, 1.0f), c); }

/// Two counter-clockwise triangles covering the NDC rectangle [x0, x1] × [y0, y1] at depth z.
inline std::vector<Vertex> quad(float x0, float y0, float x1, float y1, float z = 0.0f, const vec4& c = vec4(1.0f)) {
  return {ndc(x0, y0, z, c), ndc(x1, y0, z, c), ndc(x1, y1, z, c),
          ndc(x0, y0, z, c), ndc(x1, y1, z, c), ndc(x0, y1, z, c)};
}

/// The same quad with clockwise winding (back-facing under the default glFrontFace(GL_CCW)).
inline std::vector<Vertex> quadCw(float x0, float y0, float x1, float y1, float z = 0.0f, const vec4& c = vec4(1.0f)) {
  std::vector<Vertex> v = quad(x0, y0, x1, y1, z, c);
  std::swap(v[1], v[2]);
  std::swap(v[4], v[5]);
  return v;
}

/// Number of pixels whose overdraw count equals n.
inline std::size_t countOverdraw(const Framebuffer& fb, std::uint32_t n) {
  std::size_t count = 0;
  for (std::uint32_t v : fb.overdraws()) count += v == n ? 1 : 0;
  return count;
}

}  // namespace glint::raster::test
