// The lecture's worked numbers and the geometry helpers: transforms, edge and plane
// equations, barycentrics, fixed point, the tie rule and clipping.

#include "glint/core/error.h"
#include "glint/raster/geometry.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <set>
#include <utility>
#include <vector>

using namespace glint;
using namespace glint::raster;

namespace {
const Viewport kLectureViewport{0, 0, 500, 500};  // glViewport(0, 0, 500, 500)

FixedPoint fixedPixels(double x, double y) { return snapToSubpixel(dvec2(x, y)); }

void expectNear(const dvec3& got, const dvec3& expected, double tolerance = 1e-12) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], expected[i], tolerance) << "component " << i;
}
}  // namespace

// ---------------------------------------------------------------------------------
// "Apply the Transforms" and "Simple Triangle Vertex Depth"
// ---------------------------------------------------------------------------------

TEST(RasterLecture, ViewportTransformOfTheSimpleTriangle) {
  // First vertex: w_x = 250·(-0.8) + 250 = 50, w_y = 250·0.8 + 250 = 450.
  const dvec3 first = viewportTransform(dvec3(-0.8, 0.8, 0.3), kLectureViewport);
  EXPECT_DOUBLE_EQ(first.x, 50.0);
  EXPECT_DOUBLE_EQ(first.y, 450.0);
  // Second vertex: the slide repeats the first vertex's arithmetic; 250·0.8 + 250 = 450 is right.
  const dvec3 second = viewportTransform(dvec3(0.8, 0.8, -0.2), kLectureViewport);
  EXPECT_DOUBLE_EQ(second.x, 450.0);
  EXPECT_DOUBLE_EQ(second.y, 450.0);
  const dvec3 third = viewportTransform(dvec3(0.0, -0.8, -0.2), kLectureViewport);
  EXPECT_DOUBLE_EQ(third.x, 250.0);
  EXPECT_DOUBLE_EQ(third.y, 50.0);
  // glDepthRange(0, 1): wz = z/2 + 1/2 → 0.65, 0.4, 0.4.
  EXPECT_NEAR(first.z, 0.65, 1e-15);
  EXPECT_NEAR(second.z, 0.4, 1e-15);
  EXPECT_NEAR(third.z, 0.4, 1e-15);
}

TEST(RasterLecture, WindowZIsHalfZPlusHalfForTheDefaultRange) {
  for (double z = -1.0; z <= 1.0; z += 0.125) EXPECT_DOUBLE_EQ(viewportTransform(dvec3(0, 0, z), kLectureViewport).z, 0.5 * z + 0.5);
}

TEST(RasterTransform, ViewportOffsetDepthRangeAndClipToWindow) {
  const Viewport vp{10, 20, 100, 50};
  const DepthRange range{0.2, 0.6};
  expectNear(viewportTransform(dvec3(-1, -1, -1), vp, range), dvec3(10, 20, 0.2));
  expectNear(viewportTransform(dvec3(1, 1, 1), vp, range), dvec3(110, 70, 0.6));
  EXPECT_NEAR(viewportTransform(dvec3(0, 0, 0), vp, range).z, 0.4, 1e-15);
  // Reversed range: near maps to 1, far to 0.
  EXPECT_DOUBLE_EQ(viewportTransform(dvec3(0, 0, -1), vp, DepthRange{1.0, 0.0}).z, 1.0);
  EXPECT_DOUBLE_EQ(viewportTransform(dvec3(0, 0, 0.5), vp, DepthRange{1.0, 0.0}).z, 0.25);
  // glDepthRange clamps to [0, 1].
  EXPECT_DOUBLE_EQ(viewportTransform(dvec3(0, 0, 1), vp, DepthRange{-3.0, 7.0}).z, 1.0);
  EXPECT_DOUBLE_EQ(viewportTransform(dvec3(0, 0, -1), vp, DepthRange{-3.0, 7.0}).z, 0.0);
  // Perspective divide first: clip (2, -2, 1, 4) is NDC (0.5, -0.5, 0.25).
  EXPECT_EQ(perspectiveDivide(dvec4(2, -2, 1, 4)), dvec3(0.5, -0.5, 0.25));
  expectNear(clipToWindow(dvec4(2, -2, 1, 4), vp, range), dvec3(85, 32.5, 0.45));
}

TEST(RasterTransform, ViewportIsClampedLikeGlViewport) {
  EXPECT_THROW(clampViewport(Viewport{0, 0, -1, 10}), Error);
  EXPECT_THROW(clampViewport(Viewport{0, 0, 10, -1}), Error);
  EXPECT_EQ(clampViewport(Viewport{-100000, 100000, 99999, 20000}),
            (Viewport{kViewportBoundsMin, kViewportBoundsMax, kMaxViewportDim, kMaxViewportDim}));
  EXPECT_EQ(effectiveViewport(State{}, 64, 32), (Viewport{0, 0, 64, 32}));
  EXPECT_EQ(effectiveViewport(State{.viewport = Viewport{1, 2, 3, 4}}, 64, 32), (Viewport{1, 2, 3, 4}));
}

// ---------------------------------------------------------------------------------
// "Edge Equation Setup" and "Look at the LN edge"
// ---------------------------------------------------------------------------------

TEST(RasterLecture, EdgeCoefficientsOfTheLnEdge) {
  const dvec2 l(450, 450), n(50, 450);
  const EdgeEquation e = edgeEquation(l, n);
  EXPECT_EQ(e.a, 0.0);          // A = Ly - Ny = 450 - 450
  EXPECT_EQ(e.b, -400.0);       // B = Nx - Lx = 50 - 450
  EXPECT_EQ(e.c, 180000.0);     // C = Ny·Lx - Nx·Ly
  EXPECT_EQ(e(250, 250), 80000.0);  // 0·250 - 400·250 + 180000 > 0: (250, 250) is in
  // The expansion is the determinant |N - L; P - L|.
  const dvec2 p(123, 321);
  EXPECT_EQ(e(p.x, p.y), (n.x - l.x) * (p.y - l.y) - (n.y - l.y) * (p.x - l.x));
  // Exact fixed-point version: coefficients scale by 256 (a, b) and 256² (c).
  const FixedEdge f = fixedEdgeEquation(fixedPixels(450, 450), fixedPixels(50, 450));
  EXPECT_EQ(f.a, 0);
  EXPECT_EQ(f.b, -400 * 256);
  EXPECT_EQ(f.c, 180000LL * 256 * 256);
  EXPECT_EQ(f(250 * 256, 250 * 256), 80000LL * 256 * 256);
}

TEST(RasterLecture, AllThreeEdgeDeterminantsAndTheReversedSense) {
  // L, M, N from the slides (window space), P the centre (250, 250).
  const dvec2 l(450, 450), m(250, 50), n(50, 450);
  auto det = [](dvec2 a, dvec2 b) { return a.x * b.y - a.y * b.x; };
  auto allThree = [&](dvec2 L, dvec2 M, dvec2 N, dvec2 P) {
    return std::array<double, 3>{det(N - P, M - P), det(N - L, P - L), det(P - L, M - L)};
  };
  EXPECT_GT(det(n - l, m - l), 0.0);  // this ordering needs no reversal
  for (double v : allThree(l, m, n, dvec2(250, 250))) EXPECT_GT(v, 0.0);
  // A point outside fails at least one.
  bool anyNegative = false;
  for (double v : allThree(l, m, n, dvec2(60, 60))) anyNegative |= v < 0.0;
  EXPECT_TRUE(anyNegative);
  // Swap M and N: the orientation determinant is negative and the inside test flips sign.
  EXPECT_LT(det(m - l, n - l), 0.0);
  for (double v : allThree(l, n, m, dvec2(250, 250))) EXPECT_LT(v, 0.0);
  // The edge equation helper is the middle determinant.
  EXPECT_EQ(edgeEquation(l, n)(250, 250), det(n - l, dvec2(250, 250) - l));
}

// ---------------------------------------------------------------------------------
// "Setup Plane Equation", "Interpolating Window Space Z", barycentrics
// ---------------------------------------------------------------------------------

TEST(RasterLecture, ZPlaneEquation) {
  const std::optional<PlaneEquation> z = planeEquation(dvec3(50, 450, 0.65), dvec3(250, 50, 0.4), dvec3(450, 450, 0.4));
  ASSERT_TRUE(z);
  EXPECT_NEAR(z->a, -0.000625, 1e-15);
  EXPECT_NEAR(z->b, 0.0003125, 1e-15);
  EXPECT_NEAR(z->c, 0.540625, 1e-13);
  // It reproduces the vertex depths.
  EXPECT_NEAR((*z)(50, 450), 0.65, 1e-13);
  EXPECT_NEAR((*z)(250, 50), 0.4, 1e-13);
  EXPECT_NEAR((*z)(450, 450), 0.4, 1e-13);
  // Collinear points have no plane.
  EXPECT_FALSE(planeEquation(dvec3(0, 0, 1), dvec3(1, 1, 2), dvec3(2, 2, 3)));
}

TEST(RasterLecture, PlaneEquationsAndBarycentricsAgree) {
  // The simple triangle in window space with its colours: red (50,450), blue (250,50),
  // green (450,450), and window z.
  const dvec2 L(50, 450), M(250, 50), N(450, 450);
  const dvec4 attrL(1, 0, 0, 0.65), attrM(0, 0, 1, 0.4), attrN(0, 1, 0, 0.4);
  std::array<PlaneEquation, 4> planes;
  for (int c = 0; c < 4; ++c)
    planes[std::size_t(c)] = *planeEquation(dvec3(L, attrL[c]), dvec3(M, attrM[c]), dvec3(N, attrN[c]));
  for (double y = 0.5; y < 500; y += 7.25) {
    for (double x = 0.5; x < 500; x += 6.5) {
      const dvec3 bary = *barycentric(L, M, N, dvec2(x, y));
      EXPECT_NEAR(bary.x + bary.y + bary.z, 1.0, 1e-12);
      for (int c = 0; c < 4; ++c) {
        const double byBary = bary.x * attrL[c] + bary.y * attrM[c] + bary.z * attrN[c];
        EXPECT_NEAR(planes[std::size_t(c)](x, y), byBary, 1e-12) << "at " << x << ", " << y << " channel " << c;
      }
    }
  }
}

TEST(RasterGeometry, BarycentricBasics) {
  const dvec2 a(0, 0), b(4, 0), c(0, 4);
  EXPECT_EQ(*barycentric(a, b, c, a), dvec3(1, 0, 0));
  EXPECT_EQ(*barycentric(a, b, c, b), dvec3(0, 1, 0));
  EXPECT_EQ(*barycentric(a, b, c, c), dvec3(0, 0, 1));
  EXPECT_EQ(*barycentric(a, b, c, dvec2(1, 1)), dvec3(0.5, 0.25, 0.25));
  EXPECT_FALSE(barycentric(a, a, c, dvec2(1, 1)));
  EXPECT_EQ(signedArea2(a, b, c), 16.0);   // counter-clockwise (y up) is positive
  EXPECT_EQ(signedArea2(a, c, b), -16.0);
}

TEST(RasterGeometry, SampleBarycentricMatchesTheAreaRatios) {
  const std::array<dvec2, 3> w = {dvec2(3.25, 1.5), dvec2(40.75, 9.0), dvec2(12.5, 33.125)};  // on the 1/256 grid
  const TriangleSetup tri = *setupTriangle({snapToSubpixel(w[0]), snapToSubpixel(w[1]), snapToSubpixel(w[2])});
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 44; ++x) {
      const dvec3 expected = *barycentric(w[0], w[1], w[2], dvec2(x + 0.5, y + 0.5));
      const dvec3 got = sampleBarycentric(tri, x, y);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], expected[i], 1e-12);
    }
}

// ---------------------------------------------------------------------------------
// Fixed point and the tie rule
// ---------------------------------------------------------------------------------

TEST(RasterFixedPoint, SnapsToTheNearestSixteenthOfASixteenth) {
  EXPECT_EQ(snapToSubpixel(dvec2(50, 450)), (FixedPoint{12800, 115200}));
  EXPECT_EQ(snapToSubpixel(dvec2(0.25, -0.25)), (FixedPoint{64, -64}));
  EXPECT_EQ(snapToSubpixel(dvec2(1.0 / 512, 3.0 / 512)), (FixedPoint{0, 2}));  // ties to even
  EXPECT_EQ(snapToSubpixel(dvec2(0.0014, -0.0025)), (FixedPoint{0, -1}));
  EXPECT_EQ(kSubpixelOne, 256);
  EXPECT_EQ(sampleCoordinate(0), 128);
  EXPECT_EQ(sampleCoordinate(-1), -128);
}

TEST(RasterTieRule, OwnershipOfEdges) {
  EXPECT_TRUE(ownsTies(FixedEdge{1, 0, 0}));    // left edge (interior toward +x)
  EXPECT_TRUE(ownsTies(FixedEdge{1, -5, 0}));
  EXPECT_FALSE(ownsTies(FixedEdge{-1, 5, 0}));  // right edge
  EXPECT_TRUE(ownsTies(FixedEdge{0, 1, 0}));    // bottom edge (interior toward +y)
  EXPECT_FALSE(ownsTies(FixedEdge{0, -1, 0}));  // top edge
}

TEST(RasterTieRule, DiagonalOfASquareIsDrawnOnce) {
  // A 4×4 pixel square split along y = x, which passes through the centres of (i, i).
  const FixedPoint p00 = fixedPixels(0, 0), p40 = fixedPixels(4, 0), p44 = fixedPixels(4, 4), p04 = fixedPixels(0, 4);
  for (bool reverse : {false, true}) {  // the winding must not matter
    const auto lower = reverse ? setupTriangle({p00, p44, p40}) : setupTriangle({p00, p40, p44});
    const auto upper = reverse ? setupTriangle({p00, p04, p44}) : setupTriangle({p00, p44, p04});
    ASSERT_TRUE(lower && upper);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const int count = int(coversSample(*lower, x, y)) + int(coversSample(*upper, x, y));
        EXPECT_EQ(count, 1) << x << ", " << y;
        // The diagonal is a left edge of the lower-right triangle, so it owns (i, i).
        if (x == y) { EXPECT_TRUE(coversSample(*lower, x, y)); }
      }
  }
}

TEST(RasterTieRule, BottomAndLeftEdgesAreInTopAndRightAreOut) {
  // Rectangle [0.5, 3.5] × [0.5, 2.5] in pixels: its edges run through pixel centres.
  const FixedPoint a = fixedPixels(0.5, 0.5), b = fixedPixels(3.5, 0.5), c = fixedPixels(3.5, 2.5), d = fixedPixels(0.5, 2.5);
  const auto t1 = setupTriangle({a, b, c});
  const auto t2 = setupTriangle({a, c, d});
  ASSERT_TRUE(t1 && t2);
  std::set<std::pair<int, int>> covered;
  for (int y = -1; y < 5; ++y)
    for (int x = -1; x < 6; ++x)
      if (coversSample(*t1, x, y) || coversSample(*t2, x, y)) covered.insert({x, y});
  // Columns 0..2 (x = 0.5 left edge in, x = 3.5 right edge out), rows 0..1 (bottom in, top out).
  std::set<std::pair<int, int>> expected;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) expected.insert({x, y});
  EXPECT_EQ(covered, expected);
}

TEST(RasterTieRule, ZeroAreaHasNoSetup) {
  EXPECT_FALSE(setupTriangle({fixedPixels(0, 0), fixedPixels(1, 1), fixedPixels(2, 2)}));
  EXPECT_FALSE(setupTriangle({fixedPixels(3, 1), fixedPixels(3, 1), fixedPixels(5, 7)}));
  EXPECT_THROW(setupTriangle({FixedPoint{std::int64_t(1) << 40, 0}, fixedPixels(0, 0), fixedPixels(0, 1)}), Error);
}

// ---------------------------------------------------------------------------------
// Clipping
// ---------------------------------------------------------------------------------

TEST(RasterClip, InsideTriangleIsUntouched) {
  const std::array<dvec4, 3> t = {dvec4(-0.5, -0.5, 0, 1), dvec4(0.5, -0.5, 0.2, 1), dvec4(0, 0.5, -0.3, 2)};
  const std::vector<ClipVertex> poly = clipTriangle(t);
  ASSERT_EQ(poly.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(poly[std::size_t(i)].position, t[std::size_t(i)]);
    EXPECT_EQ(poly[std::size_t(i)].weights[i], 1.0);
  }
}

TEST(RasterClip, NearPlaneCutIsOnThePlaneWithConsistentWeights) {
  // One vertex behind the eye (w < 0).
  const std::array<dvec4, 3> t = {dvec4(-0.5, -0.5, 0.5, 1), dvec4(0.5, -0.5, 0.5, 1), dvec4(0, 0.5, -3, -1)};
  const std::vector<ClipVertex> poly = clipTriangle(t);
  ASSERT_EQ(poly.size(), 4u);
  for (const ClipVertex& v : poly) {
    EXPECT_GE(v.position.z + v.position.w, -1e-12);
    EXPECT_NEAR(v.weights.x + v.weights.y + v.weights.z, 1.0, 1e-12);
    const dvec4 fromWeights = v.weights.x * t[0] + v.weights.y * t[1] + v.weights.z * t[2];
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(v.position[c], fromWeights[c], 1e-12);
    EXPECT_GT(v.position.w, 0.0);
  }
  // Edge v1 → v2 has d = z + w = 1.5 at v1 and -4 at v2: t = 1.5 / 5.5.
  const double tCut = 1.5 / 5.5;
  bool found = false;
  for (const ClipVertex& v : poly) found |= std::abs(v.weights.y - (1 - tCut)) < 1e-12 && std::abs(v.weights.z - tCut) < 1e-12;
  EXPECT_TRUE(found);
}

TEST(RasterClip, SharedEdgeCutsAreBitIdentical) {
  // Two triangles sharing edge (p, q), listed in opposite directions, q behind the near plane.
  const dvec4 p(0.3, -0.7, 0.1, 1.1), q(-0.4, 0.9, -7.3, 0.7), r1(0.9, 0.8, 0.2, 1.3), r2(-0.9, -0.8, 0.4, 1.7);
  const auto a = clipTriangle({p, q, r1});
  const auto b = clipTriangle({q, p, r2});
  std::vector<dvec4> cutsA, cutsB;
  auto onPq = [](const ClipVertex& v, int ip, int iq) { return v.weights[3 - ip - iq] == 0.0 && v.weights[ip] != 1.0 && v.weights[iq] != 1.0; };
  for (const ClipVertex& v : a)
    if (onPq(v, 0, 1)) cutsA.push_back(v.position);
  for (const ClipVertex& v : b)
    if (onPq(v, 1, 0)) cutsB.push_back(v.position);
  ASSERT_EQ(cutsA.size(), 1u);
  ASSERT_EQ(cutsB.size(), 1u);
  EXPECT_EQ(cutsA[0], cutsB[0]);  // bitwise equal, not just close
}

TEST(RasterClip, OutsideAndBehindAreRemoved) {
  EXPECT_TRUE(clipTriangle({dvec4(0, 0, 2, 1), dvec4(1, 0, 3, 1), dvec4(0, 1, 5, 1)}).empty());      // beyond far
  EXPECT_TRUE(clipTriangle({dvec4(0, 0, 0, -1), dvec4(1, 0, 0, -1), dvec4(0, 1, 0, -2)}).empty());   // w < 0
  EXPECT_TRUE(clipTriangle({dvec4(0, 0, 0, 0), dvec4(0, 0, 0, 0), dvec4(0, 0, 0, 0)}).empty());      // w = 0
  // Right of the view volume: removed by the default band (1 = the viewport's edges) ...
  const std::array<dvec4, 3> right = {dvec4(10, 0, 0, 1), dvec4(11, 0, 0, 1), dvec4(10, 1, 0, 1)};
  EXPECT_TRUE(clipTriangle(right).empty());
  // ... but kept by a 64× guard band, and removed by it once beyond.
  EXPECT_EQ(clipTriangle(right, 64.0).size(), 3u);
  EXPECT_TRUE(clipTriangle({dvec4(100, 0, 0, 1), dvec4(101, 0, 0, 1), dvec4(100, 1, 0, 1)}, 64.0).empty());
}
