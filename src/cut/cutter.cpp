// The shadow cutter's job on one machine: cut() is cutShard (prepare.cpp: the scene
// prepared; here: every receiver of the shard cut in parallel) and mergeShards (merge.cpp:
// the pieces made one mesh, shared edges consistent, vertices rounded, slivers dropped).
#include "glint/cut/cutter.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"

#include "lights.h"
#include "pieces.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <utility>

namespace glint::cut {

namespace {

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

/// A triangle that is not cut (no area): its corners as one polygon, unlit.
ReceiverPieces uncutTriangle(const SceneData& scene, std::uint32_t f) {
  ReceiverPieces pieces = wholeTriangle(0);
  for (int k = 0; k < 3; ++k) {
    pieces.vertices[std::size_t(k)].kind = exact::VertexKind::Point;
    pieces.vertices[std::size_t(k)].a = scene.triangles[f][std::size_t(k)];
  }
  pieces.positions = {scene.geometry.point(scene.triangles[f][0]), scene.geometry.point(scene.triangles[f][1]),
                      scene.geometry.point(scene.triangles[f][2])};
  return pieces;
}

/// Cuts `receivers` in blocks of kBlockSize, in parallel, into `blocks` (one PieceBlock
/// each); returns their counts, summed in block order. Error(Interrupted) when cancelled.
ReceiverStats cutReceivers(const Prepared& prep, const std::vector<std::uint32_t>& receivers, const CutOptions& options,
                           std::vector<PieceBlock>& blocks) {
  const SceneData& scene = *prep.scene;
  const std::size_t count = (receivers.size() + kBlockSize - 1) / kBlockSize;
  blocks.resize(count);
  std::vector<ReceiverStats> blockStats(count);
  tbb::enumerable_thread_specific<ReceiverCutter> cutters(std::cref(scene), options.cancel);
  tbb::enumerable_thread_specific<ReceiverPieces> scratch;
  std::optional<Progress> progress;
  if (options.progress) progress.emplace("cut", receivers.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    ReceiverCutter& cutter = cutters.local();
    ReceiverPieces& pieces = scratch.local();
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      if (options.cancel && options.cancel->load()) return;
      const std::size_t first = b * kBlockSize, last = std::min(receivers.size(), first + kBlockSize);
      for (std::size_t i = first; i < last; ++i) {
        const std::uint32_t f = receivers[i];
        if (prep.state[f] == Prepared::kUsable) cutter.cut(f, pieces, blockStats[b]);
        else pieces = uncutTriangle(scene, f);
        blocks[b].append(f, pieces);
      }
      if (progress) progress->advance(last - first);
    }
  }, tbb::simple_partitioner());
  if (progress) progress->finish();
  if (options.cancel && options.cancel->load()) fail(ErrorKind::Interrupted, "cut interrupted");
  ReceiverStats total;
  for (const ReceiverStats& s : blockStats) total.add(s);
  return total;
}

/// Per light: its name and position, and the usable receivers whose plane contains it.
/// (ReceiverStats sums grazing pairs over all lights, so they are recounted here: cheap,
/// one exact sign per triangle and light.)
std::vector<LightStats> lightStats(const Prepared& prep, const std::vector<std::uint32_t>& receivers,
                                   const std::vector<Light>& lights) {
  const SceneData& scene = *prep.scene;
  std::vector<LightStats> stats(lights.size());
  exact::PredicateStats ignored;
  for (std::size_t l = 0; l < lights.size(); ++l) {
    stats[l].name = lightName(lights[l], l);
    stats[l].position = lights[l].position;
    std::uint64_t grazing = 0;
    for (std::uint32_t f : receivers) {
      if (prep.state[f] != Prepared::kUsable) continue;
      const auto& c = scene.triangles[f];
      grazing += scene.geometry.side(scene.lightBase + std::uint32_t(l), exact::PlaneDef{{c[0], c[1], c[2]}}, ignored) == 0;
    }
    stats[l].grazingTriangles = grazing;
  }
  return stats;
}

}  // namespace

Shard cutShard(const Mesh& mesh, const CutOptions& options) {
  if (options.shardCount < 1 || options.shardIndex < 0 || options.shardIndex >= options.shardCount)
    fail(ErrorKind::Usage, "shard {} of {} does not exist (shards are 1..n)", options.shardIndex + 1, options.shardCount);
  const auto start = Clock::now();
  const Prepared prep = prepare(mesh, options.lights, true);
  for (const std::string& w : prep.warnings) log::warn("cut: {}", w);
  Shard shard;
  shard.warnings = prep.warnings;
  shard.inputHash = prep.hash;
  shard.shardIndex = options.shardIndex;
  shard.shardCount = options.shardCount;
  shard.lights = options.lights;
  shard.pieces = std::make_shared<Shard::Impl>();
  CutStats& stats = shard.stats;
  stats.inputTriangles = prep.scene->triangles.size();
  for (std::uint8_t st : prep.state) {
    stats.degenerateTriangles += st == Prepared::kDegenerate;
    stats.collapsedTriangles += st == Prepared::kCollapsed;
  }
  const std::vector<std::uint32_t> receivers = shardReceivers(prep, options.shardIndex, options.shardCount);
  stats.receivers = receivers.size();
  stats.prepareSeconds = since(start);

  const auto cutStart = Clock::now();
  const ReceiverStats total = cutReceivers(prep, receivers, options, shard.pieces->blocks);
  stats.candidates = total.candidates;
  stats.occluders = total.occluders;
  stats.clippedPairs = total.clippedPairs;
  stats.cuts = total.cuts;
  stats.facesBeforeMerge = total.facesBeforeMerge;
  stats.symbolicPredicates = total.predicates.symbolic;
  stats.filteredPredicates = total.predicates.filtered;
  stats.exactPredicates = total.predicates.exact;
  stats.cutSeconds = since(cutStart);
  stats.lights = lightStats(prep, receivers, options.lights);
  return shard;
}

CutResult cut(const Mesh& mesh, const CutOptions& options) {
  checkMergeGroups(mesh, options);
  CutOptions whole = options;
  whole.shardIndex = 0;
  whole.shardCount = 1;
  std::vector<Shard> shards;
  shards.push_back(cutShard(mesh, whole));
  return mergeShards(mesh, std::move(shards), whole);
}

}  // namespace glint::cut
