// The maps baked beside the normal map (issue 23): bent normals, thickness, curvature,
// position and opacity, each against an analytic answer computed here (nothing shared with the baker
// but the meshes), plus what they must not change: the normal map, determinism, the cost
// of a plain bake.
#include "bake_test_util.h"

#include "glint/bake/baker.h"
#include "glint/bake/output.h"
#include "glint/core/error.h"
#include "glint/core/log.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

using namespace glint;
using namespace bake_test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

Mesh flipped(Mesh m) {
  for (std::size_t i = 0; i < m.indices.size(); i += 3) std::swap(m.indices[i + 1], m.indices[i + 2]);
  for (vec3& n : m.normals) n = -n;
  return m;
}

vec3 decoded(const Image& image, int x, int row) { return texel(image, x, row) * 2.0f - 1.0f; }

bool inIsland(const bake::BakeResult& r, int x, int row) { return r.coverage.at(x, row, 0) > 0.99f; }

}  // namespace

// On a convex shape nothing occludes the hemisphere: the bent normal is the normal, up to
// the Monte Carlo error of the mean of k cosine-weighted directions. It is noise, not bias:
// with the stratified set it falls as 1/k (measured here, mean / worst: 16 rays 2.77° /
// 5.42°, 64 rays 0.72° / 1.42°, 256 rays 0.19° / 0.35°, 1024 rays 0.05° / 0.09°), so the
// bounds are those of 64 rays with some room: mean 1°, worst 2°.
TEST(BakeExtraMaps, BentNormalOnAConvexSphereIsTheNormal) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeUvSphere(1.0f, 128, 64);
  const Mesh low = makeUvSphere(1.0f, 16, 8);
  bake::BakeOptions options;
  options.width = options.height = 48;
  options.maps.add(bake::Map::BentNormal);  // without ambientOcclusion: the AO rays are cast anyway
  options.aoSamples = 64;
  options.aoDistance = {10.0f, false};
  const auto r = bake::bake(low, high, options);
  ASSERT_FALSE(r.map(bake::Map::BentNormal).empty());
  EXPECT_TRUE(r.map(bake::Map::Ao).empty());
  EXPECT_EQ(r.map(bake::Map::BentNormal).channels(), 3);
  EXPECT_EQ(r.stats.aoRays, r.stats.hits * 64u);
  double sum = 0, worst = 0;
  int n = 0;
  for (int row = 0; row < 48; ++row)
    for (int x = 0; x < 48; ++x) {
      if (!inIsland(r, x, row)) continue;
      const double a = angleDeg(glm::dvec3(decoded(r.normal, x, row)), glm::dvec3(decoded(r.map(bake::Map::BentNormal), x, row)));
      sum += a;
      worst = std::max(worst, a);
      ++n;
    }
  std::printf("bent vs normal on a sphere: mean %.3f°, worst %.3f° (%d texels, 64 rays)\n", sum / n, worst, n);
  EXPECT_GT(n, 1500);
  EXPECT_LT(sum / n, 1.0);
  EXPECT_LT(worst, 2.0);

  // The same rays as an AO bake's: asking for AO too changes nothing in the bent map.
  options.maps.add(bake::Map::Ao);
  const auto both = bake::bake(low, high, options);
  EXPECT_TRUE(both.map(bake::Map::BentNormal) == r.map(bake::Map::BentNormal));
  EXPECT_EQ(both.stats.aoRays, r.stats.aoRays);
}

// A floor next to a tall wall: the wall hides every direction towards it (d.x < 0), so the
// unoccluded set is the half hemisphere facing away. The mean of cosine-weighted directions
// over that half is (2/(3π), 1/3, 0) (Malley: a uniform disk lifted onto the hemisphere),
// a tilt of atan(2/π) = 32.48° away from the wall, whatever the distance to it.
TEST(BakeExtraMaps, BentNormalTiltsAwayFromAWall) {
  log::setLevel(log::Level::Error);
  const Mesh low = makePlane(2.0f);  // [-1, 1]² at y = 0, normal +Y
  Mesh high = makePlane(2.0f);
  Mesh wall = makePlane(400.0f);  // rotated to face +X, at x = -1.5, from y = -1 to 399
  wall.transform(glm::translate(mat4(1.0f), vec3(-1.5f, 199.0f, 0.0f)) *
                 glm::rotate(mat4(1.0f), -0.5f * float(kPiD), vec3(0.0f, 0.0f, 1.0f)));
  high.append(wall);
  bake::BakeOptions options;
  options.width = options.height = 16;
  options.space = NormalSpace::Object;
  options.maps.add(bake::Map::BentNormal);
  options.maps.add(bake::Map::Ao);
  options.aoSamples = 256;
  options.aoDistance = {10000.0f, false};
  options.maxFront = options.maxRear = {0.01f, false};
  const auto r = bake::bake(low, high, options);
  const glm::dvec3 expected = glm::normalize(glm::dvec3(2.0 / kPiD, 1.0, 0.0));
  double sum = 0, worst = 0, aoWorst = 0;
  for (int row = 0; row < 16; ++row)
    for (int x = 0; x < 16; ++x) {
      const double a = angleDeg(glm::dvec3(decoded(r.map(bake::Map::BentNormal), x, row)), expected);
      sum += a;
      worst = std::max(worst, a);
      aoWorst = std::max(aoWorst, std::abs(r.map(bake::Map::Ao).at(x, row, 0) - 0.5));  // half the cosine-weighted hemisphere
    }
  std::printf("bent normal beside a wall: tilt %.2f° expected, mean error %.3f°, worst %.3f°; AO worst |ao - 0.5| %.4f\n",
              glm::degrees(std::atan(2.0 / kPiD)), sum / 256, worst, aoWorst);
  EXPECT_LT(sum / 256, 0.5);
  EXPECT_LT(worst, 1.5);
  EXPECT_LT(aoWorst, 0.02);
}

// In world space the bent normal goes through the same transform as the normal map: the
// object-space bent normal rotated by objectToWorld (exact to float rounding). The normal
// map's own world-space check is BakeMaps.ObjectWorldAndDirectXEncodings.
TEST(BakeExtraMaps, WorldSpaceIsTheRotatedObjectSpace) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeTorus(1.0f, 0.35f, 96, 48);
  const Mesh low = makeTorus(1.0f, 0.35f, 12, 6);
  bake::BakeOptions options;
  options.width = options.height = 40;
  options.maps.add(bake::Map::BentNormal);
  options.aoSamples = 8;
  options.space = NormalSpace::Object;
  const auto object = bake::bake(low, high, options);
  options.space = NormalSpace::World;
  const mat4 rotation = glm::rotate(mat4(1.0f), 0.7f, vec3(0.3f, 1.0f, 0.2f));
  options.objectToWorld = glm::translate(mat4(1.0f), vec3(5.0f, -2.0f, 1.0f)) * glm::scale(rotation, vec3(2.0f));
  const auto world = bake::bake(low, high, options);
  double worstNormal = 0, worstBent = 0;
  for (int row = 0; row < 40; ++row)
    for (int x = 0; x < 40; ++x) {
      const auto rotated = [&](const Image& image) { return vec3(rotation * vec4(decoded(image, x, row), 0.0f)); };
      worstNormal = std::max(worstNormal, double(glm::length(rotated(object.normal) - decoded(world.normal, x, row))));
      worstBent = std::max(worstBent, double(glm::length(rotated(object.map(bake::Map::BentNormal)) - decoded(world.map(bake::Map::BentNormal), x, row))));
    }
  std::printf("world vs rotated object space: normal %.2g, bent %.2g\n", worstNormal, worstBent);
  EXPECT_LT(worstNormal, 1e-5);
  EXPECT_LT(worstBent, 1e-5);
}

// A ray entering a sphere of radius r at angle θ to the inward normal travels 2r·cosθ;
// cosine-weighted (pdf 2·cosθ in cosθ), the mean chord is 2r·E[cosθ] = 4r/3.
TEST(BakeExtraMaps, ThicknessOfASphereIsTheMeanChord) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeUvSphere(1.0f, 128, 64);
  const Mesh low = makeUvSphere(1.0f, 16, 8);
  bake::BakeOptions options;
  options.width = options.height = 32;
  options.maps.add(bake::Map::Thickness);
  options.aoSamples = 64;
  options.thicknessDistance = {2.5f, false};  // longer than the longest chord: no ray is capped
  const auto r = bake::bake(low, high, options);
  ASSERT_FALSE(r.map(bake::Map::Thickness).empty());
  EXPECT_EQ(r.stats.thicknessRays, r.stats.hits * 64u);
  EXPECT_EQ(r.stats.aoRays, 0u);
  const double expected = 4.0 / 3.0 / 2.5;
  double sum = 0, worst = 0;
  int n = 0;
  for (int row = 0; row < 32; ++row)
    for (int x = 0; x < 32; ++x) {
      if (!inIsland(r, x, row)) continue;
      const double e = r.map(bake::Map::Thickness).at(x, row, 0) - expected;
      sum += e;
      worst = std::max(worst, std::abs(e));
      ++n;
    }
  std::printf("sphere thickness: expected %.4f, mean error %+.5f, worst %.4f (%d texels, 64 rays)\n", expected, sum / n,
              worst, n);
  EXPECT_LT(std::abs(sum / n), 0.005);  // the faceted sphere's chords are a hair shorter
  EXPECT_LT(worst, 0.02);               // 64 stratified rays per texel
}

// A slab of thickness t under the low poly's plane: a ray at angle θ to the inward normal
// leaves through the bottom after t / cosθ, capped at D. Cosine-weighted:
// E[min(t/c, D)] = ∫ min(t/c, D) 2c dc = 2t − t²/D, so the map reads 2t/D − t²/D².
TEST(BakeExtraMaps, ThicknessOfASlab) {
  log::setLevel(log::Level::Error);
  const Mesh low = makePlane(2.0f);
  Mesh high = makePlane(6.0f);  // top at y = 0; the bottom faces down at y = -t
  const float t = 0.2f;
  Mesh bottom = flipped(makePlane(6.0f));
  bottom.transform(glm::translate(mat4(1.0f), vec3(0.0f, -t, 0.0f)));
  high.append(bottom);
  bake::BakeOptions options;
  options.width = options.height = 16;
  options.maps.add(bake::Map::Thickness);
  options.aoSamples = 256;
  options.maxFront = options.maxRear = {0.01f, false};
  for (const float D : {1.0f, 0.5f, 0.15f}) {
    options.thicknessDistance = {D, false};
    const auto r = bake::bake(low, high, options);
    const double expected = D <= t ? 1.0 : 2.0 * t / D - double(t) * t / (double(D) * D);
    double worst = 0;
    for (int row = 0; row < 16; ++row)
      for (int x = 0; x < 16; ++x) worst = std::max(worst, std::abs(r.map(bake::Map::Thickness).at(x, row, 0) - expected));
    std::printf("slab t = %.2f, D = %.2f: expected %.4f, worst error %.5f\n", t, D, expected, worst);
    EXPECT_LT(worst, D <= t ? 1e-6 : 0.01) << "D = " << D;
  }
}

// Curvature of a sphere of radius R is 1/R in every direction, and the measure (normal
// differences to points at the radius) is exact on a sphere at any radius: what is left is
// the faceting of the 128×64 high poly (its interpolated normals are exact at the vertices
// only). Measured (mean / worst relative error): R = 1 and R = 0.25 alike, 0.028 % /
// 0.043 %; the bounds leave room: 0.2 % mean, 0.5 % worst. The 8-bit file reads
// 0.5 + 0.5·r/R (0.517 at the default radius), to half a step.
TEST(BakeExtraMaps, CurvatureOfASphereIsOneOverTheRadius) {
  log::setLevel(log::Level::Error);
  for (const float R : {1.0f, 0.25f}) {
    const Mesh high = makeUvSphere(R, 128, 64);
    const Mesh low = makeUvSphere(R, 16, 8);
    bake::BakeOptions options;
    options.width = options.height = 48;
    options.maps.add(bake::Map::Curvature);  // the default radius: 1 % of the low poly's diagonal
    const auto r = bake::bake(low, high, options);
    ASSERT_FALSE(r.map(bake::Map::Curvature).empty());
    EXPECT_EQ(r.map(bake::Map::Curvature).channels(), 1);
    EXPECT_FLOAT_EQ(r.stats.curvatureRadius, 0.01f * low.bounds().diagonal());
    EXPECT_GE(r.stats.curvatureRays, r.stats.hits * 8u);
    EXPECT_EQ(r.stats.aoRays + r.stats.thicknessRays, 0u);
    const Image u8 = bake::curvatureForOutput(r.map(bake::Map::Curvature), PixelType::U8, r.stats.curvatureRadius);
    const double expected = 1.0 / R, expected8 = 0.5 + 0.5 * r.stats.curvatureRadius / R;
    double sum = 0, worst = 0, worst8 = 0;
    int n = 0;
    for (int row = 0; row < 48; ++row)
      for (int x = 0; x < 48; ++x) {
        if (!inIsland(r, x, row)) continue;
        const double e = (r.map(bake::Map::Curvature).at(x, row, 0) - expected) / expected;
        sum += e;
        worst = std::max(worst, std::abs(e));
        worst8 = std::max(worst8, std::abs(u8.at(x, row, 0) - expected8));
        ++n;
      }
    std::printf("sphere curvature, R = %.2f: expected %.3f, mean relative error %+.5f, worst %.5f; 8-bit %.4f, worst "
                "error %.4f (%d texels)\n", R, expected, sum / n, worst, expected8, worst8, n);
    EXPECT_GT(n, 1500);
    EXPECT_LT(std::abs(sum / n), 0.002);
    EXPECT_LT(worst, 0.005);
    EXPECT_LT(worst8, 1.0 / 255.0);  // quantization (half a step) and the curvature's 0.5 %
  }
}

// Thickness and curvature measured at the high poly's vertices and interpolated (bake
// trace.h, VertexCache): a 512×256 bake of the 128×64 sphere has 16 samples a vertex and
// triangles (edges ≤ 0.05) far smaller than D = 2.5 and r = 0.2, so both maps take that
// path. The analytic answers are those of the per-texel tests above (4/3 · R / D; 1/R);
// the bounds are theirs too, and the whole bake must cast fewer rays than per texel and
// give the same maps and counts on one thread as on two.
TEST(BakeExtraMaps, ThicknessAndCurvatureAtVerticesOfADenseSphere) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeUvSphere(1.0f, 128, 64);
  const Mesh low = makeUvSphere(1.0f, 16, 8);
  bake::BakeOptions options;
  options.width = 512;
  options.height = 256;
  options.maps.add(bake::Map::Thickness);
  options.maps.add(bake::Map::Curvature);
  options.aoSamples = 16;
  options.thicknessDistance = {2.5f, false};
  options.curvatureRadius = {0.2f, false};
  const auto r = bake::bake(low, high, options);
  // Each of the sphere's vertices (poles and seam joined: 127 × 63 + 2 + 63 along the
  // seam, at most) measured once per map.
  EXPECT_GT(r.stats.vertexMeasurements, 2u * 7000u);
  EXPECT_LE(r.stats.vertexMeasurements, 2u * std::uint64_t(high.vertexCount()));
  EXPECT_LT(r.stats.thicknessRays, r.stats.hits * 16u / 2u);  // per texel it would be hits × 16
  EXPECT_LT(r.stats.curvatureRays, r.stats.hits * 8u / 2u);
  const double thick = 4.0 / 3.0 / 2.5;
  double sumT = 0, worstT = 0, sumC = 0, worstC = 0;
  int n = 0;
  for (int row = 0; row < 256; ++row)
    for (int x = 0; x < 512; ++x) {
      if (!inIsland(r, x, row)) continue;
      const double t = r.map(bake::Map::Thickness).at(x, row, 0) - thick, c = r.map(bake::Map::Curvature).at(x, row, 0) - 1.0;
      sumT += t;
      worstT = std::max(worstT, std::abs(t));
      sumC += c;
      worstC = std::max(worstC, std::abs(c));
      ++n;
    }
  std::printf("sphere at vertices: thickness mean error %+.5f, worst %.4f; curvature mean relative error %+.5f, worst "
              "%.5f (%d texels, %llu vertex measurements)\n", sumT / n, worstT, sumC / n, worstC, n,
              static_cast<unsigned long long>(r.stats.vertexMeasurements));
  EXPECT_GT(n, 100000);
  EXPECT_LT(std::abs(sumT / n), 0.005);
  EXPECT_LT(worstT, 0.02);
  EXPECT_LT(std::abs(sumC / n), 0.002);
  EXPECT_LT(worstC, 0.005);
  // The same on one thread: each vertex is measured once, by whichever sample comes first.
  const auto one = [&] {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    return bake::bake(low, high, options);
  }();
  EXPECT_EQ(one.stats.vertexMeasurements, r.stats.vertexMeasurements);
  EXPECT_EQ(one.stats.thicknessRays, r.stats.thicknessRays);
  EXPECT_EQ(one.stats.curvatureRays, r.stats.curvatureRays);
  EXPECT_TRUE(std::equal(one.map(bake::Map::Thickness).pixels<float>().begin(), one.map(bake::Map::Thickness).pixels<float>().end(),
                         r.map(bake::Map::Thickness).pixels<float>().begin()));
  EXPECT_TRUE(std::equal(one.map(bake::Map::Curvature).pixels<float>().begin(), one.map(bake::Map::Curvature).pixels<float>().end(),
                         r.map(bake::Map::Curvature).pixels<float>().begin()));
}

// A torus (ring radius a = 1 around +Y, tube radius b = 0.6: fat enough that its inner side
// is saddle-shaped with negative mean curvature) against the analytic mean curvature at
// each texel's own hit point (the position map of the same bake):
//   H = (a + 2b cos v) / (2b (a + b cos v)),  cos v = (√(x² + z²) − a) / b,
// convex positive (κ_tube = 1/b, κ_ring = cos v / (a + b cos v)): from +1.10 on the outer
// equator to −0.42 on the inner one. Errors: the measure's own, which falls as r² (r = 0.02:
// (r/b)² ≈ 0.1 %), and the 192×96 high poly's faceting. Measured: mean |error| 0.00085,
// worst 0.0040 (1 / scene units; H spans 1.56); bounds 0.005 and 0.02 (0.3 % and 1.3 %
// of the range).
TEST(BakeExtraMaps, CurvatureOfATorusIsTheAnalyticMeanCurvature) {
  log::setLevel(log::Level::Error);
  const double a = 1.0, b = 0.6;
  const Mesh high = makeTorus(float(a), float(b), 192, 96);
  const Mesh low = makeTorus(float(a), float(b), 24, 12);
  bake::BakeOptions options;
  options.width = options.height = 64;
  options.maps.add(bake::Map::Curvature).add(bake::Map::Position);
  options.curvatureRadius = {0.02f, false};
  options.maxFront = options.maxRear = {0.1f, false};
  const auto r = bake::bake(low, high, options);
  const Image u8 = bake::curvatureForOutput(r.map(bake::Map::Curvature), PixelType::U8, 0.3f);
  double sum = 0, worst = 0, lowest = 1e9, highest = -1e9;
  int n = 0, convexBright = 0, concaveDark = 0, convex = 0, concave = 0;
  for (int row = 0; row < 64; ++row)
    for (int x = 0; x < 64; ++x) {
      if (!inIsland(r, x, row)) continue;
      const glm::dvec3 p(texel(r.map(bake::Map::Position), x, row));
      const double cv = (std::sqrt(p.x * p.x + p.z * p.z) - a) / b;
      const double H = (a + 2.0 * b * cv) / (2.0 * b * (a + b * cv));
      const double e = std::abs(r.map(bake::Map::Curvature).at(x, row, 0) - H);
      sum += e;
      worst = std::max(worst, e);
      lowest = std::min(lowest, H);
      highest = std::max(highest, H);
      ++n;
      // The 8-bit file (scale 0.3): bright where convex, dark where concave, away from H = 0.
      if (H > 0.1) convexBright += u8.at(x, row, 0) > 0.5f, ++convex;
      if (H < -0.1) concaveDark += u8.at(x, row, 0) < 0.5f, ++concave;
    }
  std::printf("torus curvature: H from %.3f to %.3f; mean |error| %.5f, worst %.5f (%d texels); 8-bit: %d/%d convex "
              "bright, %d/%d concave dark\n", lowest, highest, sum / n, worst, n, convexBright, convex, concaveDark, concave);
  EXPECT_GT(n, 3000);
  EXPECT_LT(lowest, -0.4);  // the inner side was baked
  EXPECT_LT(sum / n, 0.005);
  EXPECT_LT(worst, 0.02);
  EXPECT_GT(concave, 200);
  EXPECT_EQ(convexBright, convex);
  EXPECT_EQ(concaveDark, concave);
}

// The inside of a sphere (normals pointing in) bends towards its normal: concave, −1/R,
// dark in an 8-bit file (0.4 at r = 0.2); the outside, bright (0.6). Measured worst error
// 0.0004 both ways; bound 0.03. (The hit normals face away from the low
// poly's, which bake() warns about: expected here.)
TEST(BakeExtraMaps, CurvatureOfAConcaveSurfaceIsNegative) {
  log::setLevel(log::Level::Off);
  const Mesh low = makeUvSphere(1.0f, 16, 8);
  bake::BakeOptions options;
  options.width = options.height = 32;
  options.maps.add(bake::Map::Curvature);
  options.curvatureRadius = {0.2f, false};
  for (const bool inward : {false, true}) {
    const Mesh high = inward ? flipped(makeUvSphere(1.0f, 128, 64)) : makeUvSphere(1.0f, 128, 64);
    const auto r = bake::bake(low, high, options);
    const Image u8 = bake::curvatureForOutput(r.map(bake::Map::Curvature), PixelType::U8, r.stats.curvatureRadius);
    double worst = 0;
    int wrongSide = 0, n = 0;
    for (int row = 0; row < 32; ++row)
      for (int x = 0; x < 32; ++x) {
        if (!inIsland(r, x, row)) continue;
        worst = std::max(worst, std::abs(r.map(bake::Map::Curvature).at(x, row, 0) - (inward ? -1.0 : 1.0)));
        wrongSide += inward ? u8.at(x, row, 0) >= 0.5f : u8.at(x, row, 0) <= 0.5f;
        ++n;
      }
    std::printf("sphere curvature, normals %s: worst error %.4f from %+d; 8-bit %.3f (%d texels)\n",
                inward ? "in" : "out", worst, inward ? -1 : 1, u8.at(16, 16, 0), n);
    EXPECT_LT(worst, 0.03);
    EXPECT_EQ(wrongSide, 0);
  }
}

// Position: the hit point. With one sample per texel the sample is the texel centre, so
// the only errors are the high poly's faceting (the analytic sphere is up to ~6e-4 from
// the 128×64 mesh) and, in a 16-bit file, half a step of the bounds (2 / 65535 / 2).
TEST(BakeExtraMaps, PositionIsTheHitPoint) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeUvSphere(1.0f, 128, 64);
  for (const float radius : {0.95f, 1.05f}) {
    const Mesh low = makeUvSphere(radius, 16, 8);
    bake::BakeOptions options;
    options.width = options.height = 48;
    options.maps.add(bake::Map::Position);
    options.maxFront = options.maxRear = {0.1f, false};
    const auto r = bake::bake(low, high, options);
    ASSERT_TRUE(r.stats.positionBounds);
    const Bounds b = *r.stats.positionBounds;
    EXPECT_EQ(b.min, high.bounds().min);
    EXPECT_EQ(b.max, high.bounds().max);
    const Image u16 = bake::positionForOutput(r.map(bake::Map::Position), PixelType::U16, b);
    ASSERT_EQ(u16.type(), PixelType::U16);
    double worstRaw = 0, worstDecoded = 0, worstRadius = 0;
    int n = 0;
    for (int row = 0; row < 48; ++row)
      for (int x = 0; x < 48; ++x) {
        if (!inIsland(r, x, row)) continue;
        const vec3 raw = texel(r.map(bake::Map::Position), x, row);
        worstRadius = std::max(worstRadius, std::abs(double(glm::length(raw)) - 1.0));
        const auto s = surfaceAt(r.low, texelCentre(x, row, 48, 48));
        if (!s) continue;  // a texel filled by the closest-point rule: its sample is not the centre
        const glm::dvec3 dir = glm::normalize(glm::dvec3(s->normal));
        const auto t = rayRoot(sphereSdf, glm::dvec3(s->position), dir, 0.1, 0.1);
        ASSERT_TRUE(t);
        const glm::dvec3 expected = glm::dvec3(s->position) + *t * dir;
        const glm::dvec3 decodedPosition = glm::dvec3(b.min) + glm::dvec3(texel(u16, x, row)) * glm::dvec3(b.max - b.min);
        worstRaw = std::max(worstRaw, glm::length(glm::dvec3(raw) - expected));
        worstDecoded = std::max(worstDecoded, glm::length(decodedPosition - expected));
        ++n;
      }
    std::printf("position (low radius %.2f): raw %.2e, 16-bit decoded %.2e from the analytic point; |p| - 1 %.2e (%d texels)\n",
                radius, worstRaw, worstDecoded, worstRadius, n);
    EXPECT_GT(n, 1500);
    EXPECT_LT(worstRaw, 1e-3);
    EXPECT_LT(worstDecoded, 1e-3 + std::sqrt(3.0) * 2.0 / 65535.0 / 2.0);
    EXPECT_LT(worstRadius, 1e-3);
  }
}

// Opacity: a plane over a high-poly plane with a rectangular hole, 16 samples per texel.
// Each texel's expected value counts its own sample points (the stratified 4×4 grid) that
// lie on the low poly's island and outside the hole: exact, including the fractions at
// the hole's border; 0 outside the island, which is not dilated.
TEST(BakeExtraMaps, OpacityCountsTheSamplesThatHit) {
  log::setLevel(log::Level::Error);
  Mesh low = makePlane(2.0f);
  shrinkUvs(low, 0.125f);  // the island is texels 4..27 of 32, its border on texel edges
  const Mesh grid = makeGrid(30, 30, 3.0f);  // 0.1 cells over [-1.5, 1.5]²
  const auto inHole = [](double x, double z) { return x > -0.3 && x < 0.3 && z > -0.2 && z < 0.4; };
  Mesh high = grid;
  high.indices.clear();
  for (std::size_t i = 0; i < grid.indices.size(); i += 3) {
    const vec3 c = (grid.positions[grid.indices[i]] + grid.positions[grid.indices[i + 1]] + grid.positions[grid.indices[i + 2]]) / 3.0f;
    if (!inHole(c.x, c.z)) high.indices.insert(high.indices.end(), {grid.indices[i], grid.indices[i + 1], grid.indices[i + 2]});
  }
  bake::BakeOptions options;
  options.width = options.height = 32;
  options.samples = 16;
  options.maps.add(bake::Map::Opacity);
  options.maxFront = options.maxRear = {0.05f, false};
  const auto r = bake::bake(low, high, options);
  ASSERT_FALSE(r.map(bake::Map::Opacity).empty());
  int mismatches = 0, fractional = 0, ones = 0, zeros = 0;
  for (int row = 0; row < 32; ++row)
    for (int x = 0; x < 32; ++x) {
      const int y = 31 - row;  // texel rows count up from v = 0
      int hits = 0;
      for (int s = 0; s < 16; ++s) {
        const vec2 uv((float(x) + (float(s % 4) + 0.5f) / 4.0f) / 32.0f, (float(y) + (float(s / 4) + 0.5f) / 4.0f) / 32.0f);
        const auto p = surfaceAt(r.low, uv);
        if (p && !inHole(p->position.x, p->position.z)) ++hits;
      }
      const float expected = float(hits) / 16.0f, got = r.map(bake::Map::Opacity).at(x, row, 0);
      if (got != expected) {
        ++mismatches;
        ADD_FAILURE() << "texel " << x << "," << row << ": opacity " << got << ", expected " << expected;
      }
      fractional += got > 0.0f && got < 1.0f;
      ones += got == 1.0f;
      zeros += got == 0.0f;
    }
  std::printf("opacity: %d texels 1, %d fractional, %d zero; %d mismatches\n", ones, fractional, zeros, mismatches);
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(fractional, 20);  // the hole's border
  EXPECT_EQ(zeros, 32 * 32 - 24 * 24 + 6 * 6);  // outside the island, and the hole's whole texels
}

// The new maps, together, do not change the normal map, do not depend on the thread count,
// and cost nothing when not asked for (the same rays).
TEST(BakeExtraMaps, NormalMapUnchangedAndDeterministic) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeTorus(1.0f, 0.35f, 96, 48);
  const Mesh low = makeTorus(1.0f, 0.35f, 12, 6);
  bake::BakeOptions plain;
  plain.width = plain.height = 64;
  plain.samples = 4;
  const auto reference = bake::bake(low, high, plain);
  bake::BakeOptions options = plain;
  // Opacity and position need only the hits: the normal pass's rays and its lean path.
  options.maps.add(bake::Map::Opacity).add(bake::Map::Position);
  const auto withHitsOnly = bake::bake(low, high, options);
  EXPECT_TRUE(withHitsOnly.normal == reference.normal);
  EXPECT_EQ(withHitsOnly.stats.rays, reference.stats.rays);
  options.maps.add(bake::Map::BentNormal).add(bake::Map::Thickness).add(bake::Map::Curvature);
  options.aoSamples = 8;
  bake::BakeResult one;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = bake::bake(low, high, options);
  }
  const auto many = bake::bake(low, high, options);
  EXPECT_TRUE(one.map(bake::Map::BentNormal) == many.map(bake::Map::BentNormal));
  EXPECT_TRUE(one.map(bake::Map::Thickness) == many.map(bake::Map::Thickness));
  EXPECT_TRUE(one.map(bake::Map::Curvature) == many.map(bake::Map::Curvature));
  EXPECT_TRUE(one.map(bake::Map::Position) == many.map(bake::Map::Position));
  EXPECT_TRUE(one.map(bake::Map::Opacity) == many.map(bake::Map::Opacity));
  EXPECT_TRUE(one.normal == many.normal);
  EXPECT_EQ(many.stats.rays, reference.stats.rays);  // the normal pass casts the same rays
  // The normal map through the per-sample path instead of the vectorized lanes: the same
  // vectors to float rounding.
  const ImageDifference diff = compareImages(many.normal, reference.normal);
  EXPECT_LT(diff.maxAbs, 1e-5);
}

TEST(BakeExtraMaps, OptionChecksReportAndMemory) {
  log::setLevel(log::Level::Off);
  bake::BakeOptions o;
  o.maps.add(bake::Map::Thickness);
  o.thicknessDistance = {0.0f, true};
  EXPECT_THROW(bake::validateOptions(o), Error);
  o.thicknessDistance = {0.1f, true};
  o.maps.remove(bake::Map::Thickness);
  o.maps.add(bake::Map::Curvature);
  o.curvatureRadius = {0.0f, false};
  EXPECT_THROW(bake::validateOptions(o), Error);
  o.curvatureRadius = {-0.01f, true};
  EXPECT_THROW(bake::validateOptions(o), Error);
  o.curvatureRadius = {0.01f, true};
  EXPECT_NO_THROW(bake::validateOptions(o));  // curvature casts no AO rays: AO samples do not matter
  o.aoSamples = 0;
  EXPECT_NO_THROW(bake::validateOptions(o));
  o.maps.remove(bake::Map::Curvature);
  o.maps.add(bake::Map::Thickness);
  EXPECT_THROW(bake::validateOptions(o), Error);
  o.maps.remove(bake::Map::Thickness);
  o.maps.add(bake::Map::BentNormal);
  EXPECT_THROW(bake::validateOptions(o), Error);
  o.maps.remove(bake::Map::BentNormal);
  EXPECT_NO_THROW(bake::validateOptions(o));  // AO samples only matter when they are cast

  bake::BakeOptions big;
  big.width = big.height = 1024;
  big.device = bake::Device::Cpu;  // (auto and gpu add a GPU wave: bake_maps_test.cpp)
  big.maps.add(bake::Map::BentNormal).add(bake::Map::Position);  // three channels each
  big.maps.add(bake::Map::Thickness).add(bake::Map::Opacity).add(bake::Map::Curvature);  // one each
  EXPECT_DOUBLE_EQ(bake::estimatePeakMemoryMiB(big, {}), 64.0 + 19.5 + 8.0 * 9);

  const Mesh low = makeUvSphere(1.0f, 16, 8), high = makeUvSphere(1.0f, 32, 16);
  bake::BakeOptions options;
  options.width = options.height = 16;
  options.maps.add(bake::Map::Thickness).add(bake::Map::Position).add(bake::Map::Curvature);
  options.thicknessDistance = {0.5f, false};
  options.curvatureRadius = {0.05f, false};
  const auto r = bake::bake(low, high, options);
  const nlohmann::ordered_json s = bake::toJson(r.stats);
  EXPECT_EQ(s["thickness_rays"], r.stats.thicknessRays);
  EXPECT_FLOAT_EQ(s["thickness_distance"].get<float>(), 0.5f);
  EXPECT_EQ(s["curvature_rays"], r.stats.curvatureRays);
  EXPECT_GT(r.stats.curvatureRays, 0u);
  EXPECT_FLOAT_EQ(s["curvature_radius"].get<float>(), 0.05f);
  const Bounds b = high.bounds();
  EXPECT_EQ(s["position_min"], nlohmann::ordered_json({b.min.x, b.min.y, b.min.z}));
  EXPECT_EQ(s["position_max"], nlohmann::ordered_json({b.max.x, b.max.y, b.max.z}));
  const auto plain = bake::toJson(bake::bake(low, high, {.width = 16, .height = 16}).stats);
  EXPECT_FALSE(plain.contains("thickness_distance"));
  EXPECT_FALSE(plain.contains("curvature_radius"));
  EXPECT_EQ(plain["curvature_rays"], 0u);
  EXPECT_FALSE(plain.contains("position_min"));
}
