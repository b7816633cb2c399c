// The baker's other outputs and options against analytic answers: ambient occlusion
// under a square roof (the form factor of a parallel rectangle), height as signed ray
// distance, the miss mask, painted height detail, object/world/DirectX encodings, hit
// selection, the cage, determinism across thread counts, cancellation and bad input.
#include "bake_test_util.h"

#include "glint/bake/baker.h"
#include "glint/core/error.h"
#include "glint/core/log.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

using namespace glint;
using namespace bake_test;

namespace {

/// Form factor from a point to a parallel rectangle with one corner straight above it at
/// height h, sides a and b (Howell's catalogue, configuration B-3).
double cornerFormFactor(double a, double b, double h) {
  const double x = a / h, y = b / h;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * 3.14159265358979323846);
}

/// Fraction of the cosine-weighted hemisphere at (px, pz) not blocked by the square
/// [-s, s]² at height h: 1 minus the sum over the four rectangles around the point.
double openFraction(double px, double pz, double s, double h) {
  double f = 0;
  for (double ax : {s - px, s + px})
    for (double bz : {s - pz, s + pz}) f += cornerFormFactor(ax, bz, h);
  return 1.0 - f;
}

Mesh flipped(Mesh m) {
  for (std::size_t i = 0; i < m.indices.size(); i += 3) std::swap(m.indices[i + 1], m.indices[i + 2]);
  for (vec3& n : m.normals) n = -n;
  return m;
}

}  // namespace

TEST(BakeMaps, AmbientOcclusionMatchesFormFactor) {
  log::setLevel(log::Level::Error);
  const Mesh low = makePlane(2.0f);  // [-1, 1]² at y = 0, normal +Y
  Mesh high = makePlane(2.0f);
  Mesh roof = flipped(makePlane(1.0f));  // [-0.5, 0.5]² facing down, at y = 0.4
  roof.transform(glm::translate(mat4(1.0f), vec3(0.0f, 0.4f, 0.0f)));
  high.append(roof);
  bake::BakeOptions options;
  options.width = options.height = 48;
  options.maps.add(bake::Map::Ao);
  options.aoSamples = 256;
  options.aoDistance = {100.0f, false};
  options.maxFront = options.maxRear = {0.01f, false};
  const auto r = bake::bake(low, high, options);
  ASSERT_FALSE(r.map(bake::Map::Ao).empty());
  double sumError = 0, worst = 0;
  int n = 0;
  for (int row = 0; row < 48; ++row) {
    for (int x = 0; x < 48; ++x) {
      const auto s = surfaceAt(r.low, texelCentre(x, row, 48, 48));
      ASSERT_TRUE(s);
      const double expected = openFraction(s->position.x, s->position.z, 0.5, 0.4);
      const double err = std::abs(r.map(bake::Map::Ao).at(x, row, 0) - expected);
      sumError += err;
      worst = std::max(worst, err);
      ++n;
    }
  }
  std::printf("AO: mean |error| %.4f, worst %.4f (256 rays per texel)\n", sumError / n, worst);
  EXPECT_LT(sumError / n, 0.01);
  EXPECT_LT(worst, 0.06);  // 256 stratified rays: noise of a few percent at most
  EXPECT_EQ(r.stats.aoRays, 48u * 48u * 256u);
}

TEST(BakeMaps, HeightIsSignedRayDistance) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeUvSphere(1.0f, 128, 64);
  for (float radius : {0.95f, 1.05f}) {  // low poly inside, then outside the high poly
    Mesh low = makeUvSphere(radius, 16, 8);
    bake::BakeOptions options;
    options.width = options.height = 64;
    options.maps.add(bake::Map::Height);
    options.maxFront = options.maxRear = {0.1f, false};
    const auto r = bake::bake(low, high, options);
    double worst = 0;
    int n = 0;
    for (int row = 0; row < 64; ++row)
      for (int x = 0; x < 64; ++x) {
        const auto s = surfaceAt(r.low, texelCentre(x, row, 64, 64));
        if (!s || r.coverage.at(x, row, 0) < 0.99f) continue;
        const glm::dvec3 dir = glm::normalize(glm::dvec3(s->normal));
        const auto t = rayRoot(sphereSdf, glm::dvec3(s->position), dir, 0.1, 0.1);
        ASSERT_TRUE(t);
        EXPECT_EQ(*t > 0, radius < 1.0f);  // inside: the surface is in front
        worst = std::max(worst, std::abs(r.map(bake::Map::Height).at(x, row, 0) - *t));
        ++n;
      }
    EXPECT_GT(n, 2000);
    EXPECT_LT(worst, 2e-3) << "radius " << radius;
    // One surface per ray: one ray per sample, plus two when a tile's first sample finds its
    // hit behind (4 tiles of 32² here), plus a retry for the rare ray that slips through a
    // vertex of the (not watertight, faster) BVH.
    EXPECT_LE(r.stats.rays, r.stats.samples + r.stats.samples / 100 + 2 * 4) << "radius " << radius;  // the high poly's own faceting (r·(1-cos 1.4°))
  }
}

TEST(BakeMaps, MissMaskMarksRaysThatFindNothing) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeUvSphere(1.0f, 64, 32);
  const Mesh lowFar = makeUvSphere(1.5f, 16, 8);
  bake::BakeOptions options;
  options.width = options.height = 32;
  options.maps.add(bake::Map::MissMask);
  options.maxFront = options.maxRear = {0.1f, false};
  auto r = bake::bake(lowFar, high, options);
  EXPECT_EQ(r.stats.hits, 0u);
  EXPECT_EQ(r.stats.misses, r.stats.samples);
  EXPECT_FALSE(r.warnings.empty());
  for (int row = 0; row < 32; ++row)
    for (int x = 0; x < 32; ++x) EXPECT_EQ(r.map(bake::Map::MissMask).at(x, row, 0), r.coverage.at(x, row, 0) > 0.99f ? 1.0f : 0.0f);
  // Missed samples keep the low poly's own normal: flat (0, 0, 1) in tangent space.
  const vec3 m = texel(r.normal, 16, 16) * 2.0f - 1.0f;
  EXPECT_NEAR(m.z, 1.0f, 1e-3f);

  options.maxRear = {0.6f, false};
  r = bake::bake(lowFar, high, options);
  EXPECT_EQ(r.stats.misses, 0u);
  EXPECT_DOUBLE_EQ(r.stats.hitRatio(), 1.0);
}

TEST(BakeMaps, HeightDetailTiltsNormalsAsPainted) {
  log::setLevel(log::Level::Error);
  const Mesh plane = makePlane(2.0f);
  bake::HeightDetail detail;
  const int hw = 128;
  detail.height = Image(hw, 4, 1, PixelType::F32);
  const double freq = 4.0;  // periods across the map: tiles seamlessly
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < hw; ++x)
      detail.height.set(x, y, 0, float(0.5 + 0.5 * std::sin(2 * 3.14159265358979 * freq * (x + 0.5) / hw)));
  detail.scale = 8.0f;
  bake::BakeOptions options;
  options.width = options.height = 64;
  options.detail = detail;
  const auto r = bake::bake(plane, plane, options);
  double worst = 0;
  for (int x = 0; x < 64; ++x) {
    const double u = (x + 0.5) / 64.0;
    // Height change per height-map texel, times the scale, is the slope.
    const double slope = detail.scale * 0.5 * 2 * 3.14159265358979 * freq * std::cos(2 * 3.14159265358979 * freq * u) / hw;
    const glm::dvec3 expected = glm::normalize(glm::dvec3(-slope, 0.0, 1.0));
    worst = std::max(worst, angleDeg(glm::dvec3(texel(r.normal, x, 20) * 2.0f - 1.0f), expected));
  }
  EXPECT_LT(worst, 0.5);
}

TEST(BakeMaps, ObjectWorldAndDirectXEncodings) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeUvSphere(1.0f, 96, 48);
  const Mesh low = makeUvSphere(1.0f, 16, 8);
  bake::BakeOptions options;
  options.width = options.height = 48;
  const auto gl = bake::bake(low, high, options);
  options.directX = true;
  const auto dx = bake::bake(low, high, options);
  for (int row = 0; row < 48; ++row)
    for (int x = 0; x < 48; ++x) {
      EXPECT_FLOAT_EQ(gl.normal.at(x, row, 0), dx.normal.at(x, row, 0));
      EXPECT_NEAR(gl.normal.at(x, row, 1), 1.0f - dx.normal.at(x, row, 1), 1e-6f);
    }

  options.directX = false;
  options.space = NormalSpace::Object;
  const auto object = bake::bake(low, high, options);
  options.space = NormalSpace::World;
  const mat4 rotation = glm::rotate(mat4(1.0f), 0.7f, vec3(0.3f, 1.0f, 0.2f));
  options.objectToWorld = glm::scale(rotation, vec3(2.0f));
  const auto world = bake::bake(low, high, options);
  for (int row = 4; row < 44; ++row)
    for (int x = 0; x < 48; ++x) {
      const vec3 n = texel(object.normal, x, row) * 2.0f - 1.0f;
      const vec3 w = texel(world.normal, x, row) * 2.0f - 1.0f;
      EXPECT_LT(glm::length(vec3(rotation * vec4(n, 0.0f)) - w), 1e-5f);
      // Object space on a sphere: the normal points at the texel's position.
      const auto s = surfaceAt(object.low, texelCentre(x, row, 48, 48));
      if (s) {
        EXPECT_LT(angleDeg(glm::dvec3(n), glm::dvec3(s->position)), 5.0);
      }
    }
}

TEST(BakeMaps, HitSelectionClosestOrFrontFirst) {
  log::setLevel(log::Level::Error);
  // Low: plane y = 0. High: a plane `up` above tilted about Z, and one `down` below tilted
  // about X (never crossing y = 0); both orders of distance, so the closest hit is mostly
  // in front in one case and mostly behind in the other.
  for (const auto& [up, down] : {std::pair{0.3f, 0.15f}, std::pair{0.15f, 0.3f}}) {
    const Mesh low = makePlane(2.0f);
    Mesh above = makePlane(4.0f), below = makePlane(4.0f);
    const mat4 tiltAbove = glm::rotate(mat4(1.0f), 0.1f, vec3(0, 0, 1)), tiltBelow = glm::rotate(mat4(1.0f), 0.1f, vec3(1, 0, 0));
    above.transform(glm::translate(mat4(1.0f), vec3(0, up, 0)) * tiltAbove);
    below.transform(glm::translate(mat4(1.0f), vec3(0, -down, 0)) * tiltBelow);
    Mesh high = above;
    high.append(below);
    bake::BakeOptions options;
    options.width = options.height = 16;
    options.space = NormalSpace::Object;
    options.maxFront = options.maxRear = {0.5f, false};
    options.maps.add(bake::Map::Height);
    const auto closest = bake::bake(low, high, options);
    options.selection = bake::HitSelection::FrontFirst;
    const auto frontFirst = bake::bake(low, high, options);
    const vec3 nAbove = vec3(tiltAbove * vec4(0, 1, 0, 0)), nBelow = vec3(tiltBelow * vec4(0, 1, 0, 0));
    const bool belowIsCloser = down < up;
    for (int row = 0; row < 16; ++row)
      for (int x = 0; x < 16; ++x) {
        const auto s = surfaceAt(closest.low, texelCentre(x, row, 16, 16));
        ASSERT_TRUE(s);
        // Distances along +Y to each tilted plane at this point.
        const float toAbove = up + std::tan(0.1f) * s->position.x, toBelow = down + std::tan(0.1f) * s->position.z;
        const vec3 expected = toBelow < toAbove ? nBelow : nAbove;
        EXPECT_LT(glm::length(texel(closest.normal, x, row) * 2.0f - 1.0f - expected), 1e-4f) << up << " " << down;
        EXPECT_NEAR(closest.map(bake::Map::Height).at(x, row, 0), toBelow < toAbove ? -toBelow : toAbove, 1e-4f);
        EXPECT_LT(glm::length(texel(frontFirst.normal, x, row) * 2.0f - 1.0f - nAbove), 1e-4f);
        EXPECT_NEAR(frontFirst.map(bake::Map::Height).at(x, row, 0), toAbove, 1e-4f);
      }
    // Two surfaces on every ray's segment: the sweep meets the far one first, so each sample
    // takes three rays (see HeightIsSignedRayDistance for the one-ray case).
    EXPECT_LE(closest.stats.rays, 3 * closest.stats.samples) << belowIsCloser;
  }
}

TEST(BakeMaps, CageGivesTheSameAnswerOnConvexShapes) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeUvSphere(1.0f, 128, 64);
  const Mesh low = makeUvSphere(1.0f, 16, 8);
  Mesh cage = low;
  for (std::size_t i = 0; i < cage.vertexCount(); ++i) cage.positions[i] += 0.1f * cage.normals[i];
  bake::BakeOptions options;
  options.width = options.height = 64;
  options.space = NormalSpace::Object;
  const auto plain = bake::bake(low, high, options);
  options.cage = cage;
  const auto caged = bake::bake(low, high, options);
  EXPECT_EQ(caged.stats.misses, 0u);
  double worst = 0;
  for (int row = 0; row < 64; ++row)
    for (int x = 0; x < 64; ++x)
      if (plain.coverage.at(x, row, 0) > 0.99f)
        worst = std::max(worst, angleDeg(glm::dvec3(texel(plain.normal, x, row) * 2.0f - 1.0f),
                                         glm::dvec3(texel(caged.normal, x, row) * 2.0f - 1.0f)));
  EXPECT_LT(worst, 1.0);

  Mesh wrong = cage;
  wrong.indices.resize(wrong.indices.size() - 3);
  options.cage = wrong;
  EXPECT_THROW(bake::bake(low, high, options), Error);
}

TEST(BakeMaps, OutputDoesNotDependOnThreadCount) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeTorus(1.0f, 0.35f, 96, 48);
  const Mesh low = makeTorus(1.0f, 0.35f, 12, 6);
  bake::BakeOptions options;
  options.width = options.height = 80;
  options.samples = 4;
  options.maps.add(bake::Map::Ao);
  options.aoSamples = 8;
  options.maps.add(bake::Map::Height);
  bake::BakeResult one;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = bake::bake(low, high, options);
  }
  const auto many = bake::bake(low, high, options);
  EXPECT_TRUE(one.normal == many.normal);
  EXPECT_TRUE(one.map(bake::Map::Ao) == many.map(bake::Map::Ao));
  EXPECT_TRUE(one.map(bake::Map::Height) == many.map(bake::Map::Height));
  EXPECT_EQ(one.stats.rays, many.stats.rays);
}

// An integer normal map straight from the baker holds exactly the codes of the float map
// converted afterwards (the baker quantizes row by row instead of copying the floats).
TEST(BakeMaps, IntegerNormalTypesMatchTheFloatMapConverted) {
  log::setLevel(log::Level::Error);
  const Mesh high = makeTorus(1.0f, 0.35f, 96, 48);
  const Mesh low = makeTorus(1.0f, 0.35f, 12, 6);
  bake::BakeOptions options;
  options.width = 90;
  options.height = 70;
  options.padding = 2;  // keep some background texels too
  const auto reference = bake::bake(low, high, options);
  ASSERT_EQ(reference.normal.type(), PixelType::F32);
  for (PixelType type : {PixelType::U8, PixelType::U16}) {
    options.normalType = type;
    const auto quantized = bake::bake(low, high, options);
    EXPECT_EQ(quantized.normal.type(), type);
    EXPECT_TRUE(quantized.normal == reference.normal.converted(type)) << pixelTypeName(type);
  }
}

TEST(BakeMaps, CancelThrowsInterrupted) {
  log::setLevel(log::Level::Error);
  std::atomic<bool> cancel{true};
  bake::BakeOptions options;
  options.width = options.height = 64;
  options.cancel = &cancel;
  try {
    bake::bake(makeUvSphere(1.0f, 16, 8), makeUvSphere(1.0f, 32, 16), options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Interrupted);
  }
}

TEST(BakeMaps, BadInputIsOneLineErrorOrWarning) {
  log::setLevel(log::Level::Off);
  const Mesh good = makeUvSphere(1.0f, 16, 8);
  const auto expectError = [&](const Mesh& low, const Mesh& high, const bake::BakeOptions& o, ErrorKind kind,
                               const char* fragment) {
    try {
      bake::bake(low, high, o);
      ADD_FAILURE() << "no error for " << fragment;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), kind) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  bake::BakeOptions o;
  o.width = o.height = 16;
  Mesh noUv = good;
  noUv.uvs.clear();
  expectError(noUv, good, o, ErrorKind::Input, "no UVs");
  expectError(Mesh{}, good, o, ErrorKind::Input, "no triangles");
  expectError(good, Mesh{}, o, ErrorKind::Input, "high-poly mesh: has no triangles");
  Mesh nan = good;
  nan.normals[3].x = std::nanf("");
  expectError(nan, good, o, ErrorKind::Input, "normal 3 is not finite");
  Mesh nanUv = good;
  nanUv.uvs[5].y = std::nanf("");
  expectError(nanUv, good, o, ErrorKind::Input, "UV 5 is not finite");
  Mesh nanPos = good;
  nanPos.positions[7].z = std::nanf("");
  expectError(good, nanPos, o, ErrorKind::Input, "not finite");
  bake::BakeOptions badSamples = o;
  badSamples.samples = 5;
  expectError(good, good, badSamples, ErrorKind::Usage, "square");
  bake::BakeOptions badSize = o;
  badSize.width = 0;
  expectError(good, good, badSize, ErrorKind::Usage, "size");
  bake::BakeOptions badPadding = o;
  badPadding.padding = -1;
  expectError(good, good, badPadding, ErrorKind::Usage, "--padding must not be negative");

  // Warnings, still baked: no normals, mirrored UVs (and the overlap they cause), degenerate triangles.
  Mesh noNormals = good;
  noNormals.normals.clear();
  auto r = bake::bake(noNormals, good, o);
  EXPECT_NE(r.warnings.at(0).find("no normals"), std::string::npos);
  Mesh mirrored = good;
  for (vec2& uv : mirrored.uvs) uv.x = uv.x < 0.5f ? uv.x : 1.0f - uv.x;  // right half folded onto the left
  r = bake::bake(mirrored, good, o);
  EXPECT_GT(r.stats.mirroredTriangles, 0u);
  EXPECT_GT(r.stats.overlappingSamples, 0u);
  EXPECT_GE(r.warnings.size(), 2u);
  Mesh degenerate = good;
  degenerate.indices.insert(degenerate.indices.end(), {0, 0, 1, 20, 21, 21});
  r = bake::bake(degenerate, good, o);
  EXPECT_EQ(r.stats.degenerateUvTriangles, 2u);
  EXPECT_GT(r.stats.coveredTexels, 100u);
}

// What `glint bake --json` reports and --max-memory checks, from the library alone.
TEST(BakeMaps, ReportAndMemoryEstimate) {
  log::setLevel(log::Level::Error);
  const Mesh low = makeUvSphere(1.0f, 16, 8), high = makeUvSphere(1.0f, 32, 16);
  bake::BakeOptions options;
  options.width = 64;
  options.height = 32;
  options.samples = 4;
  options.space = NormalSpace::Object;
  options.directX = true;
  const bake::BakeResult result = bake::bake(low, high, options);
  const nlohmann::ordered_json o = bake::toJson(options);
  EXPECT_EQ(o.dump(), R"({"width":64,"height":32,"samples_per_texel":4,"space":"object","directx":true})");
  const nlohmann::ordered_json s = bake::toJson(result.stats);
  std::vector<std::string> keys;
  for (const auto& [key, value] : s.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"low_triangles", "high_triangles", "texels", "covered_texels",
                                            "conservative_texels", "padded_texels", "samples", "rays", "ao_rays", "thickness_rays", "curvature_rays", "vertex_measurements", "hits",
                                            "inward_hits", "misses", "hit_ratio", "max_front", "max_rear", "rays_per_second", "bvh_mib",
                                            "bvh_quality", "device", "device_reason"}));
  EXPECT_EQ(s["device"], "cpu");
  EXPECT_EQ(s["device_reason"], "--device auto: this program has no GPU backend");
  EXPECT_EQ(s["low_triangles"], low.triangleCount());
  EXPECT_EQ(s["high_triangles"], high.triangleCount());
  EXPECT_EQ(s["texels"], 64u * 32u);
  EXPECT_EQ(s["rays"], result.stats.rays);
  EXPECT_DOUBLE_EQ(s["hit_ratio"].get<double>(), result.stats.hitRatio());
  EXPECT_EQ(s["bvh_quality"], result.stats.lowQualityBvh ? "low" : "medium");

  // ~64 MiB, twice the input files, 19.5 bytes per texel and 8 per extra map channel.
  const std::filesystem::path file = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "bake-estimate.bin";
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << std::string(1 << 19, 'x');
  bake::BakeOptions big;
  big.width = big.height = 1024;
  big.device = bake::Device::Cpu;
  EXPECT_DOUBLE_EQ(bake::estimatePeakMemoryMiB(big, {}), 64.0 + 19.5);
  EXPECT_DOUBLE_EQ(bake::estimatePeakMemoryMiB(big, {file, "", "missing.obj"}), 64.0 + 1.0 + 19.5);
  big.maps.add(bake::Map::Ao).add(bake::Map::MissMask);
  EXPECT_DOUBLE_EQ(bake::estimatePeakMemoryMiB(big, {}), 64.0 + 19.5 + 16.0);
  // A bake that may take the GPU holds a wave of at most 2^18 samples, 512 bytes each, a GL
  // context with its batches (56 MiB) and the GPU's hierarchy (twice the inputs again).
  big.device = bake::Device::Auto;
  EXPECT_DOUBLE_EQ(bake::estimatePeakMemoryMiB(big, {}), 64.0 + 19.5 + 16.0 + 128.0 + 56.0);
  EXPECT_DOUBLE_EQ(bake::estimatePeakMemoryMiB(big, {file}), 64.0 + 2.0 + 19.5 + 16.0 + 128.0 + 56.0);
  big.width = big.height = 64;
  EXPECT_DOUBLE_EQ(bake::estimatePeakMemoryMiB(big, {}), 64.0 + (19.5 + 16.0 + 512.0) / 256.0 + 56.0);
}
