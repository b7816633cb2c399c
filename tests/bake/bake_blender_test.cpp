// Quality cross-check against Blender 3.4 Cycles (issue 23, deliverable 5): the maps that
// both bake — ambient occlusion, position, object-space normals, and a normal map in UDIM
// tiles — from the same OBJ files, compared texel by texel over the texels both cover.
// Blender's side is bench/peers/blender_bake_check.py; every test is skipped when
// `blender` is not on PATH (apt-get install blender). docs/bake.md, "Against Blender",
// has the figures and why the files are written the way they are:
//
// - The low poly is welded (one `v` per point, the seams' UVs apart) and its `vn` are
//   Blender's own vertex normals (the faces' normals weighted by their corner angles):
//   Blender casts the rays along the vertex normals it computes from the topology, not
//   along the file's normals, so glint gets the very same directions.
// - The high poly is written unwelded (three `v`/`vn` of its own per triangle, the
//   coordinates bit for bit the same where triangles meet): Blender 3.4 shades the
//   OBJ's normals wrongly at vertices shared by several faces (up to 8.5° off the
//   interpolated normal on a 2-triangle quad; unwelded, 0.0009°). glint loads the high
//   poly unwelded anyway.
// - Both objects stay at the identity and are imported keeping the OBJ's axes, so
//   Blender's world-space position and object-space normal are glint's object space.
#include "glint/bake/samples.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include <glm/gtc/matrix_transform.hpp>

#include "support/cli.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;

namespace {

using glint::testing::runGlint;
using glint::testing::runShell;

bool blenderOnPath() { return runShell("command -v blender").status == 0; }

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

/// The low poly as Blender sees the same file: positions welded (exact duplicates, as
/// makeTorus's seams are, share one `v`), UVs per corner as the mesh has them, and per
/// welded vertex the normal Blender computes (sum over its faces of the face normal times
/// the corner angle, normalized). Each part becomes one object of the file.
void writeLowAsBlenderSeesIt(const std::vector<Mesh>& parts, const fs::path& path) {
  std::ofstream out(path);
  out.precision(9);
  std::size_t positionBase = 0, uvBase = 0;
  for (const Mesh& m : parts) {
    std::map<std::tuple<float, float, float>, std::uint32_t> weld;
    std::vector<vec3> points;
    std::vector<std::uint32_t> pointOf(m.vertexCount());
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
      const vec3& p = m.positions[i];
      const auto [it, added] = weld.try_emplace({p.x, p.y, p.z}, std::uint32_t(points.size()));
      if (added) points.push_back(p);
      pointOf[i] = it->second;
    }
    std::vector<glm::dvec3> normals(points.size(), glm::dvec3(0.0));
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
      const std::uint32_t c[3] = {pointOf[m.indices[3 * t]], pointOf[m.indices[3 * t + 1]], pointOf[m.indices[3 * t + 2]]};
      const glm::dvec3 p[3] = {glm::dvec3(points[c[0]]), glm::dvec3(points[c[1]]), glm::dvec3(points[c[2]])};
      const glm::dvec3 face = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 a = glm::normalize(p[(k + 1) % 3] - p[k]), b = glm::normalize(p[(k + 2) % 3] - p[k]);
        normals[c[k]] += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * face;
      }
    }
    for (const vec3& p : points) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const vec2& uv : m.uvs) out << "vt " << uv.x << ' ' << uv.y << '\n';
    for (const glm::dvec3& n : normals) {
      const glm::dvec3 u = glm::normalize(n);
      out << "vn " << u.x << ' ' << u.y << ' ' << u.z << '\n';
    }
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
      out << 'f';
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = m.indices[3 * t + std::size_t(k)];
        const std::size_t point = positionBase + pointOf[i] + 1, uv = uvBase + i + 1;
        out << ' ' << point << '/' << uv << '/' << point;
      }
      out << '\n';
    }
    positionBase += points.size();
    uvBase += m.uvs.size();
  }
  if (!out) FAIL() << "cannot write " << path;
}

/// The high poly unwelded: three positions and normals of its own per triangle.
void writeHighUnwelded(const Mesh& m, const fs::path& path) {
  std::ofstream out(path);
  out.precision(9);
  for (std::uint32_t i : m.indices) out << "v " << m.positions[i].x << ' ' << m.positions[i].y << ' ' << m.positions[i].z << '\n';
  for (std::uint32_t i : m.indices) out << "vn " << m.normals[i].x << ' ' << m.normals[i].y << ' ' << m.normals[i].z << '\n';
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    out << 'f';
    for (std::size_t k = 1; k <= 3; ++k) out << ' ' << 3 * t + k << "//" << 3 * t + k;
    out << '\n';
  }
  if (!out) FAIL() << "cannot write " << path;
}

/// The pair every case bakes: the 1,152-triangle torus under a 16,384-triangle studded one
/// (studs 0.03 high, a groove 0.015 deep), small enough that Blender bakes each case in
/// seconds.
Mesh lowTorus() { return makeTorus(1.0f, 0.35f, 48, 12); }
Mesh highTorus() { return bake::makeStuddedTorus({.segments = 128, .sides = 64}); }

constexpr int kSize = 256;
const std::string kRays = " --max-front 0.06 --max-rear 0.06";  // Blender: cage extrusion 0.06, max distance 0.12

/// Runs the Blender peer for one map; false (with the reason recorded) when it failed.
bool blenderBake(const fs::path& low, const fs::path& high, const fs::path& out, const std::string& map, int samples,
                 double aoDistance = 0.1) {
  const fs::path script = fs::path(GLINT_SOURCE_DIR) / "bench" / "peers" / "blender_bake_check.py";
  char args[128];
  std::snprintf(args, sizeof args, " %s %d %d 0.06 %g", map.c_str(), kSize, samples, aoDistance);
  const auto r = runShell("nice -n 5 blender -b --factory-startup --python-exit-code 1 --python " + quoted(script) + " -- " + quoted(low) +
                          " " + quoted(high) + " " + quoted(out) + args);
  EXPECT_EQ(r.status, 0) << r.output;
  for (std::size_t at = r.output.find("blender_bake_check:"); at != std::string::npos;
       at = r.output.find("blender_bake_check:", at + 1)) {
    std::printf("%s\n", r.output.substr(at, r.output.find('\n', at) - at).c_str());
  }
  return r.status == 0;
}

/// A per-texel comparison over the texels both bakes cover: glint's opacity 1 (every
/// sample on the island and hit) and Blender's alpha 1 (baked with margin 0).
struct Comparison {
  std::size_t covered = 0, glintOnly = 0, blenderOnly = 0, within = 0;
  double mean = 0, max = 0, meanSigned = 0;
  double correlation = 0;  ///< of the two bakes' values (scalar maps)
};

template <typename Diff>
Comparison compare(const Image& glint, const Image& opacity, const Image& blender, double tolerance, Diff diff) {
  Comparison c;
  EXPECT_EQ(glint.width(), blender.width());
  EXPECT_EQ(glint.height(), blender.height());
  EXPECT_EQ(blender.channels(), 4);
  if (glint.width() != blender.width() || glint.height() != blender.height() || blender.channels() != 4) return c;
  double sg = 0, sb = 0, sgg = 0, sbb = 0, sgb = 0;
  for (int y = 0; y < glint.height(); ++y) {
    for (int x = 0; x < glint.width(); ++x) {
      const bool g = opacity.at(x, y, 0) > 0.999f, b = blender.at(x, y, 3) > 0.999f;
      if (g != b) {
        ++(g ? c.glintOnly : c.blenderOnly);
        continue;
      }
      if (!g) continue;
      const auto [d, signedD] = diff(x, y);
      ++c.covered;
      c.mean += d;
      c.meanSigned += signedD;
      c.max = std::max(c.max, d);
      c.within += d <= tolerance;
      const double gv = glint.at(x, y, 0), bv = blender.at(x, y, 0);
      sg += gv, sb += bv, sgg += gv * gv, sbb += bv * bv, sgb += gv * bv;
    }
  }
  if (c.covered == 0) return c;
  const double n = double(c.covered);
  c.mean /= n;
  c.meanSigned /= n;
  const double vg = sgg / n - (sg / n) * (sg / n), vb = sbb / n - (sb / n) * (sb / n);
  c.correlation = (sgb / n - (sg / n) * (sb / n)) / std::sqrt(std::max(vg * vb, 1e-30));
  return c;
}

void print(const char* what, const Comparison& c, double tolerance, const char* unit) {
  std::printf("%s: %zu texels both cover (glint only %zu, Blender only %zu); mean |d| %.3g %s, max %.3g %s, "
              "%.2f %% within %g %s\n",
              what, c.covered, c.glintOnly, c.blenderOnly, c.mean, unit, c.max, unit,
              100.0 * double(c.within) / double(std::max<std::size_t>(c.covered, 1)), tolerance, unit);
}

vec3 decodeNormal(const Image& image, int x, int y) {
  return {2.0f * image.at(x, y, 0) - 1.0f, 2.0f * image.at(x, y, 1) - 1.0f, 2.0f * image.at(x, y, 2) - 1.0f};
}

double degreesBetween(vec3 a, vec3 b) {
  const double d = glm::dot(glm::normalize(glm::dvec3(a)), glm::normalize(glm::dvec3(b)));
  return std::acos(std::clamp(d, -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

class BakeBlender : public ::testing::Test {
protected:
  void SetUp() override {
    if (!blenderOnPath()) GTEST_SKIP() << "`blender` is not on PATH (apt-get install blender): no peer to compare with";
  }
  fs::path dir(const char* name) { return glint::testing::freshDir("bake-blender", name); }
};

// Object-space normals and positions, 1 sample per texel (Cycles' sample 0 is the texel
// centre, as glint's single sample): the same rays hit the same points, so the maps agree
// to rounding.
TEST_F(BakeBlender, NormalObjectSpaceAndPositionAgree) {
  const fs::path d = dir("normal-position");
  writeLowAsBlenderSeesIt({lowTorus()}, d / "low.obj");
  writeHighUnwelded(highTorus(), d / "high.obj");
  const auto r = runGlint("bake " + quoted(d / "low.obj") + " " + quoted(d / "high.obj") + " -o " + quoted(d / "normal.exr") +
                          " --space object --position " + quoted(d / "position.exr") + " --opacity " +
                          quoted(d / "opacity.exr") + " --size 256x256 --samples 1 --padding 0 -q" + kRays);
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(blenderBake(d / "low.obj", d / "high.obj", d / "blender-normal.exr", "normal", 1));
  ASSERT_TRUE(blenderBake(d / "low.obj", d / "high.obj", d / "blender-position.exr", "position", 1));
  const Image opacity = loadImage(d / "opacity.exr");

  // Normals: the angle between the decoded vectors. Tolerance 0.25°: both interpolate the
  // same vertex normals at nearly the same hit. Blender's UV rasterizer nudges every texel
  // centre by (0.001, 0.002) texels on purpose (a workaround for pixel-aligned UVs in its
  // bake code), so its hits sit 2e-5..4e-5 away along the surface (see the positions);
  // on the studs' flanks, where the normal turns fastest, that is up to 0.1°.
  const Image gn = loadImage(d / "normal.exr"), bn = loadImage(d / "blender-normal.exr");
  const double normalTolerance = 0.25;
  const Comparison n = compare(gn, opacity, bn, normalTolerance, [&](int x, int y) {
    const double a = degreesBetween(decodeNormal(gn, x, y), decodeNormal(bn, x, y));
    return std::pair{a, a};
  });
  print("normal (object space)", n, normalTolerance, "deg");
  EXPECT_GT(n.covered, std::size_t(kSize * kSize * 9 / 10)) << "the torus's islands fill the square";
  EXPECT_LT(n.glintOnly + n.blenderOnly, std::size_t(kSize * kSize / 100));
  EXPECT_LT(n.mean, 0.02);
  EXPECT_LT(n.max, normalTolerance);

  // Positions: the distance between the two hit points, scene units. Both lie on the high
  // poly (to 1e-7, checked by hand with Blender's BVHTree.find_nearest); they are apart by
  // Blender's nudge of (0.001, 0.002) texels, 2e-5..4e-5 here (a texel is 0.009 to 0.033
  // wide). Tolerance 1e-4: a hit one texel off would be 100× that.
  const Image gp = loadImage(d / "position.exr"), bp = loadImage(d / "blender-position.exr");
  const double positionTolerance = 1e-4;
  const Comparison p = compare(gp, opacity, bp, positionTolerance, [&](int x, int y) {
    const vec3 a(gp.at(x, y, 0), gp.at(x, y, 1), gp.at(x, y, 2)), b(bp.at(x, y, 0), bp.at(x, y, 1), bp.at(x, y, 2));
    const double l = glm::length(glm::dvec3(a) - glm::dvec3(b));
    return std::pair{l, l};
  });
  print("position", p, positionTolerance, "units");
  EXPECT_GT(p.covered, std::size_t(kSize * kSize * 9 / 10));
  EXPECT_LT(p.mean, 5e-5);
  EXPECT_LT(p.max, positionTolerance);
}

// Ambient occlusion: 64 rays per texel on both sides (Blender: 64 Cycles samples of one
// AO ray each, jittered over the texel; glint: 16 stratified samples × 4 AO rays), AO
// distance 1.5, so the inner side of the ring is shaded by the ring across the hole (1.3
// away) and the studs by their neighbours. Two Monte Carlo estimates of the same integral: they
// differ texel by texel by noise (one texel's 64 rays: σ up to 0.0625), so the test
// asserts what noise cannot produce — a bias, a low correlation, a large mean difference.
TEST_F(BakeBlender, AmbientOcclusionAgreesWithinNoise) {
  const fs::path d = dir("ao");
  writeLowAsBlenderSeesIt({lowTorus()}, d / "low.obj");
  writeHighUnwelded(highTorus(), d / "high.obj");
  const auto r = runGlint("bake " + quoted(d / "low.obj") + " " + quoted(d / "high.obj") + " -o " + quoted(d / "normal.exr") +
                          " --ao " + quoted(d / "ao.exr") + " --ao-distance 1.5 --opacity " + quoted(d / "opacity.exr") +
                          " --size 256x256 --samples 16 --ao-samples 4 --padding 0 -q" + kRays);
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(blenderBake(d / "low.obj", d / "high.obj", d / "blender-ao.exr", "ao", 64, 1.5));
  const Image ga = loadImage(d / "ao.exr"), ba = loadImage(d / "blender-ao.exr"), opacity = loadImage(d / "opacity.exr");
  const double tolerance = 0.125;  // 2σ of one texel's 64 independent rays at AO 0.5
  const Comparison a = compare(ga, opacity, ba, tolerance, [&](int x, int y) {
    const double s = double(ga.at(x, y, 0)) - double(ba.at(x, y, 0));
    return std::pair{std::abs(s), s};
  });
  print("ambient occlusion", a, tolerance, "");
  std::printf("ambient occlusion: mean signed d (glint - Blender) %.4f, correlation %.4f\n", a.meanSigned, a.correlation);
  EXPECT_GT(a.covered, std::size_t(kSize * kSize * 9 / 10));
  EXPECT_LT(std::abs(a.meanSigned), 0.005) << "a bias noise does not make";
  EXPECT_LT(a.mean, 0.03);
  EXPECT_GT(a.correlation, 0.95);
  EXPECT_GT(double(a.within), 0.99 * double(a.covered));
}

// UDIM: two tori side by side, the second turned a quarter turn about X, its UVs in tile
// 1002 and its high poly dimpled instead of studded; glint's n.<UDIM>.png tiles (8-bit, object space) against Blender's
// bake into a tiled image (8-bit PNG per tile), tile by tile.
TEST_F(BakeBlender, UdimTilesAgree) {
  const fs::path d = dir("udim");
  const mat4 apart = glm::rotate(glm::translate(mat4(1.0f), vec3(3.0f, 0.0f, 0.0f)), 1.5707964f, vec3(1.0f, 0.0f, 0.0f));
  Mesh lowB = lowTorus();
  lowB.transform(apart);
  for (vec2& uv : lowB.uvs) uv.x += 1.0f;
  writeLowAsBlenderSeesIt({lowTorus(), lowB}, d / "low.obj");
  Mesh high = highTorus();
  Mesh highB = bake::makeStuddedTorus({.segments = 96, .sides = 48, .studsAround = 12, .studsAcross = 4, .studHeight = -0.03f});
  highB.transform(apart);
  high.append(highB);
  writeHighUnwelded(high, d / "high.obj");
  const auto r = runGlint("bake " + quoted(d / "low.obj") + " " + quoted(d / "high.obj") + " -o " + quoted(d / "n.<UDIM>.png") +
                          " --space object --opacity " + quoted(d / "opacity.<UDIM>.png") +
                          " --size 256x256 --samples 1 --padding 0 -q" + kRays);
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(blenderBake(d / "low.obj", d / "high.obj", d / "blender.<UDIM>.png", "normal", 1));
  EXPECT_FALSE(fs::exists(d / "n.1003.png"));
  EXPECT_FALSE(fs::exists(d / "blender.1003.png"));
  EXPECT_FALSE(fs::exists(d / "blender.1011.png"));
  // 8-bit codes: each component within half a step of the value, so two encodings of one
  // normal differ by up to ~0.45° (a step is 2/255 in n); 1° leaves room for that.
  const double tolerance = 1.0;
  for (const char* tile : {"1001", "1002"}) {
    const Image gn = loadImage(d / ("n." + std::string(tile) + ".png"));
    const Image opacity = loadImage(d / ("opacity." + std::string(tile) + ".png"));
    const Image bn = loadImage(d / ("blender." + std::string(tile) + ".png"));
    const Comparison c = compare(gn, opacity, bn, tolerance, [&](int x, int y) {
      const double a = degreesBetween(decodeNormal(gn, x, y), decodeNormal(bn, x, y));
      return std::pair{a, a};
    });
    print((std::string("UDIM tile ") + tile + ", normal (object space, 8-bit)").c_str(), c, tolerance, "deg");
    EXPECT_GT(c.covered, std::size_t(kSize * kSize * 9 / 10)) << tile;
    EXPECT_LT(c.glintOnly + c.blenderOnly, std::size_t(kSize * kSize / 100)) << tile;
    EXPECT_LT(c.mean, 0.3) << tile;
    EXPECT_LT(c.max, tolerance) << tile;
  }
  // The tiles hold different parts: tile 1001 of glint against 1002 of Blender is far off.
  const Image g1 = loadImage(d / "n.1001.png"), b2 = loadImage(d / "blender.1002.png"), o1 = loadImage(d / "opacity.1001.png");
  const Comparison cross = compare(g1, o1, b2, tolerance, [&](int x, int y) {
    const double a = degreesBetween(decodeNormal(g1, x, y), decodeNormal(b2, x, y));
    return std::pair{a, a};
  });
  EXPECT_GT(cross.mean, 5.0) << "tile 1001 against the other tile's bake";
}

}  // namespace
