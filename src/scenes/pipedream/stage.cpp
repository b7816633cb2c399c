// The pipedream stage (scenes/pipedream.h): machine, score, cached cut → renderer geometry.
#include "glint/scenes/pipedream.h"

#include "glint/core/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace glint::scenes::pipedream {

namespace rp = render::pipedream;
namespace pd = glint::pipedream;
using glm::dvec3;

std::vector<cut::Light> cutLights(const InstrumentMachine& machine) {
  std::vector<cut::Light> lights;
  for (const MachineLight& l : machine.lights) lights.push_back({.position = l.position, .name = l.name});
  return lights;
}

namespace {

/// Normals closer than this are one (float rounding of the same interpolation).
constexpr float kSameNormal = 1e-5f;

/// Barycentric weights of `p` (on or near the plane of a, b, c), clamped into the
/// triangle; a third each for a degenerate triangle.
dvec3 barycentric(dvec3 p, dvec3 a, dvec3 b, dvec3 c) {
  const dvec3 n = glm::cross(b - a, c - a);
  const double nn = glm::dot(n, n);
  if (!(nn > 0.0)) return dvec3(1.0 / 3.0);
  dvec3 w(glm::dot(glm::cross(c - b, p - b), n), glm::dot(glm::cross(a - c, p - c), n), glm::dot(glm::cross(b - a, p - a), n));
  w = glm::max(w / nn, dvec3(0.0));
  const double sum = w.x + w.y + w.z;
  return sum > 0.0 ? w / sum : dvec3(1.0 / 3.0);
}

/// The cut's merge groups: pieces of coplanar neighbours merge only where the stage's
/// colours and normals are one across both (makeStaticGeometry interpolates them over each
/// piece's source triangle): flat triangles (three equal corner normals) by material; a
/// smooth triangle (a tube's quad) in a group of its own.
std::vector<std::uint32_t> mergeGroups(const InstrumentMachine& machine) {
  const Mesh& m = machine.staticMesh;
  std::vector<std::uint32_t> groups(m.triangleCount());
  for (std::size_t t = 0; t < groups.size(); ++t) {
    const vec3 a = m.normals[m.indices[3 * t]], b = m.normals[m.indices[3 * t + 1]], c = m.normals[m.indices[3 * t + 2]];
    const bool flat = a == b && b == c;
    groups[t] = flat ? std::uint32_t(machine.triangleMaterial[t]) : std::uint32_t(0x80000000u + t);
  }
  return groups;
}

}  // namespace

Mesh cutEdges(const cut::CutTriangles& cut) {
  // Every triangle edge with its polygon; a diagonal appears twice within its polygon.
  struct Edge {
    std::uint32_t a, b, polygon;
    auto key() const { return std::tie(a, b, polygon); }
  };
  std::vector<Edge> edges;
  edges.reserve(cut.indices.size());
  for (std::size_t t = 0; t < cut.triangleCount(); ++t)
    for (int i = 0; i < 3; ++i) {
      std::uint32_t a = cut.indices[3 * t + std::size_t(i)], b = cut.indices[3 * t + std::size_t((i + 1) % 3)];
      if (a > b) std::swap(a, b);
      edges.push_back({a, b, cut.trianglePolygon[t]});
    }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.key() < y.key(); });
  Mesh out;
  out.positions = cut.positions;
  std::uint32_t lastA = ~0u, lastB = ~0u;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key() == edges[i].key()) ++j;
    const bool side = j - i == 1;  // once in its polygon: a side, not a diagonal
    if (side && (edges[i].a != lastA || edges[i].b != lastB)) {
      out.indices.insert(out.indices.end(), {edges[i].a, edges[i].b});
      lastA = edges[i].a;
      lastB = edges[i].b;
    }
    i = j;
  }
  // Sorted by (a, b) first, so a side shared by two polygons is met twice in a row (the
  // polygon differs) and written once.
  if (out.indices.empty()) return out;
  while (out.indices.size() % 6 != 0) out.indices.insert(out.indices.end(), {out.indices[0], out.indices[1]});
  return out;
}

namespace {

/// One possible vertex of the cut mesh: a cut vertex as seen from one input triangle (its
/// interpolated normal, the triangle's material).
struct Candidate {
  std::uint32_t vertex, material;
  vec3 normal;
};

/// The cut's triangles grouped by light mask (a counting sort, stable: the cut's order within
/// a group): their order, and each group's start in `g.maskStart`.
std::vector<std::uint32_t> orderByMask(const cut::CutTriangles& cut, int lights, rp::StaticGeometry& g) {
  const std::size_t masks = std::size_t(1) << lights;
  const std::size_t n = cut.triangleCount();
  g.maskStart.assign(masks + 1, 0);
  for (std::size_t t = 0; t < n; ++t) {
    const cut::LightMask m = cut.mask(t);
    if (m >= masks) fail(ErrorKind::Internal, "cut triangle {} has light mask {} for {} lights", t, m, lights);
    ++g.maskStart[m + 1];
  }
  std::partial_sum(g.maskStart.begin(), g.maskStart.end(), g.maskStart.begin());
  std::vector<std::uint32_t> order(n);
  std::vector<std::uint32_t> next(g.maskStart.begin(), g.maskStart.end() - 1);
  for (std::size_t t = 0; t < n; ++t) order[next[cut.mask(t)]++] = std::uint32_t(t);
  return order;
}

/// Each corner's normal and albedo come from its source triangle: one candidate vertex per
/// (cut vertex, input triangle), found by sorting the corners by that pair. `cornerCandidate`
/// gets each corner's (corners in `order`).
std::vector<Candidate> cornerCandidates(const InstrumentMachine& machine, const cut::CutTriangles& cut,
                                        const std::vector<std::uint32_t>& order,
                                        std::vector<std::uint32_t>& cornerCandidate) {
  const Mesh& input = machine.staticMesh;
  const std::size_t n = order.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> corners(3 * n);  // (key, corner slot in output order)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t t = order[i];
    const std::uint64_t source = cut.source(t);
    for (int c = 0; c < 3; ++c)
      corners[3 * i + std::size_t(c)] = {(source << 32) | cut.indices[3 * std::size_t(t) + std::size_t(c)],
                                         std::uint32_t(3 * i + std::size_t(c))};
  }
  std::sort(corners.begin(), corners.end());
  std::vector<Candidate> candidates;
  cornerCandidate.assign(3 * n, 0);
  for (std::size_t i = 0; i < corners.size();) {
    const std::uint64_t key = corners[i].first;
    const std::uint32_t source = std::uint32_t(key >> 32), vertex = std::uint32_t(key & 0xFFFFFFFFu);
    const vec3 p = cut.positions[vertex];
    const std::uint32_t* s = &input.indices[3 * std::size_t(source)];
    const dvec3 w = barycentric(dvec3(p), dvec3(input.positions[s[0]]), dvec3(input.positions[s[1]]), dvec3(input.positions[s[2]]));
    const dvec3 normal = w.x * dvec3(input.normals[s[0]]) + w.y * dvec3(input.normals[s[1]]) + w.z * dvec3(input.normals[s[2]]);
    const double len = glm::length(normal);
    candidates.push_back({vertex, std::uint32_t(machine.triangleMaterial[source]),
                          len > 0.0 ? vec3(normal / len) : input.normals[s[0]]});
    for (; i < corners.size() && corners[i].first == key; ++i)
      cornerCandidate[corners[i].second] = std::uint32_t(candidates.size() - 1);
  }
  return candidates;
}

/// Candidates at one cut vertex with one material and (to rounding) one normal are one
/// vertex: a smooth surface's triangles meet with equal normals, so the cut mesh keeps the
/// input's sharing and the vertex stage shades each point once, not once per triangle.
/// Each candidate's canonical one (the first earlier one with its normal).
std::vector<std::uint32_t> canonicalCandidates(const std::vector<Candidate>& candidates) {
  std::vector<std::uint32_t> byKey(candidates.size());
  std::iota(byKey.begin(), byKey.end(), 0u);
  const auto keyOf = [&](std::uint32_t c) { return std::make_pair(candidates[c].vertex, candidates[c].material); };
  std::sort(byKey.begin(), byKey.end(), [&](std::uint32_t a, std::uint32_t b) {
    return keyOf(a) != keyOf(b) ? keyOf(a) < keyOf(b) : a < b;
  });
  std::vector<std::uint32_t> canonical(candidates.size());
  for (std::size_t i = 0, run = 0; i < byKey.size(); ++i) {
    if (i > 0 && keyOf(byKey[i]) != keyOf(byKey[i - 1])) run = i;
    const std::uint32_t c = byKey[i];
    canonical[c] = c;
    for (std::size_t j = run; j < i; ++j)  // the first earlier one with this normal (a handful at most)
      if (canonical[byKey[j]] == byKey[j] && glm::length(candidates[byKey[j]].normal - candidates[c].normal) < kSameNormal) {
        canonical[c] = byKey[j];
        break;
      }
  }
  return canonical;
}

}  // namespace

rp::StaticGeometry makeStaticGeometry(const InstrumentMachine& machine, const cut::CutTriangles& cut, bool edges) {
  const int lights = int(machine.lights.size());
  rp::StaticGeometry g;
  g.lights = lights;
  g.polygons = cut.polygonCount();
  const std::vector<std::uint32_t> order = orderByMask(cut, lights, g);
  const std::size_t n = order.size();
  std::vector<std::uint32_t> cornerCandidate;
  const std::vector<Candidate> candidates = cornerCandidates(machine, cut, order, cornerCandidate);
  const std::vector<std::uint32_t> canonical = canonicalCandidates(candidates);
  // Vertices numbered by first use in draw order: what a vertex cache and fetch like best.
  std::vector<std::uint32_t> id(candidates.size(), ~0u);
  g.mesh.indices.resize(3 * n);
  for (std::size_t k = 0; k < 3 * n; ++k) {
    const std::uint32_t c = canonical[cornerCandidate[k]];
    if (id[c] == ~0u) {
      id[c] = std::uint32_t(g.mesh.positions.size());
      g.mesh.positions.push_back(cut.positions[candidates[c].vertex]);
      g.mesh.normals.push_back(candidates[c].normal);
      g.colors.push_back(vec4(machineMaterialColor(MachineMaterial(candidates[c].material)), 1.0f));
    }
    g.mesh.indices[k] = id[c];
  }
  if (edges) g.edges = cutEdges(cut);
  return g;
}

std::size_t Stage::trianglesPerFrame(const pd::MachinePose& pose) const {
  return geometry.mesh.triangleCount() + pose.skins.size() * machine.skin.triangleCount() +
         pose.cymbals.size() * machine.cymbal.triangleCount() + pose.mallets.size() * machine.mallet.triangleCount() +
         pose.balls.size() * pd::buildBlurBall(32, 16).triangleCount();
}

std::string Stage::describe() const {
  const std::size_t dark = geometry.maskStart[1];
  return fmt::format("detail {}: {} input triangles cut into {} polygons, {} triangles ({} reached by no light: the "
                     "cheap shader); cut {} {} in {:.2f} s",
                     detail, machine.staticMesh.triangleCount(), geometry.polygons, geometry.mesh.triangleCount(), dark,
                     cutBuilt ? "built into" : "loaded from", cutFile.string(), cutSeconds);
}

std::shared_ptr<const Stage> loadStage(const StageOptions& options) {
  static std::mutex mutex;
  static std::map<std::pair<int, std::string>, std::shared_ptr<const Stage>> stages;
  const std::lock_guard lock(mutex);
  const int detail = std::clamp(options.detail, 1, 16);
  const auto key = std::make_pair(detail, options.cacheDirectory.string());
  if (auto it = stages.find(key); it != stages.end()) return it->second;

  const auto start = std::chrono::steady_clock::now();
  auto stage = std::make_shared<Stage>();
  stage->detail = detail;
  stage->machine = makeInstrumentMachine({.detail = detail});
  stage->score = pd::makeScore(stage->machine);
  const cut::CachedCut cut =
      cut::cachedCut(stage->machine.staticMesh, cutLights(stage->machine),
                     {.directory = options.cacheDirectory, .name = fmt::format("pipedream-detail{}", detail),
                      .progress = options.progress, .mergeGroups = mergeGroups(stage->machine)});
  stage->cutFile = cut.file;
  stage->cutBuilt = cut.built;
  stage->cutSeconds = cut.seconds;
  stage->geometry = makeStaticGeometry(stage->machine, cut.triangles);
  stage->buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stages[key] = stage;
  return stage;
}

namespace {
// Aimed as WWDC 2003 session 212's demo was. The room has no front wall and no ceiling: 'stage' and
// 'drums' stand in front of its open front (the floor's edge and the clear colour show
// below and above the picture), the others inside it.
const NamedCamera kCameras[] = {
    {"stage", "the whole machine from the front, a little above", {0.0f, 7.2f, 16.5f}, {0.0f, 2.0f, -0.5f}, 52.0f},
    {"drums", "over the drum machine on the left, looking down", {-9.0f, 5.6f, 8.2f}, {-5.2f, 1.0f, 2.4f}, 48.0f},
    {"wall", "the back wall: the pipes' baked shadows and the balls' crossing them", {1.0f, 6.8f, -0.5f}, {-1.0f, 4.6f, -6.8f}, 55.0f},
    {"side", "across the machine from the right, where the volumes overlap most", {10.0f, 4.8f, 6.5f}, {-2.0f, 1.6f, -1.0f}, 58.0f},
    {"balls", "a close look at balls in flight", {3.0f, 6.2f, 2.5f}, {3.6f, 3.2f, -2.6f}, 48.0f},
};
}  // namespace

std::span<const NamedCamera> namedCameras() { return kCameras; }

glint::Camera namedCamera(int index, float aspect) {
  const NamedCamera& c = kCameras[std::size_t(std::clamp(index, 0, int(std::size(kCameras)) - 1))];
  return glint::Camera::lookAt(c.eye, c.target, {0.0f, 1.0f, 0.0f}, c.fovY, aspect, 0.3f, 100.0f);
}

}  // namespace glint::scenes::pipedream
