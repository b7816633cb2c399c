// The shadow cutter against independent computations: Embree shadow rays, areas per
// input triangle, the edge topology of the result; WWDC 2003 session 212's hard cases.
#include "glint/core/error.h"
#include "glint/cut/cutter.h"
#include "glint/pipedream/machine_room.h"

#include "cut_test_util.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

using namespace glint;
using namespace glint::cut;
using namespace glint::cut::testing;

namespace {

/// A closed slab as the floor, a closed box floating above it.
Mesh boxOverFloor() {
  Mesh scene = makeBox({-4, -1, -4}, {4, 0, 4});
  scene.append(makeBox({-0.5f, 1, -0.5f}, {0.5f, 2, 0.5f}));
  return scene;
}

void expectClosed(const Mesh& scene, const CutMesh& mesh) { EXPECT_EQ(surfacesStillClosed(scene, mesh), ""); }

/// Output vertices within a hair (1e-9) of an input point are that point, exactly: precise
/// and float positions. Returns how many there are.
std::size_t expectInputPointsExact(const Mesh& scene, const CutMesh& mesh) {
  std::vector<vec3> points = scene.positions;
  std::sort(points.begin(), points.end(), [](const vec3& a, const vec3& b) { return a.x < b.x; });
  std::size_t found = 0, wrong = 0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const dvec3& x = mesh.precisePositions[v];
    auto it = std::lower_bound(points.begin(), points.end(), x.x - 1e-9, [](const vec3& q, double key) { return q.x < key; });
    for (; it != points.end() && double(it->x) <= x.x + 1e-9; ++it) {
      const dvec3 d = glm::abs(x - dvec3(*it));
      if (std::max({d.x, d.y, d.z}) > 1e-9) continue;
      ++found;
      if ((x != dvec3(*it) || mesh.positions[v] != *it) && ++wrong <= 5)
        ADD_FAILURE() << fmt::format("vertex {} at ({}, {}, {}) is input point ({}, {}, {}) but for {:.3g}", v, x.x, x.y,
                                     x.z, it->x, it->y, it->z, std::max({d.x, d.y, d.z}));
      break;
    }
  }
  EXPECT_EQ(wrong, 0u) << "of " << found << " output vertices on input points";
  return found;
}

/// The oracle's figures, printed for docs/cut.md, and checked.
void expectAgreement(const char* what, const OracleResult& o) {
  EXPECT_GT(o.samples, 1000u);
  std::printf("[ oracle   ] %s: %zu of %zu shadow rays agree (%.5f %%), %zu thin pieces not sampled\n", what, o.agree,
              o.samples, 100.0 * o.agreement(), o.skipped);
  EXPECT_GE(o.agreement(), 0.9999) << o.agree << " of " << o.samples;
}

}  // namespace

TEST(Cut, BoxOverFloorAgreesWithShadowRays) {
  const Mesh scene = boxOverFloor();
  CutOptions options;
  options.lights = {{.position = {0.7f, 6.0f, 0.4f}, .name = "key"}};
  const CutResult result = cut::cut(scene, options);
  EXPECT_GT(result.mesh.polygonCount(), scene.triangleCount());
  const OracleResult o = shadowOracle(scene, result.mesh, options.lights, 64);
  expectAgreement("box over floor", o);
  EXPECT_LT(worstAreaError(scene, result.mesh), 1e-6);
  expectClosed(scene, result.mesh);
  // The floor under the box is shadowed, its far corners lit.
  EXPECT_GT(result.stats.lights[0].shadowedArea, 1.0);
  EXPECT_GT(result.stats.lights[0].litArea, 60.0);
}

/// Three long triangles, each passing over the next one and under the previous one: no
/// order sorts them (WWDC 2003 session 212's "root of all evil"), over a closed floor slab.
Mesh cyclicTriangles() {
  Mesh scene = makeBox({-4, -1, -4}, {4, 0, 4});
  for (int i = 0; i < 3; ++i) {
    const float angle = float(i) * 2.0f * kPi / 3.0f;
    const vec3 t(std::cos(angle), 0.0f, std::sin(angle));   // along the triangle
    const vec3 n(-t.z, 0.0f, t.x);                            // across it
    const vec3 c = 0.6f * n;                                  // the three lines make a triangle
    const vec3 start = c - 2.2f * t, end = c + 2.2f * t;
    // High (1.6) at its wide start, low (0.8) at its tip: where the tip of i crosses the
    // start of i + 1, i + 1 is above.
    scene.append(makeTriangle(start + vec3(0, 1.6f, 0) - 0.5f * n, end + vec3(0, 0.8f, 0), start + vec3(0, 1.6f, 0) + 0.5f * n));
  }
  return scene;
}

/// Shadowed area of the triangle's pieces (of its patch's, when it merged with coplanar
/// neighbours).
double shadowedAreaOf(const CutResult& r, std::uint32_t triangle, int light = 0) {
  double area = 0.0;
  for (std::size_t p = 0; p < r.mesh.polygonCount(); ++p)
    if (r.mesh.polygonSource[p] == r.mesh.trianglePatch[triangle] && !(r.mesh.polygonMask[p] & (1u << light)))
      area += polygonArea(r.mesh, p);
  return area;
}

TEST(Cut, CyclicallyOverlappingTrianglesAllShadowEachOther) {
  const Mesh scene = cyclicTriangles();
  CutOptions options;
  options.lights = {{.position = {0.2f, 8.0f, -0.3f}}};
  const CutResult r = cut::cut(scene, options);
  const OracleResult o = shadowOracle(scene, r.mesh, options.lights, 256);
  expectAgreement("cyclic triangles", o);
  EXPECT_LT(worstAreaError(scene, r.mesh), 1e-6);
  // Each of the three (input triangles 12, 13, 14) is partly in the shadow of another.
  for (std::uint32_t t = 12; t < 15; ++t) {
    const double shadowed = shadowedAreaOf(r, t);
    EXPECT_GT(shadowed, 0.01) << "triangle " << t;
  }
}

TEST(Cut, CoplanarTrianglesDoNotShadowEachOther) {
  Mesh scene = makeBox({-4, -1, -4}, {4, 0, 4});
  // Three overlapping triangles in one plane (decals), and a stack of parallel squares.
  for (int i = 0; i < 3; ++i) {
    const float x = -2.5f + 0.4f * float(i);
    scene.append(makeTriangle({x, 0.5f, -1.0f}, {x + 1.5f, 0.5f, 1.0f}, {x + 1.5f, 0.5f, -1.0f}));
  }
  for (int i = 0; i < 3; ++i) {
    const float h = 1.0f + 0.5f * float(i), s = 1.0f - 0.25f * float(i);
    Mesh square = makePlane(2.0f * s);
    square.transform(glm::translate(mat4(1.0f), vec3(2.0f, h, 0.0f)));
    scene.append(square);
  }
  CutOptions options;
  options.lights = {{.position = {1.0f, 7.0f, 0.5f}}};
  const CutResult r = cut::cut(scene, options);
  const OracleResult o = shadowOracle(scene, r.mesh, options.lights, 128);
  expectAgreement("coplanar stack", o);
  EXPECT_LT(worstAreaError(scene, r.mesh), 1e-6);
  for (std::uint32_t t = 12; t < 15; ++t) EXPECT_EQ(shadowedAreaOf(r, t), 0.0) << "decal " << t;
  // The lower squares are partly shadowed by the ones above; the top one is not.
  EXPECT_GT(shadowedAreaOf(r, 15) + shadowedAreaOf(r, 16), 0.1);
  EXPECT_EQ(shadowedAreaOf(r, 19) + shadowedAreaOf(r, 20), 0.0);
}

TEST(Cut, OccluderSharingAnEdgeWithItsReceiver) {
  // An open book: the hinge along z at x = 0, the receiver flat on x ∈ [0, 2], the other
  // page leaning over it at 60°. Light high on the left: the leaning page shades the
  // receiver near the hinge; light high on the right: nothing is shaded.
  const vec3 h0(0, 0, -1), h1(0, 0, 1);
  const vec3 lean(std::cos(1.0472f) * 2.0f, std::sin(1.0472f) * 2.0f, 0.0f);
  Mesh scene = makeTriangle(h0, h1, vec3(2, 0, 0));
  scene.append(makeTriangle(h1, h0, lean));
  CutOptions options;
  options.lights = {{.position = {-0.5f, 6.0f, 0.2f}, .name = "left"}, {.position = {4.0f, 3.0f, 0.1f}, .name = "right"}};
  const CutResult r = cut::cut(scene, options);
  const OracleResult o = shadowOracle(scene, r.mesh, options.lights, 512);
  expectAgreement("shared-edge occluder", o);
  EXPECT_LT(worstAreaError(scene, r.mesh), 1e-6);
  const double shaded = shadowedAreaOf(r, 0, 0);
  EXPECT_GT(shaded, 0.05);
  EXPECT_LT(shaded, 2.0);
  EXPECT_EQ(shadowedAreaOf(r, 0, 1), 0.0);
  // The shared edge stays shared: two triangles, one edge between them, both sides agree.
  const EdgeMap map = EdgeMap::build(triangulate(r.mesh).mesh);
  EXPECT_EQ(map.count(EdgeKind::NonManifold), 0u);
  EXPECT_EQ(map.count(EdgeKind::Inconsistent), 0u);
  EXPECT_EQ(map.borderLoops(), 1u);
}

TEST(Cut, RandomTriangleSoupAgreesWithShadowRays) {
  // Intersecting, touching and thin triangles at random, two lights.
  Mesh scene = makeBox({-3, -1, -3}, {3, 0, 3});
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f), h(0.3f, 2.5f), s(0.05f, 0.8f);
  for (int i = 0; i < 150; ++i) {
    const vec3 c(u(rng), h(rng), u(rng));
    scene.append(makeTriangle(c + vec3(s(rng), s(rng) - 0.4f, s(rng)), c - vec3(s(rng), s(rng) - 0.4f, 0.0f),
                              c + vec3(0.0f, s(rng) - 0.4f, -s(rng))));
  }
  CutOptions options;
  options.lights = {{.position = {0.3f, 6.0f, 0.2f}}, {.position = {-4.0f, 3.0f, 2.5f}}};
  const CutResult r = cut::cut(scene, options);
  const OracleResult o = shadowOracle(scene, r.mesh, options.lights, 32);
  expectAgreement("random soup", o);
  EXPECT_GT(o.samples, 50000u);
  EXPECT_LT(worstAreaError(scene, r.mesh), 1e-6);
}

TEST(Cut, GridAlignedSceneStaysWatertight) {
  // Axis-aligned boxes on a tessellated slab, lights at round coordinates: many vertices
  // lie exactly on many planes, which only exact predicates classify consistently.
  Mesh scene = makeBox({-4, -1, -4}, {4, 0, 4});
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      scene.append(makeBox({-3.0f + 1.5f * float(i), 0.0f, -3.0f + 1.5f * float(j)},
                           {-2.0f + 1.5f * float(i), 0.5f + 0.25f * float(i + j), -2.0f + 1.5f * float(j)}));
  CutOptions options;
  options.lights = {{.position = {0.0f, 4.0f, 0.0f}}, {.position = {2.0f, 2.0f, -1.0f}}};
  const CutResult r = cut::cut(scene, options);
  expectClosed(scene, r.mesh);
  EXPECT_LT(worstAreaError(scene, r.mesh), 1e-6);
  const OracleResult o = shadowOracle(scene, r.mesh, options.lights, 64);
  expectAgreement("grid-aligned boxes", o);
  EXPECT_GT(r.stats.symbolicPredicates, 0u);
}


namespace {

Mesh soup(int count, std::uint32_t seed) {
  Mesh scene = makeBox({-3, -1, -3}, {3, 0, 3});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f), h(0.3f, 2.5f), s(0.05f, 0.8f);
  for (int i = 0; i < count; ++i) {
    const vec3 c(u(rng), h(rng), u(rng));
    scene.append(makeTriangle(c + vec3(s(rng), s(rng) - 0.4f, s(rng)), c - vec3(s(rng), s(rng) - 0.4f, 0.0f),
                              c + vec3(0.0f, s(rng) - 0.4f, -s(rng))));
  }
  scene.append(makeMachineRoom({.modules = 1}));
  return scene;
}

void expectSame(const CutMesh& a, const CutMesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.precisePositions, b.precisePositions);
  EXPECT_EQ(a.polygonStart, b.polygonStart);
  EXPECT_EQ(a.corners, b.corners);
  EXPECT_EQ(a.straight, b.straight);
  EXPECT_EQ(a.polygonSource, b.polygonSource);
  EXPECT_EQ(a.polygonMask, b.polygonMask);
}

}  // namespace

TEST(Cut, OutputDoesNotDependOnThreads) {
  const Mesh scene = soup(300, 11);
  CutOptions options;
  options.lights = {{.position = {0.3f, 9.0f, 0.2f}}, {.position = {-5.0f, 4.0f, 3.5f}}};
  CutResult one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = cut::cut(scene, options);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = cut::cut(scene, options);
  }
  ASSERT_GT(one.stats.facesBeforeMerge, scene.triangleCount());  // shadows were cut in
  expectSame(one.mesh, two.mesh);
}

TEST(Cut, ShardsMergeIntoTheSameMesh) {
  const Mesh scene = soup(120, 5);
  CutOptions options;
  options.lights = {{.position = {0.3f, 9.0f, 0.2f}, .name = "key"}};
  const CutResult whole = cut::cut(scene, options);
  const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "cut-shards";
  std::filesystem::create_directories(dir);
  std::vector<Shard> shards;
  for (int i = 2; i >= 0; --i) {  // any order
    options.shardIndex = i;
    options.shardCount = 3;
    saveShard(cutShard(scene, options), dir / fmt::format("part{}.shard", i));
    shards.push_back(loadShard(dir / fmt::format("part{}.shard", i)));
  }
  const CutResult merged = mergeShards(scene, shards);
  expectSame(whole.mesh, merged.mesh);
  ASSERT_EQ(merged.lights.size(), 1u);  // the shards' lights, names included
  EXPECT_EQ(merged.lights[0].name, "key");
  // Lights in the options must be the shards' (by position); none: theirs.
  CutOptions same;
  same.lights = {{.position = {0.3f, 9.0f, 0.2f}}};
  expectSame(whole.mesh, mergeShards(scene, shards, same).mesh);
  CutOptions other;
  other.lights = {{.position = {0.3f, 9.5f, 0.2f}, .name = "key"}};
  try {
    mergeShards(scene, shards, other);
    ADD_FAILURE() << "other lights accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("differs from the lights the shards were cut with"), std::string::npos);
  }
  // A missing shard, a shard twice, another scene: one-line errors.
  EXPECT_THROW(mergeShards(scene, {shards[0], shards[1]}), Error);
  EXPECT_THROW(mergeShards(scene, {shards[0], shards[1], shards[1]}), Error);
  EXPECT_THROW(mergeShards(soup(121, 5), shards), Error);
  std::filesystem::resize_file(dir / "part1.shard", 100);
  EXPECT_THROW(loadShard(dir / "part1.shard"), Error);
}

// What `glint cut --json` reports and --max-memory checks, from the library alone.
TEST(Cut, ReportAndMemoryEstimate) {
  const Mesh scene = boxOverFloor();
  CutOptions options;
  options.lights = {{.position = {0.1f, 5.0f, 0.2f}, .name = "lamp"}, {.position = {2.0f, 4.0f, -1.0f}}};
  const CutResult r = cut::cut(scene, options);
  const nlohmann::ordered_json j = toJson(r.stats);
  std::vector<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"input_triangles", "output_polygons", "output_triangles", "output_vertices",
                                            "polygons_per_input_triangle", "triangles_per_input_triangle", "pieces_before_merge", "merged_patches", "degenerate_triangles",
                                            "collapsed_triangles", "dropped_slivers", "per_light", "candidates",
                                            "occluders", "clipped_pairs", "cuts", "clipped_pairs_per_second",
                                            "predicates"}));
  EXPECT_EQ(j["input_triangles"], scene.triangleCount());
  EXPECT_EQ(j["output_polygons"], r.mesh.polygonCount());
  EXPECT_DOUBLE_EQ(j["polygons_per_input_triangle"].get<double>(),
                   double(r.mesh.polygonCount()) / double(scene.triangleCount()));
  ASSERT_EQ(j["per_light"].size(), 2u);
  EXPECT_EQ(j["per_light"][0]["name"], "lamp");
  EXPECT_EQ(j["per_light"][1]["name"], "light1");
  EXPECT_EQ(j["per_light"][0]["lit_polygons"].get<std::uint64_t>() + j["per_light"][0]["shadowed_polygons"].get<std::uint64_t>(),
            r.mesh.polygonCount());
  EXPECT_EQ(j["predicates"]["exact"], r.stats.exactPredicates);
  EXPECT_EQ(toJson(options.lights).dump(),
            R"([{"name":"lamp","position":[0.10000000149011612,5.0,0.20000000298023224]},{"name":"","position":[2.0,4.0,-1.0]}])");
  options.shardCount = 2;
  const Shard half = cutShard(scene, options);
  EXPECT_EQ(toJson(half).dump(), fmt::format(R"({{"input_triangles":{},"receivers":{},"clipped_pairs":{}}})",
                                             scene.triangleCount(), half.stats.receivers, half.stats.clippedPairs));
  // 28 MiB, per thread 4 + 6 MiB per light (at most 2 KiB per triangle and light), 700
  // bytes per triangle and 400 per triangle and light (at least one light).
  EXPECT_DOUBLE_EQ(estimatePeakMemoryMiB(0, 1, 2), 28.0);
  EXPECT_DOUBLE_EQ(estimatePeakMemoryMiB(1024, 1, 2), 28.0 + 2 * 2.0 + 1024.0 * 1100.0 / (1 << 20));  // small: small scratch
  EXPECT_DOUBLE_EQ(estimatePeakMemoryMiB(1 << 20, 1, 2), 28.0 + 2 * 10.0 + 1100.0);
  EXPECT_DOUBLE_EQ(estimatePeakMemoryMiB(1 << 20, 0, 2), estimatePeakMemoryMiB(1 << 20, 1, 2));
  EXPECT_DOUBLE_EQ(estimatePeakMemoryMiB(1 << 20, 4, 8), 28.0 + 8 * 28.0 + 2300.0);
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_DOUBLE_EQ(estimatePeakMemoryMiB(1 << 20, 2), 28.0 + 16.0 + 1500.0);  // threads: oneTBB's limit
  }
}

TEST(Cut, DegenerateInputIsCarriedThroughWithWarnings) {
  Mesh scene = makeBox({-2, -1, -2}, {2, 0, 2});
  scene.append(makeBox({-0.5f, 1, -0.5f}, {0.5f, 2, 0.5f}));
  scene.append(makeTriangle({0, 0.5f, 0}, {1, 0.5f, 0}, {2, 0.5f, 0}));        // collinear: zero area
  scene.append(makeTriangle({0, 0.7f, 0}, {0, 0.7f, 0}, {1, 0.7f, 1}));        // two corners at one point
  scene.append(makeTriangle({-1, 0.6f, 1}, {1, 0.6f, 1}, {1, 0.6f, 1.000001f}));  // a sliver, 1e-6 wide
  CutOptions options;
  options.lights = {{.position = {0.1f, 5.0f, 0.2f}}};
  const CutResult r = cut::cut(scene, options);
  EXPECT_EQ(r.stats.degenerateTriangles, 1u);
  EXPECT_EQ(r.stats.collapsedTriangles, 1u);
  ASSERT_GE(r.warnings.size(), 2u);
  // The zero-area triangle is kept, unlit; the collapsed one dropped.
  bool found = false;
  for (std::size_t p = 0; p < r.mesh.polygonCount(); ++p) {
    EXPECT_NE(r.mesh.polygonSource[p], 25u);
    if (r.mesh.polygonSource[p] == 24) {
      found = true;
      EXPECT_EQ(r.mesh.polygonMask[p], 0u);
    }
  }
  EXPECT_TRUE(found);
  const OracleResult o = shadowOracle(scene, r.mesh, options.lights, 64);
  expectAgreement("degenerate input", o);
  expectClosed(scene, r.mesh);
}

TEST(Cut, BadInputIsAOneLineError) {
  CutOptions options;
  options.lights = {{.position = {0, 5, 0}}};
  EXPECT_THROW(cut::cut(Mesh{}, options), Error);
  Mesh nan = makeBox({-1, -1, -1}, {1, 1, 1});
  nan.positions[3].y = std::numeric_limits<float>::quiet_NaN();
  try {
    cut::cut(nan, options);
    FAIL() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  CutOptions none;
  EXPECT_THROW(cut::cut(makeBox({-1, -1, -1}, {1, 1, 1}), none), Error);
  CutOptions far;
  far.lights = {{.position = {std::numeric_limits<float>::infinity(), 0, 0}}};
  EXPECT_THROW(cut::cut(makeBox({-1, -1, -1}, {1, 1, 1}), far), Error);
}

TEST(Cut, LightsInOddPlacesWarn) {
  const Mesh scene = boxOverFloor();
  CutOptions options;
  // On the floor's top face; inside the floating box.
  options.lights = {{.position = {2.0f, 0.0f, 1.0f}, .name = "onfloor"}, {.position = {0.1f, 1.5f, 0.2f}, .name = "inbox"}};
  const CutResult r = cut::cut(scene, options);
  std::string all;
  for (const auto& w : r.warnings) all += w + "\n";
  EXPECT_NE(all.find("'onfloor' lies on a surface"), std::string::npos) << all;
  EXPECT_NE(all.find("'inbox' is inside a closed mesh"), std::string::npos) << all;
  // Inside the box, only the box's inside is lit.
  EXPECT_EQ(r.stats.lights[1].litArea, 6.0) << "the box's six faces, from inside";
  const OracleResult o = shadowOracle(scene, r.mesh, options.lights, 64);
  expectAgreement("odd lights", o);
  EXPECT_GT(r.stats.lights[0].grazingTriangles, 0u);
}

// Issue 21: a floor at y = 0 came out at y = −1.1e-16. Vertices that are input points, or
// that lie on an input triangle whose plane is axis-aligned, keep the input's coordinates.
TEST(Cut, ExactInputCoordinatesStayExact) {
  Mesh scene = makeGrid(6, 6, 8.0f);                            // the floor: y = 0, open
  scene.append(makeBox({4.0f, 0.0f, -4.0f}, {4.5f, 3.0f, 4.0f}));  // a wall: its face x = 4
  scene.append(makeBox({-1.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f}));  // a box standing on the floor
  scene.append(makeBox({1.0f, 1.0f, 1.0f}, {1.5f, 1.7f, 1.5f}));    // one floating above it
  CutOptions options;
  options.lights = {{.position = {0.3f, 5.0f, 0.2f}, .name = "key"}, {.position = {-2.1f, 3.3f, 1.7f}, .name = "fill"}};
  const CutResult r = cut::cut(scene, options);
  const CutMesh& m = r.mesh;
  ASSERT_GT(r.stats.cuts, 0u);
  std::size_t onAxisPlanes = 0, onInputPoints = 0, floorVertices = 0;
  for (std::size_t p = 0; p < m.polygonCount(); ++p) {
    const std::uint32_t f = m.polygonSource[p];
    const vec3 a = scene.positions[scene.indices[3 * f]], b = scene.positions[scene.indices[3 * f + 1]],
               c = scene.positions[scene.indices[3 * f + 2]];
    for (std::uint32_t i = m.polygonStart[p]; i < m.polygonStart[p + 1]; ++i) {
      const std::uint32_t v = m.corners[i];
      for (int k = 0; k < 3; ++k) {
        if (a[k] != b[k] || a[k] != c[k]) continue;
        ++onAxisPlanes;
        floorVertices += f < 72;  // the grid's triangles come first
        EXPECT_EQ(m.positions[v][k], a[k]) << "polygon " << p << " of triangle " << f << ", axis " << k;
        EXPECT_EQ(m.precisePositions[v][k], double(a[k])) << "polygon " << p << " of triangle " << f << ", axis " << k;
        EXPECT_FALSE(std::signbit(m.positions[v][k]) && a[k] == 0.0f) << "−0 for 0, polygon " << p;
      }
    }
  }
  // Vertices that are input points (within a hair: nothing else of this scene comes so close)
  // are those points exactly: the box's corners on the floor, shadows meeting them.
  onInputPoints = expectInputPointsExact(scene, m);
  // Enough of each kind to mean something (the floor's 72 cells merge into a few convex
  // pieces around the shadows: 86 floor corners, 214 on axis planes, 29 input points).
  EXPECT_GT(floorVertices, 60u);
  EXPECT_GT(onAxisPlanes, 150u);
  EXPECT_GT(onInputPoints, 20u);
  // Still the same cut: watertight, every piece's mask as the shadow rays say.
  expectClosed(scene, m);
  EXPECT_LT(worstAreaError(scene, m), 1e-6);
  expectAgreement("exact coordinates", shadowOracle(scene, m, options.lights, 32));
}

// Issue 24: the optimization step across triangles. A floor of 8 × 8 cells (128
// triangles) under a box comes out as a few convex pieces around the box's shadow, with
// the box's four shadow corners and the floor's four corners, and nothing else of the grid.
TEST(Cut, CoplanarNeighboursMergeAcrossTriangles) {
  Mesh scene = makeGrid(8, 8, 8.0f);                            // y = 0, open; triangles 0–127
  scene.append(makeBox({-1.0f, 1.0f, -1.0f}, {1.0f, 1.5f, 1.0f}));  // floating above it
  CutOptions options;
  options.lights = {{.position = {0.7f, 6.0f, 0.4f}, .name = "key"}};
  const CutResult r = cut::cut(scene, options);
  const CutMesh& m = r.mesh;
  ASSERT_EQ(m.trianglePatch.size(), scene.triangleCount());
  for (std::uint32_t t = 0; t < 128; ++t) EXPECT_EQ(m.trianglePatch[t], 0u) << "floor triangle " << t;
  std::size_t floorTriangles = 0, floorPolygons = 0, shadowed = 0;
  for (std::size_t p = 0; p < m.polygonCount(); ++p)
    if (m.polygonSource[p] == 0) {
      ++floorPolygons;
      floorTriangles += m.cornerCount(p) - 2;
      shadowed += m.polygonMask[p] == 0;
    }
  // The lit floor is a square with a square hole: 8 corners, 2 loops, 8 triangles; the
  // shadow a quadrilateral: 2. (Each box face's two triangles merge too.)
  EXPECT_EQ(floorTriangles, 10u);
  EXPECT_GE(shadowed, 1u);
  EXPECT_LE(floorPolygons, 8u);
  EXPECT_EQ(r.stats.mergedPatches, 1u + 0u) << "the floor (the box's faces are whole: nothing to drop)";
  EXPECT_LT(worstAreaError(scene, m), 1e-9);
  expectClosed(scene, m);
  expectAgreement("floor under a box, merged", shadowOracle(scene, m, options.lights, 256));

  // The same by shards, and on one thread: the same mesh.
  std::vector<Shard> shards;
  for (int i = 0; i < 3; ++i) {
    CutOptions part = options;
    part.shardIndex = i;
    part.shardCount = 3;
    shards.push_back(cutShard(scene, part));
  }
  expectSame(m, mergeShards(scene, shards).mesh);
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    expectSame(m, cut::cut(scene, options).mesh);
  }

  // Merge groups: a group of its own per triangle merges nothing; two halves merge apart.
  CutOptions apart = options;
  apart.mergeGroups.resize(scene.triangleCount());
  std::iota(apart.mergeGroups.begin(), apart.mergeGroups.end(), 0u);
  const CutResult alone = cut::cut(scene, apart);
  EXPECT_EQ(alone.stats.mergedPatches, 0u);
  for (std::uint32_t t = 0; t < scene.triangleCount(); ++t) EXPECT_EQ(alone.mesh.trianglePatch[t], t);
  EXPECT_GT(alone.stats.outputTriangles, 128u);
  expectAgreement("floor under a box, unmerged", shadowOracle(scene, alone.mesh, options.lights, 16));
  CutOptions halves = options;
  halves.mergeGroups.assign(scene.triangleCount(), 7u);
  for (std::uint32_t t = 0; t < 64; ++t) halves.mergeGroups[t] = 3u;  // the grid's first four rows
  const CutResult two = cut::cut(scene, halves);
  EXPECT_EQ(two.mesh.trianglePatch[0], 0u);
  EXPECT_EQ(two.mesh.trianglePatch[127], 64u);
  EXPECT_LT(worstAreaError(scene, two.mesh), 1e-9);
  expectAgreement("floor under a box, two groups", shadowOracle(scene, two.mesh, options.lights, 64));
  CutOptions wrong = options;
  wrong.mergeGroups = {1, 2, 3};
  EXPECT_THROW(cut::cut(scene, wrong), Error);
}

TEST(Cut, MachineRoomAgreesWithShadowRaysAndStaysClosed) {
  // The bench's Pipe Dream stand-in at one module (~10k triangles), its two lights.
  const MachineRoomOptions room{.modules = 1};
  const Mesh scene = makeMachineRoom(room);
  const auto l = machineRoomLights(room);
  CutOptions options;
  options.lights = {{.position = l[0], .name = "key"}, {.position = l[1], .name = "fill"}};
  const CutResult r = cut::cut(scene, options);
  expectAgreement("machine room, 1 module", shadowOracle(scene, r.mesh, options.lights, 8));
  const double areaError = worstAreaError(scene, r.mesh);
  std::printf("[ area     ] machine room, 1 module: worst relative area error per input triangle %.3g\n", areaError);
  EXPECT_LT(areaError, 1e-6);
  expectClosed(scene, r.mesh);
  EXPECT_EQ(r.stats.droppedSlivers, 0u);
  // Issue 21: where the floor's and the parts' pieces meet a part's corner (another surface's
  // input point), they have its exact coordinates; a hair off before.
  EXPECT_GT(expectInputPointsExact(scene, r.mesh), 1000u);
}

TEST(Cut, MachineRoomPartsAreClosedOutwardSolids) {
  const Mesh one = makeMachineRoom({.modules = 1}), four = makeMachineRoom({.modules = 4});
  // Each module adds the same parts; the floor and walls grow with the stage.
  EXPECT_EQ(machineRoomModulesFor(550000), 63);
  const std::vector<std::uint32_t> label = surfaces(four);
  std::map<std::uint32_t, std::vector<std::uint32_t>> parts;
  for (std::uint32_t t = 0; t < label.size(); ++t) parts[label[t]].push_back(t);
  int closed = 0, open = 0;
  for (const auto& [root, triangles] : parts) {
    Mesh part;
    part.positions = four.positions;
    double volume = 0.0;
    for (std::uint32_t t : triangles) {
      const std::uint32_t a = four.indices[3 * t], b = four.indices[3 * t + 1], c = four.indices[3 * t + 2];
      part.indices.insert(part.indices.end(), {a, b, c});
      volume += glm::dot(dvec3(four.positions[a]), glm::cross(dvec3(four.positions[b]), dvec3(four.positions[c]))) / 6.0;
    }
    if (EdgeMap::build(part).isClosedManifold()) {
      ++closed;
      EXPECT_GT(volume, 0.0) << "part of triangle " << root << " faces inwards";
    } else {
      ++open;
    }
  }
  EXPECT_EQ(open, 1);  // the floor and two walls, joined along their shared edges
  EXPECT_EQ(closed, 4 * (1 + 3 + 6 + 2 + 4));  // platform, drums, upright pipes, pipes, struts
  EXPECT_GT(one.triangleCount(), 9000u);
}
