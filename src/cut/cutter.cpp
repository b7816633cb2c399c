// The shadow cutter's job: prepare the scene, cut every receiver in parallel, then make
// the pieces one mesh (shared edges consistent, vertices rounded, slivers dropped).
#include "glint/cut/cutter.h"

#include "glint/core/error.h"
#include "glint/core/hash.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"
#include "glint/core/text.h"

#include "pieces.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numeric>
#include <optional>
#include <span>

namespace glint::cut {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// Receivers per task: small enough to balance two cores, big enough that the blocks'
/// bookkeeping is noise. Fixed, so blocks (and shard files) never depend on threads.
constexpr std::size_t kBlockSize = 64;

/// Morton code of a point in the unit cube (10 bits per axis).
std::uint32_t morton(const dvec3& unit) {
  const auto spread = [](std::uint32_t v) {
    v = (v | (v << 16)) & 0x030000FF;
    v = (v | (v << 8)) & 0x0300F00F;
    v = (v | (v << 4)) & 0x030C30C3;
    v = (v | (v << 2)) & 0x09249249;
    return v;
  };
  const auto q = [](double x) { return std::uint32_t(std::clamp(x, 0.0, 1.0) * 1023.0); };
  return spread(q(unit.x)) | (spread(q(unit.y)) << 1) | (spread(q(unit.z)) << 2);
}

/// Solid angle of triangle (a, b, c) seen from the origin (van Oosterom–Strackee).
double solidAngle(const dvec3& a, const dvec3& b, const dvec3& c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double det = glm::dot(a, glm::cross(b, c));
  const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(det, den);
}

std::string lightName(const Light& light, std::size_t i) {
  return light.name.empty() ? fmt::format("light{}", i) : light.name;
}

}  // namespace

// ------------------------------------------------------------------ PieceBlock

PieceBlock::PieceBlock() {
  vertexStart.push_back(0);
  polygonFirst.push_back(0);
  polygonStart.push_back(0);
}

void PieceBlock::append(std::uint32_t triangle, const ReceiverPieces& p) {
  receiver.push_back(triangle);
  vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
  positions.insert(positions.end(), p.positions.begin(), p.positions.end());
  vertexStart.push_back(std::uint32_t(vertices.size()));
  const std::uint32_t cornerBase = std::uint32_t(corners.size());
  for (std::size_t i = 1; i < p.polygonStart.size(); ++i) polygonStart.push_back(cornerBase + p.polygonStart[i]);
  corners.insert(corners.end(), p.corners.begin(), p.corners.end());
  flags.insert(flags.end(), p.cornerFlags.begin(), p.cornerFlags.end());
  masks.insert(masks.end(), p.masks.begin(), p.masks.end());
  polygonFirst.push_back(std::uint32_t(masks.size()));
}

// ------------------------------------------------------------------ prepare

std::uint64_t inputHash(const Mesh& mesh, const std::vector<Light>& lights) {
  Fnv1a h;
  h.add(mesh.positions).add(mesh.indices);
  for (const Light& l : lights) h.add(l.position);
  return h.value();
}

Prepared prepare(const Mesh& mesh, const std::vector<Light>& lights, bool bvh) {
  if (lights.empty()) fail(ErrorKind::Usage, "cut needs at least one light (--light x,y,z)");
  if (lights.size() > std::size_t(kMaxLights))
    fail(ErrorKind::Usage, "cut handles at most {} lights, got {}", kMaxLights, lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const vec3& p = lights[i].position;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(ErrorKind::Usage, "light '{}' has a non-finite position", lightName(lights[i], i));
  }
  Prepared out;
  out.edges = EdgeMap::build(mesh);  // validates: Error(Input) for empty, NaN, bad indices
  out.hash = inputHash(mesh, lights);

  std::vector<dvec3> points;
  points.reserve(out.edges.positions().size() + lights.size());
  for (const vec3& p : out.edges.positions()) points.emplace_back(p);
  const std::uint32_t lightBase = std::uint32_t(points.size());
  for (const Light& l : lights) points.emplace_back(l.position);
  double radius = 1.0;
  for (const dvec3& p : points) radius = std::max(radius, glm::length(p));

  out.scene = std::make_unique<SceneData>(std::move(points));
  SceneData& s = *out.scene;
  s.lightBase = lightBase;
  s.lightCount = int(lights.size());
  s.radius = radius;
  const std::size_t n = out.edges.faceCount();
  s.triangles.resize(n);
  s.usable.assign(n, 0);
  out.state.assign(n, Prepared::kUsable);
  std::vector<dvec3> lo(n), hi(n);
  std::uint64_t degenerate = 0, collapsed = 0;
  for (std::uint32_t f = 0; f < n; ++f) {
    const auto c = out.edges.corners(f);
    s.triangles[f] = c;
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      out.state[f] = Prepared::kCollapsed;
      ++collapsed;
      continue;
    }
    if (s.geometry.degenerate(exact::PlaneDef{{c[0], c[1], c[2]}})) {
      out.state[f] = Prepared::kDegenerate;
      ++degenerate;
      continue;
    }
    s.usable[f] = 1;
    const dvec3 &a = s.geometry.point(c[0]), &b = s.geometry.point(c[1]), &d = s.geometry.point(c[2]);
    lo[f] = glm::min(a, glm::min(b, d));
    hi[f] = glm::max(a, glm::max(b, d));
  }
  if (degenerate > 0)
    out.warnings.push_back(fmt::format("{} degenerate (zero-area) triangle(s): kept unlit, they cast no shadow", degenerate));
  if (collapsed > 0)
    out.warnings.push_back(fmt::format("{} triangle(s) with two corners at one position dropped", collapsed));
  // Connected surfaces (triangles joined by edges), numbered in triangle order.
  {
    std::vector<std::uint32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0u);
    const auto root = [&](std::uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (const Edge& edge : out.edges.edges()) {
      const auto faces = out.edges.faces(edge);
      for (std::size_t i = 1; i < faces.size(); ++i) {
        const std::uint32_t a = root(faces[0].face), b = root(faces[i].face);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
    }
    std::vector<std::uint32_t> number(n, 0xFFFFFFFFu);
    s.component.resize(n);
    std::uint32_t count = 0;
    for (std::uint32_t f = 0; f < n; ++f) {
      const std::uint32_t r = root(f);
      if (number[r] == 0xFFFFFFFFu) number[r] = count++;
      s.component[f] = number[r];
    }
    s.convexOutside.assign(count, 0);
  }
  if (!bvh) return out;
  s.bvh = TriangleBvh(lo, hi, s.usable);

  // Closed convex surfaces: every face with area, every edge shared by two faces running
  // it in opposite directions and bending outwards (or flat), and the topology of a sphere
  // (V − E + F = 2), which with local convexity makes the surface the boundary of a convex
  // solid. Decided exactly, like everything the cut depends on.
  {
    const std::size_t count = s.convexOutside.size();
    std::vector<std::uint8_t> convex(count, 1);
    std::vector<std::int64_t> euler(count, 0);
    exact::PredicateStats ignored;
    for (std::uint32_t f = 0; f < n; ++f) {
      if (!s.usable[f]) convex[s.component[f]] = 0;
      euler[s.component[f]] += 1;
    }
    std::vector<std::uint32_t> pointComponent(out.edges.positions().size(), 0xFFFFFFFFu);
    for (std::uint32_t f = 0; f < n; ++f)
      for (std::uint32_t c : s.triangles[f])
        if (pointComponent[c] == 0xFFFFFFFFu) {
          pointComponent[c] = s.component[f];
          euler[s.component[f]] += 1;
        } else if (pointComponent[c] != s.component[f]) {
          convex[s.component[f]] = convex[pointComponent[c]] = 0;  // surfaces meeting at a point
        }
    for (const Edge& edge : out.edges.edges()) {
      const auto faces = out.edges.faces(edge);
      const std::uint32_t c = s.component[faces[0].face];
      euler[c] -= 1;
      if (!convex[c]) continue;
      if (out.edges.kind(edge) != EdgeKind::Manifold) {
        convex[c] = 0;
        continue;
      }
      // The corner of the second face off the edge, against the first face's plane.
      const auto& t1 = s.triangles[faces[0].face];
      const auto& t2 = s.triangles[faces[1].face];
      std::uint32_t apex = t2[0];
      for (std::uint32_t v : t2)
        if (v != edge.a && v != edge.b) apex = v;
      if (s.geometry.side(apex, exact::PlaneDef{{t1[0], t1[1], t1[2]}}, ignored) > 0) convex[c] = 0;
    }
    for (std::size_t c = 0; c < count; ++c)
      if (euler[c] != 2) convex[c] = 0;
    // A light is outside a convex solid when some face of it faces the light.
    for (std::uint32_t f = 0; f < n; ++f) {
      const std::uint32_t c = s.component[f];
      if (!convex[c]) continue;
      const auto& t = s.triangles[f];
      const exact::PlaneDef plane{{t[0], t[1], t[2]}};
      for (int l = 0; l < s.lightCount; ++l)
        if (!(s.convexOutside[c] & (LightMask(1) << l)) && s.geometry.side(lightBase + std::uint32_t(l), plane, ignored) > 0)
          s.convexOutside[c] |= LightMask(1) << l;
    }
  }

  // Lights in odd places: both still give a well-defined result, so they are warnings.
  std::vector<std::uint32_t> near;
  for (std::size_t l = 0; l < lights.size(); ++l) {
    const dvec3 L = s.geometry.point(lightBase + std::uint32_t(l));
    const std::string name = lightName(lights[l], l);
    // On (or within a hair of) a surface: that surface grazes the light and stays dark.
    const double eps = 1e-6 * radius;
    bool onSurface = false;
    near.clear();
    s.bvh.query(L - eps, L + eps, {}, near);
    for (std::uint32_t f : near) {
      const auto& c = s.triangles[f];
      const dvec3 a = s.geometry.point(c[0]), b = s.geometry.point(c[1]), d = s.geometry.point(c[2]);
      const dvec3 nrm = glm::normalize(glm::cross(b - a, d - a));
      const double dist = glm::dot(L - a, nrm);
      const dvec3 q = L - dist * nrm;
      const bool inside = glm::dot(glm::cross(b - a, q - a), nrm) >= -eps && glm::dot(glm::cross(d - b, q - b), nrm) >= -eps &&
                          glm::dot(glm::cross(a - d, q - d), nrm) >= -eps;
      if (std::abs(dist) <= eps && inside) {
        out.warnings.push_back(fmt::format("light '{}' lies on a surface (triangle {}): it lights nothing there", name, f));
        onSurface = true;
        break;
      }
    }
    // Inside a closed mesh whose normals point out: the generalized winding number is 1.
    // (Not decided for a light on a surface, where it is half-way by definition.)
    if (onSurface) continue;
    double winding = 0.0;
    for (std::uint32_t f = 0; f < n; ++f) {
      if (!s.usable[f]) continue;
      const auto& c = s.triangles[f];
      winding += solidAngle(s.geometry.point(c[0]) - L, s.geometry.point(c[1]) - L, s.geometry.point(c[2]) - L);
    }
    winding /= 4.0 * 3.14159265358979323846;
    if (winding > 0.5)
      out.warnings.push_back(fmt::format("light '{}' is inside a closed mesh (winding number {:.2f}): only the inside "
                                         "of it can be lit", name, winding));
  }
  return out;
}

// ------------------------------------------------------------------ cutShard

namespace {

/// The receivers of shard i of n: all triangles with area or none, sorted along a
/// Morton curve of their centres, cut into n runs.
std::vector<std::uint32_t> shardReceivers(const Prepared& p, int index, int count) {
  const SceneData& s = *p.scene;
  dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const dvec3& q : s.geometry.points()) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  const dvec3 extent = glm::max(hi - lo, dvec3(1e-300));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed;
  for (std::uint32_t f = 0; f < s.triangles.size(); ++f) {
    if (p.state[f] == Prepared::kCollapsed) continue;
    const auto& c = s.triangles[f];
    const dvec3 centre = (s.geometry.point(c[0]) + s.geometry.point(c[1]) + s.geometry.point(c[2])) / 3.0;
    keyed.emplace_back(morton((centre - lo) / extent), f);
  }
  std::sort(keyed.begin(), keyed.end());
  const std::size_t per = (keyed.size() + std::size_t(count) - 1) / std::size_t(count);
  const std::size_t begin = std::min(keyed.size(), per * std::size_t(index));
  const std::size_t end = std::min(keyed.size(), begin + per);
  std::vector<std::uint32_t> out;
  for (std::size_t i = begin; i < end; ++i) out.push_back(keyed[i].second);
  return out;
}

ReceiverPieces wholeTriangle(LightMask mask) {
  ReceiverPieces p;
  for (int k = 0; k < 3; ++k) {
    exact::VertexDef d;
    p.vertices.push_back(d);  // filled by the caller
    p.corners.push_back(std::uint32_t(k));
    p.cornerFlags.push_back(std::uint8_t(k));
  }
  p.polygonStart = {0, 3};
  p.masks = {mask};
  return p;
}

}  // namespace

Shard cutShard(const Mesh& mesh, const CutOptions& options) {
  if (options.shardCount < 1 || options.shardIndex < 0 || options.shardIndex >= options.shardCount)
    fail(ErrorKind::Usage, "shard {} of {} does not exist (shards are 1..n)", options.shardIndex + 1, options.shardCount);
  const auto start = Clock::now();
  Prepared prep = prepare(mesh, options.lights, true);
  for (const std::string& w : prep.warnings) log::warn("cut: {}", w);
  const SceneData& scene = *prep.scene;
  Shard shard;
  shard.warnings = prep.warnings;
  shard.inputHash = prep.hash;
  shard.shardIndex = options.shardIndex;
  shard.shardCount = options.shardCount;
  shard.lights = options.lights;
  shard.pieces = std::make_shared<Shard::Impl>();
  CutStats& stats = shard.stats;
  stats.inputTriangles = scene.triangles.size();
  for (std::uint8_t st : prep.state) {
    stats.degenerateTriangles += st == Prepared::kDegenerate;
    stats.collapsedTriangles += st == Prepared::kCollapsed;
  }
  const std::vector<std::uint32_t> receivers = shardReceivers(prep, options.shardIndex, options.shardCount);
  stats.receivers = receivers.size();
  stats.prepareSeconds = since(start);

  const auto cutStart = Clock::now();
  const std::size_t blocks = (receivers.size() + kBlockSize - 1) / kBlockSize;
  auto& out = shard.pieces->blocks;
  out.resize(blocks);
  std::vector<ReceiverStats> blockStats(blocks);
  tbb::enumerable_thread_specific<ReceiverCutter> cutters(std::cref(scene), options.cancel);
  tbb::enumerable_thread_specific<ReceiverPieces> scratch;
  std::optional<Progress> progress;
  if (options.progress) progress.emplace("cut", receivers.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    ReceiverCutter& cutter = cutters.local();
    ReceiverPieces& pieces = scratch.local();
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      if (options.cancel && options.cancel->load()) return;
      const std::size_t first = b * kBlockSize, last = std::min(receivers.size(), first + kBlockSize);
      for (std::size_t i = first; i < last; ++i) {
        const std::uint32_t f = receivers[i];
        if (prep.state[f] == Prepared::kUsable) {
          cutter.cut(f, pieces, blockStats[b]);
        } else {
          pieces = wholeTriangle(0);
          for (int k = 0; k < 3; ++k) {
            pieces.vertices[std::size_t(k)].kind = exact::VertexKind::Point;
            pieces.vertices[std::size_t(k)].a = scene.triangles[f][std::size_t(k)];
          }
          pieces.positions = {scene.geometry.point(scene.triangles[f][0]), scene.geometry.point(scene.triangles[f][1]),
                              scene.geometry.point(scene.triangles[f][2])};
        }
        out[b].append(f, pieces);
      }
      if (progress) progress->advance(last - first);
    }
  }, tbb::simple_partitioner());
  if (progress) progress->finish();
  if (options.cancel && options.cancel->load()) fail(ErrorKind::Interrupted, "cut interrupted");
  ReceiverStats total;
  for (const ReceiverStats& s : blockStats) total.add(s);
  stats.candidates = total.candidates;
  stats.occluders = total.occluders;
  stats.clippedPairs = total.clippedPairs;
  stats.cuts = total.cuts;
  stats.facesBeforeMerge = total.facesBeforeMerge;
  stats.symbolicPredicates = total.predicates.symbolic;
  stats.filteredPredicates = total.predicates.filtered;
  stats.exactPredicates = total.predicates.exact;
  stats.cutSeconds = since(cutStart);
  stats.lights.resize(options.lights.size());
  for (std::size_t l = 0; l < options.lights.size(); ++l) {
    stats.lights[l].name = lightName(options.lights[l], l);
    stats.lights[l].position = options.lights[l].position;
  }
  // Grazing counts per light need the per-light split; ReceiverStats sums them all, so
  // they are recounted here (cheap: one exact sign per triangle and light).
  exact::PredicateStats ignored;
  for (std::size_t l = 0; l < options.lights.size(); ++l) {
    std::uint64_t grazing = 0;
    for (std::uint32_t f : receivers) {
      if (prep.state[f] != Prepared::kUsable) continue;
      const auto& c = scene.triangles[f];
      grazing += scene.geometry.side(scene.lightBase + std::uint32_t(l), exact::PlaneDef{{c[0], c[1], c[2]}}, ignored) == 0;
    }
    stats.lights[l].grazingTriangles = grazing;
  }
  return shard;
}

// ------------------------------------------------------------------ merge

namespace {

struct EdgeEntry {
  std::uint32_t edge;       ///< EdgeMap edge
  std::uint32_t block, entry, local;  ///< where the vertex is
  std::uint32_t unionIndex = 0;  ///< position in the edge's sorted, deduplicated list
};

}  // namespace

CutResult mergeShards(const Mesh& mesh, std::vector<Shard> shards, const CutOptions& options) {
  (void)options;
  if (shards.empty()) fail(ErrorKind::Usage, "nothing to merge: no shards");
  const auto start = Clock::now();
  const std::vector<Light> lights = shards.front().lights;
  Prepared prep = prepare(mesh, lights, false);
  const SceneData& scene = *prep.scene;
  const exact::Geometry& g = scene.geometry;
  const int count = shards.front().shardCount;
  std::vector<char> seen(std::size_t(count), 0);
  for (const Shard& s : shards) {
    if (s.inputHash != prep.hash)
      fail(ErrorKind::Input, "shard {}/{} was cut from another scene or other lights", s.shardIndex + 1, s.shardCount);
    if (s.shardCount != count) fail(ErrorKind::Input, "shards of different splits: {} and {} parts", count, s.shardCount);
    if (seen[std::size_t(s.shardIndex)]) fail(ErrorKind::Input, "shard {}/{} given twice", s.shardIndex + 1, count);
    seen[std::size_t(s.shardIndex)] = 1;
  }
  for (int i = 0; i < count; ++i)
    if (!seen[std::size_t(i)]) fail(ErrorKind::Input, "shard {}/{} is missing", i + 1, count);

  CutResult result;
  CutStats& stats = result.stats;
  for (const Shard& s : shards)
    for (const std::string& w : s.warnings)
      if (std::find(result.warnings.begin(), result.warnings.end(), w) == result.warnings.end()) result.warnings.push_back(w);
  stats.inputTriangles = scene.triangles.size();
  stats.lights = shards.front().stats.lights;
  for (const Shard& s : shards) {
    stats.receivers += s.stats.receivers;
    stats.candidates += s.stats.candidates;
    stats.occluders += s.stats.occluders;
    stats.clippedPairs += s.stats.clippedPairs;
    stats.cuts += s.stats.cuts;
    stats.facesBeforeMerge += s.stats.facesBeforeMerge;
    stats.symbolicPredicates += s.stats.symbolicPredicates;
    stats.filteredPredicates += s.stats.filteredPredicates;
    stats.exactPredicates += s.stats.exactPredicates;
    stats.prepareSeconds += s.stats.prepareSeconds;
    stats.cutSeconds += s.stats.cutSeconds;
    for (std::size_t l = 0; l < stats.lights.size() && l < s.stats.lights.size(); ++l)
      if (&s != &shards.front()) stats.lights[l].grazingTriangles += s.stats.lights[l].grazingTriangles;
  }
  for (std::uint8_t st : prep.state) {
    stats.degenerateTriangles += st == Prepared::kDegenerate;
    stats.collapsedTriangles += st == Prepared::kCollapsed;
  }

  // Every piece block of every shard, and where each triangle's pieces are.
  std::vector<const PieceBlock*> blocks;
  for (const Shard& s : shards)
    for (const PieceBlock& b : s.pieces->blocks) blocks.push_back(&b);
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> where(scene.triangles.size(), {kNone, kNone});
  for (std::uint32_t b = 0; b < blocks.size(); ++b)
    for (std::uint32_t e = 0; e < blocks[b]->entries(); ++e) {
      const std::uint32_t f = blocks[b]->receiver[e];
      if (f >= where.size() || where[f].first != kNone) fail(ErrorKind::Input, "shards overlap: triangle {} cut twice", f);
      where[f] = {b, e};
    }
  for (std::uint32_t f = 0; f < where.size(); ++f)
    if (where[f].first == kNone && prep.state[f] != Prepared::kCollapsed)
      fail(ErrorKind::Input, "shards do not cover triangle {}", f);

  // 1. Shared edges: every vertex any receiver has on an input edge, sorted along the edge
  //    exactly and deduplicated, so both sides of the edge get all of them.
  std::vector<EdgeEntry> entries;
  for (std::uint32_t f = 0; f < where.size(); ++f) {
    if (where[f].first == kNone) continue;
    const auto [b, e] = where[f];
    const PieceBlock& blk = *blocks[b];
    const auto faceEdges = prep.edges.faceEdges(f);
    for (std::uint32_t p = blk.polygonFirst[e]; p < blk.polygonFirst[e + 1]; ++p) {
      const std::uint32_t c0 = blk.polygonStart[p], c1 = blk.polygonStart[p + 1];
      for (std::uint32_t c = c0; c < c1; ++c) {
        const int k = blk.flags[c] & kEdgeMask;
        if (k == kInterior) continue;
        for (std::uint32_t corner : {c, c + 1 < c1 ? c + 1 : c0}) {
          const std::uint32_t local = blk.corners[corner];
          if (blk.vertices[blk.vertexStart[e] + local].kind != exact::VertexKind::LinePlane) continue;
          entries.push_back({faceEdges[std::size_t(k)], b, e, local});
        }
      }
    }
  }
  // By edge, then receiver triangle: the first entry of each point along an edge (its
  // position is the one kept) never depends on how receivers were grouped into blocks
  // or shards.
  std::sort(entries.begin(), entries.end(), [&](const EdgeEntry& x, const EdgeEntry& y) {
    const std::uint32_t tx = blocks[x.block]->receiver[x.entry], ty = blocks[y.block]->receiver[y.entry];
    return std::tie(x.edge, tx, x.local) < std::tie(y.edge, ty, y.local);
  });
  entries.erase(std::unique(entries.begin(), entries.end(),
                            [](const EdgeEntry& x, const EdgeEntry& y) {
                              return x.edge == y.edge && x.block == y.block && x.entry == y.entry && x.local == y.local;
                            }),
                entries.end());
  const auto defOf = [&](const EdgeEntry& x) -> const exact::VertexDef& {
    return blocks[x.block]->vertices[blocks[x.block]->vertexStart[x.entry] + x.local];
  };
  const auto posOf = [&](const EdgeEntry& x) -> const dvec3& {
    return blocks[x.block]->positions[blocks[x.block]->vertexStart[x.entry] + x.local];
  };
  // Group boundaries, then each edge's group sorted along it (in parallel: groups are independent).
  std::vector<std::size_t> groupStart;
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (i == 0 || entries[i].edge != entries[i - 1].edge) groupStart.push_back(i);
  groupStart.push_back(entries.size());
  std::vector<std::uint32_t> unionCount(groupStart.size() - 1, 0);
  tbb::enumerable_thread_specific<exact::PredicateStats> mergeStats;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groupStart.size() - 1), [&](const tbb::blocked_range<std::size_t>& r) {
    exact::PredicateStats& ps = mergeStats.local();
    std::vector<exact::PlaneRec> planes;
    std::vector<std::size_t> order;
    for (std::size_t gi = r.begin(); gi != r.end(); ++gi) {
      const std::size_t a = groupStart[gi], z = groupStart[gi + 1];
      const Edge& edge = prep.edges.edges()[entries[a].edge];
      planes.clear();
      order.clear();
      for (std::size_t i = a; i < z; ++i) {
        planes.push_back(g.plane(defOf(entries[i]).q));
        order.push_back(i - a);
      }
      const auto cmp = [&](std::size_t x, std::size_t y) {
        return g.compareAlongLine(edge.a, edge.b, planes[x], planes[y], ps);
      };
      std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return cmp(x, y) < 0; });
      std::uint32_t u = 0;
      for (std::size_t i = 0; i < order.size(); ++i) {
        if (i > 0 && cmp(order[i - 1], order[i]) != 0) ++u;
        entries[a + order[i]].unionIndex = u;
      }
      unionCount[gi] = order.empty() ? 0 : u + 1;
    }
  });
  for (const auto& ps : mergeStats) {
    stats.symbolicPredicates += ps.symbolic;
    stats.filteredPredicates += ps.filtered;
    stats.exactPredicates += ps.exact;
  }

  // Vertices are welded below only within one connected surface of the input, so
  // surfaces that merely touch stay apart, as they were.
  const std::vector<std::uint32_t>& component = scene.component;

  // 2. Vertex ids: welded points, then edge vertices edge by edge, then each receiver's
  //    interior vertices in triangle order.
  const std::uint32_t pointCount = std::uint32_t(prep.edges.positions().size());
  std::vector<std::uint32_t> groupBase(unionCount.size() + 1, pointCount);
  for (std::size_t gi = 0; gi < unionCount.size(); ++gi) groupBase[gi + 1] = groupBase[gi] + unionCount[gi];
  std::vector<dvec3> precise(groupBase.back());
  std::vector<std::uint32_t> vertexComponent(groupBase.back(), kNone);
  for (std::uint32_t i = 0; i < pointCount; ++i) precise[i] = g.point(i);
  for (std::uint32_t f = 0; f < scene.triangles.size(); ++f)
    for (std::uint32_t c : scene.triangles[f])
      if (vertexComponent[c] == kNone) vertexComponent[c] = component[f];
  std::vector<std::uint32_t> edgeGroup(prep.edges.edges().size(), kNone);
  for (std::size_t gi = 0; gi + 1 < groupStart.size(); ++gi) {
    edgeGroup[entries[groupStart[gi]].edge] = std::uint32_t(gi);
    const std::uint32_t c = component[prep.edges.faces(prep.edges.edges()[entries[groupStart[gi]].edge])[0].face];
    for (std::size_t i = groupStart[gi + 1]; i-- > groupStart[gi];) {  // the first entry's position wins
      precise[groupBase[gi] + entries[i].unionIndex] = posOf(entries[i]);
      vertexComponent[groupBase[gi] + entries[i].unionIndex] = c;
    }
  }
  // Per (block, entry): its edge entries sorted by local vertex, to look them up.
  std::vector<std::size_t> byReceiver(entries.size());
  std::iota(byReceiver.begin(), byReceiver.end(), 0);
  std::sort(byReceiver.begin(), byReceiver.end(), [&](std::size_t x, std::size_t y) {
    return std::tie(entries[x].block, entries[x].entry, entries[x].local) <
           std::tie(entries[y].block, entries[y].entry, entries[y].local);
  });

  // 3. Polygons, triangle by triangle, with the edge vertices inserted on boundary runs.
  CutMesh& out = result.mesh;
  out.polygonStart.push_back(0);
  std::vector<std::uint32_t> localId;
  std::vector<std::uint8_t> localStraight;
  for (std::uint32_t f = 0; f < where.size(); ++f) {
    if (where[f].first == kNone) continue;
    const auto [b, e] = where[f];
    const PieceBlock& blk = *blocks[b];
    const std::uint32_t v0 = blk.vertexStart[e], v1 = blk.vertexStart[e + 1];
    localId.assign(v1 - v0, kNone);
    // The receiver's edge entries.
    auto lo = std::lower_bound(byReceiver.begin(), byReceiver.end(), std::make_pair(b, e),
                               [&](std::size_t x, const std::pair<std::uint32_t, std::uint32_t>& key) {
                                 return std::tie(entries[x].block, entries[x].entry) < std::tie(key.first, key.second);
                               });
    // Edge vertex local → (group, union index): several edges can't share a LinePlane vertex.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edgeOf(v1 - v0, {kNone, kNone});
    for (auto it = lo; it != byReceiver.end() && entries[*it].block == b && entries[*it].entry == e; ++it) {
      const EdgeEntry& x = entries[*it];
      const std::uint32_t gi = edgeGroup[x.edge];
      edgeOf[x.local] = {gi, x.unionIndex};
      localId[x.local] = groupBase[gi] + x.unionIndex;
    }
    for (std::uint32_t v = 0; v < v1 - v0; ++v) {
      if (localId[v] != kNone) continue;
      const exact::VertexDef& d = blk.vertices[v0 + v];
      if (d.kind == exact::VertexKind::Point) {
        localId[v] = d.a;
      } else {
        localId[v] = std::uint32_t(precise.size());
        precise.push_back(blk.positions[v0 + v]);
        vertexComponent.push_back(component[f]);
      }
    }
    const auto faceEdges = prep.edges.faceEdges(f);
    for (std::uint32_t p = blk.polygonFirst[e]; p < blk.polygonFirst[e + 1]; ++p) {
      const std::uint32_t c0 = blk.polygonStart[p], c1 = blk.polygonStart[p + 1];
      for (std::uint32_t c = c0; c < c1; ++c) {
        const std::uint32_t local = blk.corners[c];
        out.corners.push_back(localId[local]);
        out.straight.push_back((blk.flags[c] & kStraight) ? 1 : 0);
        const int k = blk.flags[c] & kEdgeMask;
        if (k == kInterior) continue;
        const std::uint32_t edgeIndex = faceEdges[std::size_t(k)];
        const std::uint32_t gi = edgeGroup[edgeIndex];
        if (gi == kNone) continue;  // no vertex on this edge anywhere
        const Edge& edge = prep.edges.edges()[edgeIndex];
        const std::uint32_t next = blk.corners[c + 1 < c1 ? c + 1 : c0];
        // Positions along the edge (a → b): an end corner is −1 or the count.
        const auto along = [&](std::uint32_t l) -> std::int64_t {
          if (edgeOf[l].first != kNone) return edgeOf[l].second;
          const std::uint32_t id = blk.vertices[v0 + l].a;  // a corner of the triangle
          return id == edge.a ? -1 : std::int64_t(unionCount[gi]);
        };
        const std::int64_t from = along(local), to = along(next);
        if (from < to)
          for (std::int64_t i = from + 1; i < to; ++i) {
            out.corners.push_back(groupBase[gi] + std::uint32_t(i));
            out.straight.push_back(1);
          }
        else
          for (std::int64_t i = from - 1; i > to; --i) {
            out.corners.push_back(groupBase[gi] + std::uint32_t(i));
            out.straight.push_back(1);
          }
      }
      out.polygonStart.push_back(std::uint32_t(out.corners.size()));
      out.polygonSource.push_back(f);
      out.polygonMask.push_back(blk.masks[p]);
    }
  }

  // 4. Round to float; vertices of one surface that round to one position become one, and
  //    polygons left with fewer than three corners (slivers thinner than a float) are dropped.
  std::vector<vec3> rounded(precise.size());
  for (std::size_t i = 0; i < precise.size(); ++i)
    rounded[i] = i < pointCount ? prep.edges.positions()[i] : vec3(precise[i]);
  std::vector<std::uint32_t> byPosition(precise.size());
  std::iota(byPosition.begin(), byPosition.end(), 0u);
  const auto bits = [&](std::uint32_t i) {
    std::array<std::uint32_t, 4> k;
    std::memcpy(k.data(), &rounded[i], sizeof(vec3));
    k[3] = vertexComponent[i];
    return k;
  };
  std::sort(byPosition.begin(), byPosition.end(), [&](std::uint32_t x, std::uint32_t y) {
    const auto kx = bits(x), ky = bits(y);
    return kx < ky || (kx == ky && x < y);
  });
  std::vector<std::uint32_t> canonical(precise.size());
  for (std::size_t i = 0; i < byPosition.size(); ++i)
    canonical[byPosition[i]] = (i > 0 && bits(byPosition[i]) == bits(byPosition[i - 1])) ? canonical[byPosition[i - 1]]
                                                                                          : byPosition[i];
  CutMesh final;
  final.polygonStart.push_back(0);
  std::vector<std::uint32_t> finalId(precise.size(), kNone);
  std::vector<std::uint32_t> ring;
  std::vector<std::uint8_t> ringStraight;
  for (std::size_t p = 0; p < out.polygonMask.size(); ++p) {
    ring.clear();
    ringStraight.clear();
    for (std::uint32_t c = out.polygonStart[p]; c < out.polygonStart[p + 1]; ++c) {
      const std::uint32_t v = canonical[out.corners[c]];
      if (!ring.empty() && ring.back() == v) continue;
      ring.push_back(v);
      ringStraight.push_back(out.straight[c]);
    }
    while (ring.size() > 1 && ring.back() == ring.front()) {
      ring.pop_back();
      ringStraight.pop_back();
    }
    if (ring.size() < 3) {
      ++stats.droppedSlivers;
      continue;
    }
    for (std::size_t i = 0; i < ring.size(); ++i) {
      std::uint32_t& id = finalId[ring[i]];
      if (id == kNone) {
        id = std::uint32_t(final.positions.size());
        final.positions.push_back(rounded[ring[i]]);
        final.precisePositions.push_back(precise[ring[i]]);
      }
      final.corners.push_back(id);
      final.straight.push_back(ringStraight[i]);
    }
    final.polygonStart.push_back(std::uint32_t(final.corners.size()));
    final.polygonSource.push_back(out.polygonSource[p]);
    final.polygonMask.push_back(out.polygonMask[p]);
  }
  result.mesh = std::move(final);
  CutMesh& m = result.mesh;
  stats.outputPolygons = m.polygonCount();
  stats.outputVertices = m.positions.size();
  for (std::size_t p = 0; p < m.polygonCount(); ++p) {
    stats.outputTriangles += m.cornerCount(p) - 2;
    const double area = polygonArea(m, p);
    for (std::size_t l = 0; l < stats.lights.size(); ++l) {
      if (m.polygonMask[p] & (LightMask(1) << l)) {
        ++stats.lights[l].litPolygons;
        stats.lights[l].litArea += area;
      } else {
        ++stats.lights[l].shadowedPolygons;
        stats.lights[l].shadowedArea += area;
      }
    }
  }
  stats.assembleSeconds = since(start);
  if (stats.droppedSlivers > 0) {
    result.warnings.push_back(fmt::format("{} sliver piece(s) thinner than float precision dropped", stats.droppedSlivers));
    log::warn("cut: {}", result.warnings.back());
  }
  return result;
}

CutResult cut(const Mesh& mesh, const CutOptions& options) {
  CutOptions whole = options;
  whole.shardIndex = 0;
  whole.shardCount = 1;
  std::vector<Shard> shards;
  shards.push_back(cutShard(mesh, whole));
  return mergeShards(mesh, std::move(shards), whole);
}

// ------------------------------------------------------------------ triangles

Light parseLight(std::string_view text) {
  const auto fields = splitFields(text, ',');
  if (fields.size() != 3 && fields.size() != 4) {
    fail(ErrorKind::Usage, "--light must be x,y,z or x,y,z,name, got '{}'", printable(text));
  }
  Light light;
  for (int i = 0; i < 3; ++i) light.position[i] = parseFloat(fields[std::size_t(i)], "--light");
  if (fields.size() == 4) light.name = std::string(fields[3]);
  return light;
}

double polygonArea(const CutMesh& mesh, std::size_t polygon) {
  const std::uint32_t s = mesh.polygonStart[polygon], e = mesh.polygonStart[polygon + 1];
  const dvec3& o = mesh.precisePositions[mesh.corners[s]];
  dvec3 sum(0.0);
  for (std::uint32_t c = s + 1; c + 1 < e; ++c)
    sum += glm::cross(mesh.precisePositions[mesh.corners[c]] - o, mesh.precisePositions[mesh.corners[c + 1]] - o);
  return 0.5 * glm::length(sum);
}

void triangulatePolygon(std::span<const std::uint32_t> corners, std::span<const std::uint8_t> straight,
                        std::vector<std::uint32_t>& out) {
  // Ear clipping at corners that turn: the ear (prev, v, next) then has area, and prev and
  // next turn afterwards (they were on v's two sides, which are different lines). An ear
  // is taken only when at least three turning corners remain, so what is left keeps its
  // area: n − 2 triangles, none of zero area, no extra vertex.
  std::vector<std::uint32_t> v(corners.begin(), corners.end());
  std::vector<std::uint8_t> st(straight.begin(), straight.end());
  while (v.size() > 3) {
    const std::size_t n = v.size();
    std::size_t turning = 0;
    for (std::uint8_t x : st) turning += !x;
    std::size_t ear = n;
    for (std::size_t i = 0; i < n && ear == n; ++i) {
      if (st[i]) continue;
      const std::size_t left = turning - 1 + st[(i + n - 1) % n] + st[(i + 1) % n];
      if (left >= 3) ear = i;
    }
    if (ear == n) ear = 0;  // not reached for a convex polygon with area (cutter.h)
    const std::size_t prev = (ear + n - 1) % n, next = (ear + 1) % n;
    out.insert(out.end(), {v[prev], v[ear], v[next]});
    st[prev] = st[next] = 0;
    v.erase(v.begin() + std::ptrdiff_t(ear));
    st.erase(st.begin() + std::ptrdiff_t(ear));
  }
  out.insert(out.end(), v.begin(), v.end());
}

Triangles triangulate(const CutMesh& mesh) {
  Triangles t;
  t.mesh.positions = mesh.positions;
  for (std::size_t p = 0; p < mesh.polygonCount(); ++p) {
    const std::uint32_t s = mesh.polygonStart[p];
    const std::size_t n = mesh.cornerCount(p), before = t.mesh.indices.size();
    triangulatePolygon(std::span(mesh.corners).subspan(s, n), std::span(mesh.straight).subspan(s, n), t.mesh.indices);
    for (std::size_t i = before; i < t.mesh.indices.size(); i += 3) t.trianglePolygon.push_back(std::uint32_t(p));
  }
  return t;
}

}  // namespace glint::cut
