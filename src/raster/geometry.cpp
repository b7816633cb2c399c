// Transforms, clipping and triangle setup of the reference rasterizer (see geometry.h).

#include "glint/raster/geometry.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cmath>

namespace glint::raster {

// ---------------------------------------------------------------------------------
// Transforms
// ---------------------------------------------------------------------------------

Viewport clampViewport(const Viewport& viewport) {
  if (viewport.width < 0 || viewport.height < 0)
    fail(ErrorKind::Usage, "viewport size must not be negative, got {}x{}", viewport.width, viewport.height);
  return Viewport{
      .x = std::clamp(viewport.x, kViewportBoundsMin, kViewportBoundsMax),
      .y = std::clamp(viewport.y, kViewportBoundsMin, kViewportBoundsMax),
      .width = std::min(viewport.width, kMaxViewportDim),
      .height = std::min(viewport.height, kMaxViewportDim),
  };
}

Viewport effectiveViewport(const State& state, int framebufferWidth, int framebufferHeight) {
  if (state.viewport) return clampViewport(*state.viewport);
  // A GL context's initial viewport is the size of the surface it is first bound to.
  return Viewport{0, 0, framebufferWidth, framebufferHeight};
}

namespace {
double clamp01(double v) {
  if (!(v > 0.0)) return 0.0;  // also maps NaN to 0
  return std::min(v, 1.0);
}
}  // namespace

DepthRange clampDepthRange(const DepthRange& range) {
  return DepthRange{.nearVal = clamp01(range.nearVal), .farVal = clamp01(range.farVal)};
}

dvec3 perspectiveDivide(const dvec4& clip) { return dvec3(clip) / clip.w; }

dvec3 viewportTransform(const dvec3& ndc, const Viewport& viewport, const DepthRange& range) {
  const DepthRange r = clampDepthRange(range);
  const double halfW = viewport.width / 2.0;
  const double halfH = viewport.height / 2.0;
  return dvec3(halfW * ndc.x + viewport.x + halfW,  // w_x = (w/2)·x + v_x + w/2
               halfH * ndc.y + viewport.y + halfH,  // w_y = (h/2)·y + v_y + h/2
               (r.farVal - r.nearVal) / 2.0 * ndc.z + (r.nearVal + r.farVal) / 2.0);
}

dvec3 clipToWindow(const dvec4& clip, const Viewport& viewport, const DepthRange& range) {
  return viewportTransform(perspectiveDivide(clip), viewport, range);
}

// ---------------------------------------------------------------------------------
// Clipping
// ---------------------------------------------------------------------------------

namespace {

/// A half-space dot(normal, v) + offset >= 0 in homogeneous clip space.
struct ClipPlane {
  dvec4 normal;
  double offset = 0.0;
  double distance(const dvec4& v) const { return glm::dot(normal, v) + offset; }
};

/// The point where edge (in → out) meets the plane. Always parameterised from the inside
/// vertex so that both triangles sharing an edge produce the same bits.
ClipVertex intersect(const ClipVertex& in, const ClipVertex& out, double dIn, double dOut) {
  const double t = dIn / (dIn - dOut);  // dIn > 0 > dOut, so 0 < t < 1
  return ClipVertex{in.position + t * (out.position - in.position), in.weights + t * (out.weights - in.weights)};
}

std::vector<ClipVertex> clipAgainst(const std::vector<ClipVertex>& polygon, const ClipPlane& plane) {
  std::vector<ClipVertex> result;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const ClipVertex& cur = polygon[i];
    const ClipVertex& next = polygon[(i + 1) % n];
    const double dCur = plane.distance(cur.position);
    const double dNext = plane.distance(next.position);
    const bool curInside = dCur >= 0.0;
    const bool nextInside = dNext >= 0.0;
    if (curInside) result.push_back(cur);
    if (curInside == nextInside) continue;
    // The edge crosses the plane. When the inside end lies exactly on the plane the cut
    // point is that vertex itself, which is (or will be) emitted on its own.
    if (curInside && dCur > 0.0) result.push_back(intersect(cur, next, dCur, dNext));
    if (nextInside && dNext > 0.0) result.push_back(intersect(next, cur, dNext, dCur));
  }
  return result;
}

}  // namespace

namespace {

/// The four planes -g·w <= x <= g·w, -g·w <= y <= g·w.
void addGuardBand(std::vector<ClipPlane>& planes, double g) {
  planes.push_back({dvec4(1, 0, 0, g), 0.0});   // x >= -g·w
  planes.push_back({dvec4(-1, 0, 0, g), 0.0});  // x <=  g·w
  planes.push_back({dvec4(0, 1, 0, g), 0.0});   // y >= -g·w
  planes.push_back({dvec4(0, -1, 0, g), 0.0});  // y <=  g·w
}

/// Every plane clipTriangle applies, in order.
std::vector<ClipPlane> clipPlanes(double guardBand) {
  std::vector<ClipPlane> planes;
  // Coarse guard bands first, shrinking by 2^32 at a time. A cut point is computed with an
  // absolute error of about 2^-53 times the size of the vertices it comes from, so cutting
  // a 1e30-sized triangle straight down to the viewport would land kilometres off; each
  // stage here only has to be accurate relative to the previous, much larger, band.
  // (Mathematically these planes change nothing: the final band lies inside them.)
  for (double g : {0x1p96, 0x1p64, 0x1p32, 0x1p16})
    if (g > guardBand) addGuardBand(planes, g);
  planes.push_back({dvec4(0, 0, 1, 1), 0.0});          // near:  z >= -w
  planes.push_back({dvec4(0, 0, -1, 1), 0.0});         // far:   z <=  w
  planes.push_back({dvec4(0, 0, 0, 1), -kMinClipW});   // w >= kMinClipW (never divide by ~0)
  addGuardBand(planes, guardBand);
  return planes;
}

}  // namespace

std::vector<ClipVertex> clipTriangle(const std::array<dvec4, 3>& clip, double guardBand) {
  std::vector<ClipVertex> polygon = {
      {clip[0], dvec3(1, 0, 0)},
      {clip[1], dvec3(0, 1, 0)},
      {clip[2], dvec3(0, 0, 1)},
  };
  const std::vector<ClipPlane> planes = clipPlanes(guardBand);
  // Trivial accept: inside the last (tightest) planes means inside all of them.
  const bool allInside = std::all_of(polygon.begin(), polygon.end(), [&](const ClipVertex& v) {
    return std::all_of(planes.end() - 7, planes.end(), [&](const ClipPlane& p) { return p.distance(v.position) >= 0.0; });
  });
  if (allInside) return polygon;
  for (const ClipPlane& plane : planes) {
    polygon = clipAgainst(polygon, plane);
    if (polygon.size() < 3) return {};
  }
  return polygon;
}

// ---------------------------------------------------------------------------------
// Edge equations, plane equations, barycentric coordinates
// ---------------------------------------------------------------------------------

EdgeEquation edgeEquation(const dvec2& l, const dvec2& n) {
  return EdgeEquation{.a = l.y - n.y, .b = n.x - l.x, .c = n.y * l.x - n.x * l.y};
}

double signedArea2(const dvec2& l, const dvec2& m, const dvec2& n) {
  return (m.x - l.x) * (n.y - l.y) - (m.y - l.y) * (n.x - l.x);
}

std::optional<PlaneEquation> planeEquation(const dvec3& l, const dvec3& m, const dvec3& n) {
  // GLM matrices are built from columns; these columns are the slide's rows, hence the transpose.
  const glm::dmat3 matrix = glm::transpose(glm::dmat3(dvec3(l.x, l.y, 1.0),   // [Lx Ly 1]
                                                      dvec3(m.x, m.y, 1.0),   // [Mx My 1]
                                                      dvec3(n.x, n.y, 1.0))); // [Nx Ny 1]
  if (glm::determinant(matrix) == 0.0) return std::nullopt;
  const dvec3 abc = glm::inverse(matrix) * dvec3(l.z, m.z, n.z);
  return PlaneEquation{.a = abc.x, .b = abc.y, .c = abc.z};
}

std::optional<dvec3> barycentric(const dvec2& l, const dvec2& m, const dvec2& n, const dvec2& p) {
  const double area = signedArea2(l, m, n);
  if (area == 0.0) return std::nullopt;
  return dvec3(signedArea2(p, m, n) / area,   // α = Area(PMN) / Area(LMN)
               signedArea2(l, p, n) / area,   // β = Area(LPN) / Area(LMN)
               signedArea2(l, m, p) / area);  // γ = Area(LMP) / Area(LMN)
}

// ---------------------------------------------------------------------------------
// Fixed point and coverage
// ---------------------------------------------------------------------------------

namespace {
/// Fixed-point coordinates must stay below this (2^21 pixels) so that edge values,
/// products of two 31-bit differences plus a 60-bit constant, fit in int64.
constexpr std::int64_t kMaxFixedCoordinate = std::int64_t(1) << 29;
}  // namespace

FixedPoint snapToSubpixel(const dvec2& window) {
  // nearbyint rounds to nearest, ties to even, in the default floating-point environment.
  return FixedPoint{static_cast<std::int64_t>(std::nearbyint(window.x * double(kSubpixelOne))),
                    static_cast<std::int64_t>(std::nearbyint(window.y * double(kSubpixelOne)))};
}

FixedEdge fixedEdgeEquation(const FixedPoint& l, const FixedPoint& n) {
  return FixedEdge{.a = l.y - n.y, .b = n.x - l.x, .c = n.y * l.x - n.x * l.y};
}

std::optional<TriangleSetup> setupTriangle(const std::array<FixedPoint, 3>& v) {
  for (const FixedPoint& p : v)
    if (std::abs(p.x) > kMaxFixedCoordinate || std::abs(p.y) > kMaxFixedCoordinate)
      fail(ErrorKind::Usage, "fixed-point vertex ({}, {}) is beyond the rasterizer's range of ±2^21 pixels", p.x, p.y);

  TriangleSetup tri;
  tri.v = v;
  tri.edges = {fixedEdgeEquation(v[1], v[2]), fixedEdgeEquation(v[2], v[0]), fixedEdgeEquation(v[0], v[1])};
  // The edge opposite v0 evaluated at v0 is twice the triangle's signed area.
  tri.area2 = tri.edges[0](v[0].x, v[0].y);
  if (tri.area2 == 0) return std::nullopt;
  if (tri.area2 < 0) {
    // Clockwise: reverse the comparison sense by negating every edge, so "inside" is
    // always "all three edges positive".
    for (FixedEdge& e : tri.edges) e = FixedEdge{-e.a, -e.b, -e.c};
  }
  return tri;
}

bool ownsTies(const FixedEdge& e) {
  // (a, b) is the edge's inward normal. Left edge: interior toward +x. Bottom edge:
  // horizontal with the interior toward +y.
  return e.a > 0 || (e.a == 0 && e.b > 0);
}

bool coversSample(const TriangleSetup& tri, int px, int py) {
  const std::int64_t sx = sampleCoordinate(px);
  const std::int64_t sy = sampleCoordinate(py);
  for (const FixedEdge& e : tri.edges) {
    const std::int64_t value = e(sx, sy);
    if (value < 0) return false;
    if (value == 0 && !ownsTies(e)) return false;
  }
  return true;
}

dvec3 sampleBarycentric(const TriangleSetup& tri, int px, int py) {
  const std::int64_t sx = sampleCoordinate(px);
  const std::int64_t sy = sampleCoordinate(py);
  // Edges are orientation-normalized, so divide by |area2|: λi = E_i / (2·area) >= 0 inside.
  const double area = double(tri.area2 < 0 ? -tri.area2 : tri.area2);
  return dvec3(double(tri.edges[0](sx, sy)) / area, double(tri.edges[1](sx, sy)) / area,
               double(tri.edges[2](sx, sy)) / area);
}

}  // namespace glint::raster
