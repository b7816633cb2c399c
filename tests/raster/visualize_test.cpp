// Edge-function pictures: the zero line lies on the edge, inside is red, outside blue.
#include "glint/core/error.h"
#include "glint/raster/visualize.h"

#include <gtest/gtest.h>

#include <array>

using namespace glint;
using namespace glint::raster;

namespace {
// Window pixel (x, y) of panel `panel` (0..2) in an edgeFunctionsImage of panels w×h.
vec3 at(const Image& img, int panel, int x, int y, int w, int h) {
  const int px = panel * (w + 4) + x, py = h - 1 - y;
  return {img.at(px, py, 0), img.at(px, py, 1), img.at(px, py, 2)};
}
}  // namespace

TEST(RasterVisualize, DivergingColorMapIsWhiteAtZeroAndSaturates) {
  EXPECT_EQ(divergingColor(0.0), vec3(1.0f));
  EXPECT_EQ(divergingColor(-5.0), divergingColor(-1.0));
  EXPECT_GT(divergingColor(1.0).r, divergingColor(1.0).b);   // positive: red
  EXPECT_GT(divergingColor(-1.0).b, divergingColor(-1.0).r); // negative: blue
}

TEST(RasterVisualize, LectureTriangleEdgesAreOrientedInsidePositive) {
  // The lecture's triangle is clockwise in window space, so every edge is negated:
  // edge 2 (v0→v1, from (50,450) to (450,450)) becomes the slide's (0, -400, 180000).
  const std::array<dvec2, 3> v = {dvec2(50, 450), dvec2(450, 450), dvec2(250, 50)};
  const auto e = orientedEdges(v);
  EXPECT_DOUBLE_EQ(e[2].a, 0.0);
  EXPECT_DOUBLE_EQ(e[2].b, -400.0);
  EXPECT_DOUBLE_EQ(e[2].c, 180000.0);
  EXPECT_DOUBLE_EQ(e[2](250, 250), 80000.0);  // the slide's "80,000 > 0 so (250,250) is in"
  for (const auto& edge : e) EXPECT_GT(edge(250, 250), 0.0);
}

TEST(RasterVisualize, PanelsShowSignZeroLineAndInside) {
  const int w = 100, h = 80;
  const std::array<dvec2, 3> v = {dvec2(10, 10), dvec2(90, 10), dvec2(50, 70)};  // counter-clockwise
  const Image img = edgeFunctionsImage(v, w, h);
  ASSERT_EQ(img.width(), 3 * w + 8);
  ASSERT_EQ(img.height(), h);
  // Edge 2 is v0→v1, the line y = 10: black on it, red (positive) above, blue below.
  EXPECT_EQ(at(img, 2, 50, 9, w, h) + at(img, 2, 50, 10, w, h), vec3(0.0f));  // the centre 9.5 or 10.5 is 0.5 away
  const vec3 above = at(img, 2, 5, 40, w, h), below = at(img, 2, 5, 2, w, h);
  EXPECT_GT(above.r, above.b);
  EXPECT_GT(below.b, below.r);
  // Inside the triangle (all three positive) is darkened relative to the same value outside.
  EXPECT_LT(at(img, 2, 50, 30, w, h).g, at(img, 2, 5, 30, w, h).g);
  // The gap between panels is grey.
  EXPECT_NEAR(img.at(w + 1, 5, 0), 0.35f, 0.01f);
}

TEST(RasterVisualize, DegenerateInputIsAUsageError) {
  EXPECT_THROW(edgeFunctionsImage({dvec2(0, 0), dvec2(1, 1), dvec2(2, 2)}, 10, 10), Error);
  EXPECT_THROW(edgeFunctionImage(EdgeEquation{0, 0, 1}, 10, 10), Error);
  EXPECT_THROW(edgeFunctionImage(EdgeEquation{1, 0, 0}, 0, 10), Error);
}
