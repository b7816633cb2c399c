// Quality of the normal mapper against analytic answers (issue 6, item 9): a finely
// tessellated sphere and torus baked onto coarse versions of themselves. Every texel
// inside the UV islands is decoded with the MikkTSpace per-pixel rule and compared
// with the true surface normal where the texel's ray meets the analytic surface.
#include "bake_test_util.h"

#include "glint/bake/baker.h"
#include "glint/core/log.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

using namespace glint;
using namespace bake_test;

namespace {

struct Analytic {
  const char* name;
  Mesh high;
  Mesh low;
  std::function<double(const glm::dvec3&)> sdf;
  std::function<glm::dvec3(const glm::dvec3&)> normal;
};

std::vector<Analytic> cases() {
  std::vector<Analytic> c;
  c.push_back({"sphere", makeUvSphere(1.0f, 256, 128), makeUvSphere(1.0f, 16, 8), sphereSdf, sphereNormal});
  c.push_back({"torus", makeTorus(1.0f, 0.35f, 256, 128), makeTorus(1.0f, 0.35f, 24, 12), torusSdf(1.0, 0.35),
               torusNormal(1.0)});
  for (Analytic& a : c) shrinkUvs(a.low, 0.1f);  // room for padding around the islands
  return c;
}

struct ErrorStats {
  double mean = 0, p99 = 0, max = 0;
  std::size_t count = 0;
};

/// Angular error of every texel whose centre lies in a UV triangle.
ErrorStats measure(const Analytic& a, const bake::BakeResult& r, NormalSpace space) {
  std::vector<double> errors;
  const int w = r.normal.width(), h = r.normal.height();
  for (int row = 0; row < h; ++row) {
    for (int x = 0; x < w; ++x) {
      const auto s = surfaceAt(r.low, texelCentre(x, row, w, h));
      if (!s) continue;
      const glm::dvec3 dir = glm::normalize(glm::dvec3(s->normal));
      const auto t = rayRoot(a.sdf, glm::dvec3(s->position), dir, r.stats.rearDistance, r.stats.frontDistance);
      if (!t) continue;
      const glm::dvec3 exact = a.normal(glm::dvec3(s->position) + *t * dir);
      const vec3 rgb = texel(r.normal, x, row);
      const vec3 baked = space == NormalSpace::Tangent ? decodeTangentSpace(rgb, *s) : rgb * 2.0f - 1.0f;
      errors.push_back(angleDeg(glm::dvec3(baked), exact));
    }
  }
  ErrorStats e;
  e.count = errors.size();
  for (double v : errors) {
    e.mean += v / double(errors.size());
    e.max = std::max(e.max, v);
  }
  e.p99 = percentile(errors, 0.99);
  return e;
}

}  // namespace

TEST(BakeQuality, AnalyticNormalsWithinOneDegree) {
  log::setLevel(log::Level::Error);
  for (const Analytic& a : cases()) {
    for (const auto space : {NormalSpace::Tangent, NormalSpace::Object}) {
      bake::BakeOptions options;
      options.width = options.height = 160;
      options.space = space;
      const auto result = bake::bake(a.low, a.high, options);
      const ErrorStats e = measure(a, result, space);
      std::printf("%s %s: %zu texels, mean %.3f°, p99 %.3f°, max %.3f°, hit ratio %.4f\n", a.name,
                  space == NormalSpace::Tangent ? "tangent" : "object", e.count, e.mean, e.p99, e.max,
                  result.stats.hitRatio());
      EXPECT_GT(e.count, 5000u) << a.name;
      EXPECT_LE(e.mean, 1.0) << a.name;
      EXPECT_LE(e.p99, 3.0) << a.name;
      EXPECT_EQ(result.stats.misses, 0u) << a.name;
    }
  }
}

TEST(BakeQuality, NoEmptyTexelInsideIslandsAndPaddingAround) {
  log::setLevel(log::Level::Error);
  for (const Analytic& a : cases()) {
    bake::BakeOptions options;
    options.width = 150;  // not square, not a multiple of the tile size
    options.height = 130;
    const auto result = bake::bake(a.low, a.high, options);
    const int w = options.width, h = options.height;
    const Image& cov = result.coverage;
    // Any texel a UV triangle overlaps (tested at 6×6 points inside it) is baked.
    std::vector<std::uint8_t> island(std::size_t(w * h), 0);
    int touched = 0, empty = 0;
    for (int row = 0; row < h; ++row) {
      for (int x = 0; x < w; ++x) {
        bool inside = false;
        for (int j = 0; j < 6 && !inside; ++j) {
          for (int i = 0; i < 6 && !inside; ++i) {
            const vec2 uv((float(x) + (float(i) + 0.5f) / 6.0f) / float(w), 1.0f - (float(row) + (float(j) + 0.5f) / 6.0f) / float(h));
            inside = surfaceAt(result.low, uv).has_value();
          }
        }
        if (!inside) continue;
        ++touched;
        island[std::size_t(row * w + x)] = 1;
        if (cov.at(x, row, 0) < 0.99f) ++empty;
      }
    }
    EXPECT_GT(touched, 1000) << a.name;
    EXPECT_EQ(empty, 0) << a.name << ": texels inside islands left empty";
    // Padding: every texel within 16 texels (Chebyshev) of an island is filled, none beyond.
    int missingPadding = 0, extraPadding = 0;
    for (int row = 0; row < h; ++row) {
      for (int x = 0; x < w; ++x) {
        int d = 1000;
        for (int dy = -17; dy <= 17; ++dy)
          for (int dx = -17; dx <= 17; ++dx) {
            const int xx = x + dx, yy = row + dy;
            if (xx >= 0 && yy >= 0 && xx < w && yy < h && cov.at(xx, yy, 0) > 0.99f) d = std::min(d, std::max(std::abs(dx), std::abs(dy)));
          }
        const bool filled = cov.at(x, row, 0) > 0.4f;
        if (d <= 16 && !filled) ++missingPadding;
        if (d > 16 && filled) ++extraPadding;
      }
    }
    EXPECT_EQ(missingPadding, 0) << a.name;
    EXPECT_EQ(extraPadding, 0) << a.name;
    EXPECT_GT(result.stats.paddedTexels, 1000u) << a.name;
    // Padded texels hold unit normals, not the background.
    const vec3 corner = texel(result.normal, 2, 2);  // far outside: background
    EXPECT_NEAR(corner.z, 1.0f, 1e-6f);
  }
}

TEST(BakeQuality, FillAllLeavesNothingEmpty) {
  log::setLevel(log::Level::Error);
  const Analytic a = cases()[0];
  bake::BakeOptions options;
  options.width = options.height = 96;
  options.fillAll = true;
  const auto result = bake::bake(a.low, a.high, options);
  for (int row = 0; row < 96; ++row)
    for (int x = 0; x < 96; ++x) ASSERT_GT(result.coverage.at(x, row, 0), 0.4f) << x << "," << row;
  // Even the far corner holds a dilated unit normal, not the flat background.
  const vec3 n = texel(result.normal, 0, 0) * 2.0f - 1.0f;
  EXPECT_NEAR(glm::length(n), 1.0f, 0.01f);
}

TEST(BakeQuality, SupersamplingIsSmootherThanOneSample) {
  // A sphere with bumps near the texel frequency: one sample per texel aliases, 16 average.
  log::setLevel(log::Level::Error);
  Mesh high = makeUvSphere(1.0f, 512, 256);
  for (vec3& p : high.positions) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(p));
    const double phi = std::atan2(d.x, d.z), theta = std::acos(std::clamp(d.y, -1.0, 1.0));
    p *= float(1.0 + 0.006 * std::sin(57.0 * phi) * std::sin(41.0 * theta));
  }
  computeNormals(high);
  Mesh low = makeUvSphere(1.0f, 16, 8);
  shrinkUvs(low, 0.05f);

  const auto bakeWith = [&](int samples) {
    bake::BakeOptions options;
    options.width = options.height = 64;
    options.samples = samples;
    return bake::bake(low, high, options);
  };
  const auto one = bakeWith(1), sixteen = bakeWith(16), reference = bakeWith(64);
  const auto roughness = [](const bake::BakeResult& r) {
    // Mean angle between horizontally adjacent texels inside islands.
    double sum = 0;
    int n = 0;
    for (int row = 0; row < 64; ++row)
      for (int x = 0; x + 1 < 64; ++x) {
        if (r.coverage.at(x, row, 0) < 0.99f || r.coverage.at(x + 1, row, 0) < 0.99f) continue;
        sum += angleDeg(glm::dvec3(texel(r.normal, x, row) * 2.0f - 1.0f), glm::dvec3(texel(r.normal, x + 1, row) * 2.0f - 1.0f));
        ++n;
      }
    return sum / n;
  };
  const auto distance = [](const bake::BakeResult& a, const bake::BakeResult& b) {
    double sum = 0;
    int n = 0;
    for (int row = 0; row < 64; ++row)
      for (int x = 0; x < 64; ++x) {
        if (a.coverage.at(x, row, 0) < 0.99f) continue;
        sum += angleDeg(glm::dvec3(texel(a.normal, x, row) * 2.0f - 1.0f), glm::dvec3(texel(b.normal, x, row) * 2.0f - 1.0f));
        ++n;
      }
    return sum / n;
  };
  const double r1 = roughness(one), r16 = roughness(sixteen);
  const double e1 = distance(one, reference), e16 = distance(sixteen, reference);
  std::printf("neighbour angle: 1 spp %.3f°, 16 spp %.3f°; error to 64 spp: 1 spp %.3f°, 16 spp %.3f°\n", r1, r16, e1, e16);
  EXPECT_LT(r16, 0.8 * r1);
  EXPECT_LT(e16, 0.5 * e1);
  // Partially covered border texels take fewer samples; never more than 16 per texel.
  EXPECT_GE(sixteen.stats.samples, sixteen.stats.coveredTexels);
  EXPECT_LE(sixteen.stats.samples, 16u * sixteen.stats.coveredTexels);
  EXPECT_GT(sixteen.stats.samples, 14u * sixteen.stats.coveredTexels);
}
