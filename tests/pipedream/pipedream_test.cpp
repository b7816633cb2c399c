// The pipedream scene's CPU parts (no GL): the instrument machine, its score, the motion-
// blur ball mesh, the cut cache and the geometry the renderer draws from a cut.
#include "glint/core/cache.h"
#include "glint/core/error.h"
#include "glint/cut/cache.h"
#include "glint/mesh/adjacency.h"
#include "glint/pipedream/machine_room.h"
#include "glint/pipedream/motion_blur.h"
#include "glint/pipedream/score.h"
#include "glint/scenes/pipedream.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>
#include <tuple>
#include <thread>
#include <vector>

using namespace glint;
namespace rp = glint::render::pipedream;
namespace pd = glint::scenes::pipedream;
namespace fs = std::filesystem;

namespace {

fs::path freshDirectory(const std::string& name) {
  const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "pipedream" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

bool sameMesh(const Mesh& a, const Mesh& b) {
  return a.indices == b.indices && a.positions.size() == b.positions.size() &&
         std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(vec3)) == 0 &&
         a.normals.size() == b.normals.size() &&
         std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(vec3)) == 0;
}

}  // namespace

// ------------------------------------------------------------------ the machine

TEST(InstrumentMachine, IsDeterministicAndEveryStaticPartIsClosed) {
  const InstrumentMachine a = makeInstrumentMachine({.detail = 2}), b = makeInstrumentMachine({.detail = 2});
  EXPECT_TRUE(sameMesh(a.staticMesh, b.staticMesh));
  EXPECT_TRUE(sameMesh(a.skin, b.skin));
  EXPECT_EQ(a.triangleMaterial.size(), a.staticMesh.triangleCount());
  a.staticMesh.validate("machine");
  // The room is one open surface; everything after it is closed solids (what the cutter
  // and the naive method's volumes rely on).
  Mesh solids;
  solids.positions = a.staticMesh.positions;
  solids.indices.assign(a.staticMesh.indices.begin() + std::ptrdiff_t(3 * a.shellTriangles), a.staticMesh.indices.end());
  EXPECT_TRUE(EdgeMap::build(solids).isClosedManifold());
  for (const Mesh* part : {&a.skin, &a.cymbal, &a.mallet}) EXPECT_TRUE(EdgeMap::build(*part).isClosedManifold());
  EXPECT_EQ(a.drums.size(), 12u);
  EXPECT_EQ(a.mallets.size(), 12u);
  EXPECT_EQ(a.launchers.size(), 6u);
  EXPECT_EQ(a.lights.size(), 2u);
}

TEST(InstrumentMachine, TheMalletsShadowCasterIsInsideTheMallet) {
  // Detail 13 (the default): 30 × 15 head, a 10 × 5 proxy. Detail 1: an 8 × 4 head, no
  // proxy small enough to divide it (the mallet casts its own shadow).
  for (const int detail : {13, 1}) {
    const InstrumentMachine m = makeInstrumentMachine({.detail = detail});
    const Mesh& proxy = m.malletShadow;
    EXPECT_TRUE(EdgeMap::build(proxy).isClosedManifold()) << detail;
    // Every proxy vertex is inside the mallet's arm or its head (both convex: behind every
    // face's plane), so the whole proxy is.
    const auto inside = [&](vec3 p, std::size_t first, std::size_t last) {
      for (std::size_t t = first; t < last; ++t) {
        const vec3 a = m.mallet.positions[m.mallet.indices[3 * t]], b = m.mallet.positions[m.mallet.indices[3 * t + 1]],
                   c = m.mallet.positions[m.mallet.indices[3 * t + 2]];
        const vec3 n = glm::cross(b - a, c - a);
        if (glm::length(n) > 0.0f && glm::dot(glm::normalize(n), p - a) > 1e-6f) return false;  // float rounding at ~1 m
      }
      return true;
    };
    const std::size_t arm = 12, all = m.mallet.triangleCount();
    for (const vec3& p : proxy.positions) ASSERT_TRUE(inside(p, 0, arm) || inside(p, arm, all)) << detail;
    if (detail == 13) {
      EXPECT_LT(proxy.triangleCount() * 5, m.mallet.triangleCount());
    } else {
      EXPECT_EQ(proxy.triangleCount(), m.mallet.triangleCount());
    }
  }
}

TEST(InstrumentMachine, PolygonsGrowWithDetail) {
  std::size_t last = 0;
  for (int detail = 1; detail <= 6; ++detail) {
    const std::size_t n = makeInstrumentMachine({.detail = detail}).staticMesh.triangleCount();
    EXPECT_GT(n, last) << "detail " << detail;
    last = n;
  }
}

// ------------------------------------------------------------------ the score

TEST(Score, BallsFlyExactParabolasFromLauncherToInstrumentToCollector) {
  const InstrumentMachine m = makeInstrumentMachine({.detail = 1});
  const glint::pipedream::Score score = glint::pipedream::makeScore(m);
  ASSERT_GE(score.flights.size(), 30u);
  for (const glint::pipedream::BallFlight& f : score.flights) {
    // Leaves from inside its launcher's mouth, strikes at `hit`, lands at `land`.
    const vec3 mouth = m.launchers[std::size_t(f.launcher)].mouth;
    EXPECT_LT(glm::length(glint::pipedream::ballAt(f, 0.0).position - mouth), m.ballRadius + 0.02f);
    EXPECT_LT(glm::length(glint::pipedream::ballAt(f, f.hit - f.launch - 1e-6).position - f.strike), 1e-3f);
    EXPECT_LT(glm::length(glint::pipedream::ballAt(f, f.land - f.launch).position - f.finish), 1e-3f);
    // Velocity is the derivative of position (central differences on both arcs).
    for (const double t : {0.2 * (f.hit - f.launch), 0.5 * (f.hit - f.launch), (f.hit - f.launch) + 0.3 * (f.land - f.hit)}) {
      const double h = 1e-3;
      const vec3 d = (glint::pipedream::ballAt(f, t + h).position - glint::pipedream::ballAt(f, t - h).position) / float(2.0 * h);
      EXPECT_LT(glm::length(d - glint::pipedream::ballAt(f, t).velocity), 1e-2f * std::max(1.0f, glm::length(d)));
    }
    // It ends inside its collector's tube: below the rim, within its radius.
    const glint::pipedream::BallState last = glint::pipedream::ballAt(f, f.end - f.launch);
    const MachineCollector& c = m.collectors[std::size_t(f.collector)];
    EXPECT_LT(last.position.y + m.ballRadius, c.top.y + 1e-3f);
    EXPECT_LT(glm::length(vec2(last.position.x - c.top.x, last.position.z - c.top.z)) + m.ballRadius, c.radius + 1e-3f);
  }
}

TEST(Score, PosesAreAFunctionOfTimeThatLoops) {
  const InstrumentMachine m = makeInstrumentMachine({.detail = 1});
  const glint::pipedream::Score score = glint::pipedream::makeScore(m);
  for (const double t : {0.0, 3.7, 6.35, 11.1}) {
    const glint::pipedream::MachinePose a = glint::pipedream::poseAt(m, score, t), b = glint::pipedream::poseAt(m, score, t), c = glint::pipedream::poseAt(m, score, t + score.period);
    ASSERT_EQ(a.balls.size(), c.balls.size()) << t;
    for (std::size_t i = 0; i < a.balls.size(); ++i) {
      EXPECT_EQ(a.balls[i].position, b.balls[i].position);
      EXPECT_LT(glm::length(a.balls[i].position - c.balls[i].position), 1e-3f);
    }
    ASSERT_EQ(a.skins.size(), m.drums.size());
    ASSERT_EQ(a.cymbals.size(), m.cymbals.size());
    ASSERT_EQ(a.mallets.size(), m.mallets.size());
    for (std::size_t i = 0; i < a.mallets.size(); ++i)
      EXPECT_LT(glm::length(vec3(a.mallets[i][3]) - vec3(c.mallets[i][3])), 1e-4f);
  }
  // Balls are always in flight (the talk's stage is never still) and mallets move.
  std::size_t fewest = 1000;
  for (double t = 0.0; t < score.period; t += 0.25) fewest = std::min(fewest, glint::pipedream::poseAt(m, score, t).balls.size());
  EXPECT_GE(fewest, 2u);
  EXPECT_NE(glint::pipedream::poseAt(m, score, 0.1).mallets[0], glint::pipedream::poseAt(m, score, 1.3).mallets[0]);
}

// ------------------------------------------------------------------ motion blur

TEST(MotionBlur, StretchIsSpeedTimesShutterAndTheBallStaysClosed) {
  const glint::pipedream::BlurBallMesh ball = glint::pipedream::buildBlurBall(24, 12);
  EXPECT_EQ(ball.seamTriangles, 48u);
  const float radius = 0.12f, shutter = 1.0f / 30.0f;
  const vec3 centre(1.0f, 2.0f, 3.0f);
  for (const vec3 velocity : {vec3(0.0f), vec3(0.0f, 0.0f, 3.0f), vec3(4.0f, 7.5f, -2.0f), vec3(-12.0f, -3.0f, 1.0f)}) {
    const float speed = glm::length(velocity);
    Mesh stretched;
    stretched.indices = ball.indices;
    for (std::size_t i = 0; i < ball.positions.size(); ++i)
      stretched.positions.push_back(glint::pipedream::stretchVertex(ball.positions[i], ball.rear[i], centre, velocity, radius, shutter));
    // Closed at every speed: at rest the seam quads collapse (degenerate, no edges); moving,
    // they are the pill's sides.
    const EdgeMap edges = EdgeMap::build(stretched);
    EXPECT_EQ(edges.count(EdgeKind::Open), 0u) << speed;
    EXPECT_EQ(edges.count(EdgeKind::NonManifold), 0u) << speed;
    EXPECT_EQ(edges.count(EdgeKind::Inconsistent), 0u) << speed;
    EXPECT_EQ(edges.degenerateFaces(), speed > 0.0f ? 0u : ball.seamTriangles) << speed;
    // Its length along the velocity: the diameter plus speed × shutter; across, the diameter.
    const vec3 dir = speed > 0.0f ? velocity / speed : vec3(0.0f, 0.0f, 1.0f);
    float lo = 1e9f, hi = -1e9f, across = 0.0f;
    for (const vec3& p : stretched.positions) {
      const float along = glm::dot(p - centre, dir);
      lo = std::min(lo, along);
      hi = std::max(hi, along);
      across = std::max(across, glm::length((p - centre) - along * dir));
    }
    EXPECT_NEAR(hi, radius, 1e-5f);
    EXPECT_NEAR(hi - lo, 2.0f * radius + speed * shutter, 1e-4f) << speed;
    EXPECT_NEAR(across, radius, 1e-5f);
    const glint::pipedream::BallBlur blur = glint::pipedream::blurOf(velocity, radius, shutter);
    EXPECT_NEAR(blur.stretch, speed * shutter, 1e-6f);
  }
  // Faster: more see-through and blurrier, never below the floor.
  glint::pipedream::BallBlur last = glint::pipedream::blurOf(vec3(0.0f), radius, shutter);
  EXPECT_EQ(last.opacity, 1.0f);
  EXPECT_EQ(last.lodBias, 0.0f);
  for (float speed = 1.0f; speed < 60.0f; speed *= 1.5f) {
    const glint::pipedream::BallBlur b = glint::pipedream::blurOf(vec3(speed, 0.0f, 0.0f), radius, shutter);
    EXPECT_LE(b.opacity, last.opacity);
    EXPECT_GE(b.opacity, 0.25f);
    EXPECT_GT(b.lodBias, last.lodBias);
    last = b;
  }
  EXPECT_THROW(glint::pipedream::buildBlurBall(24, 11), Error);
}

// ------------------------------------------------------------------ caches

TEST(Cache, BuildsOnceUnderALockAndRebuildsOnlyWhenAsked) {
  const fs::path dir = freshDirectory("core-cache");
  std::atomic<int> builds{0};
  const auto build = [&](const fs::path& tmp) {
    ++builds;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // let the other thread queue on the lock
    std::ofstream(tmp) << "content";
  };
  std::vector<std::thread> threads;
  std::atomic<int> built{0};
  for (int i = 0; i < 4; ++i)
    threads.emplace_back([&] { built += cachedFile(dir, "entry.txt", build).built ? 1 : 0; });
  for (auto& t : threads) t.join();
  EXPECT_EQ(builds.load(), 1);
  EXPECT_EQ(built.load(), 1);
  EXPECT_FALSE(cachedFile(dir, "entry.txt", build).built);
  EXPECT_TRUE(cachedFile(dir, "entry.txt", build, /*rebuild=*/true).built);
  EXPECT_EQ(builds.load(), 2);
  // A builder that fails leaves no file.
  EXPECT_THROW(cachedFile(dir, "broken.txt", [](const fs::path&) { fail(ErrorKind::Internal, "no"); }), Error);
  EXPECT_FALSE(fs::exists(dir / "broken.txt"));
}

TEST(CutCache, CutOnFirstUseLoadedAfterwardsRecutWhenTheInputChanges) {
  const fs::path dir = freshDirectory("cut-cache");
  const InstrumentMachine m = makeInstrumentMachine({.detail = 1});
  const std::vector<cut::Light> lights = pd::cutLights(m);
  const cut::CachedCut first = cut::cachedCut(m.staticMesh, lights, {.directory = dir, .name = "t"});
  EXPECT_TRUE(first.built);
  ASSERT_TRUE(fs::exists(first.file));
  EXPECT_GT(first.triangles.triangleCount(), m.staticMesh.triangleCount());
  const cut::CachedCut second = cut::cachedCut(m.staticMesh, lights, {.directory = dir, .name = "t"});
  EXPECT_FALSE(second.built);
  EXPECT_EQ(second.file, first.file);
  EXPECT_EQ(second.triangles.indices, first.triangles.indices);
  EXPECT_EQ(second.triangles.polygonMask, first.triangles.polygonMask);
  EXPECT_EQ(second.triangles.polygonSource, first.triangles.polygonSource);
  ASSERT_EQ(second.triangles.positions.size(), first.triangles.positions.size());
  EXPECT_EQ(std::memcmp(second.triangles.positions.data(), first.triangles.positions.data(),
                        first.triangles.positions.size() * sizeof(vec3)),
            0);
  // A light moved: another key, another file, cut again.
  std::vector<cut::Light> moved = lights;
  moved[1].position.x += 0.25f;
  const cut::CachedCut third = cut::cachedCut(m.staticMesh, moved, {.directory = dir, .name = "t"});
  EXPECT_TRUE(third.built);
  EXPECT_NE(third.key, first.key);
  EXPECT_NE(third.file, first.file);
  // The geometry changed (another detail): cut again.
  const InstrumentMachine other = makeInstrumentMachine({.detail = 1, .seed = 2});
  EXPECT_NE(cut::cutCacheKey(other.staticMesh, lights), first.key);
  // A damaged file is noticed and replaced.
  fs::resize_file(first.file, fs::file_size(first.file) / 2);
  EXPECT_THROW(cut::loadCutTriangles(first.file, first.key), Error);
  const cut::CachedCut repaired = cut::cachedCut(m.staticMesh, lights, {.directory = dir, .name = "t"});
  EXPECT_TRUE(repaired.built);
  EXPECT_EQ(repaired.triangles.indices, first.triangles.indices);
  EXPECT_NO_THROW(cut::loadCutTriangles(first.file, first.key));
  // Another scene's file under this key's name is refused.
  EXPECT_THROW(cut::loadCutTriangles(third.file, first.key), Error);
}

// ------------------------------------------------------------------ the renderer's geometry

TEST(StaticGeometry, KeepsEveryCutTriangleGroupedByMaskWithUnitNormals) {
  const fs::path dir = freshDirectory("geometry");
  const InstrumentMachine m = makeInstrumentMachine({.detail = 1});
  const cut::CachedCut c = cut::cachedCut(m.staticMesh, pd::cutLights(m), {.directory = dir, .name = "g"});
  const rp::StaticGeometry g = pd::makeStaticGeometry(m, c.triangles);
  ASSERT_EQ(g.mesh.triangleCount(), c.triangles.triangleCount());
  ASSERT_EQ(g.maskStart.size(), 5u);
  EXPECT_EQ(g.maskStart.front(), 0u);
  EXPECT_EQ(g.maskStart.back(), c.triangles.triangleCount());
  EXPECT_EQ(g.polygons, c.triangles.polygonCount());
  // Per mask: the same number of triangles and the same area as the cut.
  double cutArea[4] = {}, area[4] = {};
  std::size_t cutCount[4] = {};
  const auto triArea = [](vec3 a, vec3 b, vec3 c) { return 0.5 * double(glm::length(glm::cross(b - a, c - a))); };
  for (std::size_t t = 0; t < c.triangles.triangleCount(); ++t) {
    const auto* i = &c.triangles.indices[3 * t];
    cutArea[c.triangles.mask(t)] += triArea(c.triangles.positions[i[0]], c.triangles.positions[i[1]], c.triangles.positions[i[2]]);
    ++cutCount[c.triangles.mask(t)];
  }
  for (std::size_t mask = 0; mask < 4; ++mask) {
    EXPECT_EQ(g.maskStart[mask + 1] - g.maskStart[mask], cutCount[mask]);
    for (std::size_t t = g.maskStart[mask]; t < g.maskStart[mask + 1]; ++t) {
      const auto* i = &g.mesh.indices[3 * t];
      area[mask] += triArea(g.mesh.positions[i[0]], g.mesh.positions[i[1]], g.mesh.positions[i[2]]);
    }
    EXPECT_NEAR(area[mask], cutArea[mask], 1e-6 * cutArea[mask] + 1e-9) << "mask " << mask;
  }
  for (const vec3& n : g.mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
  // Vertices are shared as the input's are: no two are the same point of the same colour
  // with the same normal (to rounding), and there are about as many as the cut has points
  // (not one per triangle corner).
  std::vector<std::uint32_t> order(g.mesh.positions.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto key = [&](std::uint32_t v) {
    const vec3 p = g.mesh.positions[v];
    const vec4 col = g.colors[v];
    return std::make_tuple(p.x, p.y, p.z, col.r, col.g, col.b);
  };
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  std::size_t twins = 0;
  for (std::size_t i = 0, run = 0; i < order.size(); ++i) {
    if (i > 0 && key(order[i]) != key(order[i - 1])) run = i;
    for (std::size_t j = run; j < i; ++j)
      twins += glm::length(g.mesh.normals[order[i]] - g.mesh.normals[order[j]]) < 1e-5f;
  }
  EXPECT_EQ(twins, 0u);
  EXPECT_LT(g.mesh.positions.size(), 2 * c.triangles.positions.size());
  std::printf("[ geometry ] %zu vertices for %zu cut points, %zu triangles\n", g.mesh.positions.size(),
              c.triangles.positions.size(), g.mesh.triangleCount());
  // Wireframe: each side once; no diagonal (an edge inside a polygon) among them.
  ASSERT_FALSE(g.edges.indices.empty());
  EXPECT_EQ(g.edges.indices.size() % 6, 0u);
  EXPECT_LT(g.edges.indices.size() / 2, 3 * c.triangles.triangleCount());
}

TEST(Stage, TheDefaultFrameIsInTheSeedsRange) {
  // Seed 001: "about 400,000 polygons per frame on average, 550,000 peak". The default
  // stage's cut is shared with the gallery and the golden tests (glint's cache directory:
  // the build's cache/ under ctest).
  const auto stage = pd::loadStage({.progress = false});
  for (const double t : {0.0, 4.0, 6.35, 12.5}) {
    const std::size_t n = stage->trianglesPerFrame(glint::pipedream::poseAt(stage->machine, stage->score, t));
    EXPECT_GE(n, 400'000u) << t;
    EXPECT_LE(n, 550'000u) << t;
  }
  std::printf("[ stage    ] %s\n", stage->describe().c_str());
}
