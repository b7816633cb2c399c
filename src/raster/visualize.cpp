// Pictures of the edge equations (see visualize.h).

#include "glint/raster/visualize.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cmath>

namespace glint::raster {

namespace {
constexpr int kGap = 4;                   // pixels between panels
constexpr float kGapGrey = 0.35f;
constexpr float kInsideDarkening = 0.72f;  // covered pixels keep 72% of their brightness
constexpr float kContourDarkening = 0.85f;

double signedDistance(const EdgeEquation& e, double x, double y) { return e(x, y) / std::hypot(e.a, e.b); }

/// Draws one edge panel into `image` at column offset x0; `inside` darkens covered pixels.
template <typename Inside>
void drawPanel(Image& image, int x0, const EdgeEquation& edge, int width, int height, double scale, Inside inside) {
  const double contourStep = scale / 8.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;  // pixel centre, window coordinates
      const double d = signedDistance(edge, cx, cy);
      vec3 c = divergingColor(d / scale);
      // Contours: the pixel straddles a multiple of contourStep.
      const double k = std::floor(d / contourStep + 0.5);
      if (k != 0.0 && std::abs(d - k * contourStep) <= 0.5) c *= kContourDarkening;
      if (inside(cx, cy)) c *= kInsideDarkening;
      if (std::abs(d) <= 0.5) c = vec3(0.0f);  // the zero line: the edge itself
      for (int i = 0; i < 3; ++i) image.set(x0 + x, height - 1 - y, i, c[i]);
    }
  }
}

void checkSize(int width, int height) {
  if (width < 1 || height < 1) fail(ErrorKind::Usage, "edge function image: size must be positive, got {}x{}", width, height);
}
}  // namespace

vec3 divergingColor(double t) {
  const float s = float(std::clamp(t, -1.0, 1.0));
  const vec3 negative{0.23f, 0.30f, 0.75f}, positive{0.71f, 0.02f, 0.15f}, zero{1.0f};
  return s < 0.0f ? glm::mix(zero, negative, -s) : glm::mix(zero, positive, s);
}

Image edgeFunctionImage(const EdgeEquation& edge, int width, int height, double scale) {
  checkSize(width, height);
  if (edge.a == 0.0 && edge.b == 0.0) fail(ErrorKind::Usage, "edge function image: the edge has no direction (A = B = 0)");
  if (!(scale > 0.0)) scale = std::max(width, height);
  Image image(width, height, 3, PixelType::U8);
  drawPanel(image, 0, edge, width, height, scale, [](double, double) { return false; });
  return image;
}

std::array<EdgeEquation, 3> orientedEdges(const std::array<dvec2, 3>& v) {
  std::array<EdgeEquation, 3> edges = {edgeEquation(v[1], v[2]), edgeEquation(v[2], v[0]), edgeEquation(v[0], v[1])};
  if (signedArea2(v[0], v[1], v[2]) < 0.0) {
    // "If the determinant is negative, reverse the comparison sense."
    for (EdgeEquation& e : edges) e = EdgeEquation{0.0 - e.a, 0.0 - e.b, 0.0 - e.c};  // 0 - x: no -0
  }
  return edges;
}

Image edgeFunctionsImage(const std::array<dvec2, 3>& v, int width, int height, double scale) {
  checkSize(width, height);
  if (signedArea2(v[0], v[1], v[2]) == 0.0) fail(ErrorKind::Usage, "edge function image: the triangle has zero area");
  if (!(scale > 0.0)) scale = std::max(width, height);
  const std::array<EdgeEquation, 3> edges = orientedEdges(v);
  const auto inside = [&](double x, double y) { return edges[0](x, y) >= 0 && edges[1](x, y) >= 0 && edges[2](x, y) >= 0; };
  Image image(3 * width + 2 * kGap, height, 3, PixelType::U8);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int i = 0; i < 3; ++i) image.set(x, y, i, kGapGrey);
  for (int e = 0; e < 3; ++e) drawPanel(image, e * (width + kGap), edges[std::size_t(e)], width, height, scale, inside);
  return image;
}

}  // namespace glint::raster
