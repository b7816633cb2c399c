// Joining shards into the cut mesh. mergeShards, at the end, reads as the list of steps;
// the steps share their tables through one struct, Merge, each filling its part:
//   check        the shards are one job's, each once, cut with these lights
//   totals       the shards' stats and warnings summed
//   locate       which block and entry of which shard holds each triangle's pieces
//   1. edges     every vertex a receiver has on an input edge, sorted along that edge
//                exactly and deduplicated, so both sides of the edge get all of them
//   2. ids       vertex ids: welded points, then edge vertices edge by edge, then each
//                receiver's interior vertices in triangle order
//   3. polygons  triangle by triangle, with the edge vertices inserted on boundary runs
//   3b. coplanar pieces of coplanar neighbours with one light mask merged, the vertices
//                inside them dropped (coplanar.h)
//   4. rounding  to float; vertices of one surface that round to one position become one,
//                and polygons left with fewer than three corners are dropped
//   count        polygons, triangles, vertices and areas per light
#include "glint/core/error.h"
#include "glint/core/log.h"

#include "coplanar.h"
#include "lights.h"
#include "pieces.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace glint::cut {

namespace {

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

/// A vertex some receiver has on an input edge.
struct EdgeEntry {
  std::uint32_t edge;       ///< EdgeMap edge
  std::uint32_t block, entry, local;  ///< where the vertex is
  std::uint32_t unionIndex = 0;  ///< position in the edge's sorted, deduplicated list
};

void throwIfCancelled(const CutOptions& options) {
  if (options.cancel && options.cancel->load()) fail(ErrorKind::Interrupted, "cut interrupted");
}

/// check: the shards belong to this scene and these lights, each shard once, none missing.
void checkShards(const std::vector<Shard>& shards, const Prepared& prep) {
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
}

/// totals: the shards' warnings (each once) and stats, summed.
CutResult shardTotals(const std::vector<Shard>& shards, const Prepared& prep) {
  CutResult result;
  CutStats& stats = result.stats;
  for (const Shard& s : shards)
    for (const std::string& w : s.warnings)
      if (std::find(result.warnings.begin(), result.warnings.end(), w) == result.warnings.end()) result.warnings.push_back(w);
  stats.inputTriangles = prep.scene->triangles.size();
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
  return result;
}

/// The tables the steps share; each step fills the part marked with its name.
struct Merge {
  explicit Merge(const Prepared& p) : prep(p), scene(*p.scene), g(p.scene->geometry) {}

  const Prepared& prep;
  const SceneData& scene;
  const exact::Geometry& g;
  // locate
  std::vector<const PieceBlock*> blocks;                       ///< every piece block of every shard
  std::vector<std::pair<std::uint32_t, std::uint32_t>> where;  ///< triangle → (block, entry); kNone: dropped
  // 1. edges
  std::vector<EdgeEntry> entries;         ///< by edge, then receiver triangle, then local vertex
  std::vector<std::size_t> groupStart;    ///< one group per edge with vertices: entries [groupStart[gi], groupStart[gi + 1])
  std::vector<std::uint32_t> unionCount;  ///< distinct points on each group's edge
  // 2. ids
  std::uint32_t pointCount = 0;           ///< welded input points: ids 0 .. pointCount − 1
  std::vector<std::uint32_t> groupBase;   ///< id of each group's first point
  std::vector<std::uint32_t> edgeGroup;   ///< EdgeMap edge → group; kNone: no vertex on it
  std::vector<std::size_t> byReceiver;    ///< entries sorted by (block, entry, local)
  std::vector<dvec3> precise;             ///< position of every id
  std::vector<exact::VertexDef> defs;     ///< name of every id
  std::vector<std::uint32_t> vertexComponent;  ///< connected surface of every id
  // 3. polygons
  CutMesh polygons;                       ///< corners are ids; no positions yet
  std::vector<std::uint32_t> polygonFirst;  ///< per triangle, and the end: its polygons

  const PieceBlock& block(std::uint32_t b) const { return *blocks[b]; }
  const exact::VertexDef& defOf(const EdgeEntry& x) const {
    return blocks[x.block]->vertices[blocks[x.block]->vertexStart[x.entry] + x.local];
  }
  const dvec3& posOf(const EdgeEntry& x) const {
    return blocks[x.block]->positions[blocks[x.block]->vertexStart[x.entry] + x.local];
  }

  void locate(const std::vector<Shard>& shards);
  void collectEdgeVertices();
  void sortAlongEdges(CutStats& stats);
  void numberVertices();
  void addPolygons(std::uint32_t f);
  CutMesh rounded(std::uint64_t& droppedSlivers) const;

private:
  /// Ids of receiver f's vertices (localId), and for those on an edge, (group, union index).
  void receiverIds(std::uint32_t f, std::vector<std::uint32_t>& localId,
                   std::vector<std::pair<std::uint32_t, std::uint32_t>>& edgeOf);
};

void Merge::locate(const std::vector<Shard>& shards) {
  for (const Shard& s : shards)
    for (const PieceBlock& b : s.pieces->blocks) blocks.push_back(&b);
  where.assign(scene.triangles.size(), {kNone, kNone});
  for (std::uint32_t b = 0; b < blocks.size(); ++b)
    for (std::uint32_t e = 0; e < blocks[b]->entries(); ++e) {
      const std::uint32_t f = blocks[b]->receiver[e];
      if (f >= where.size() || where[f].first != kNone) fail(ErrorKind::Input, "shards overlap: triangle {} cut twice", f);
      where[f] = {b, e};
    }
  for (std::uint32_t f = 0; f < where.size(); ++f)
    if (where[f].first == kNone && prep.state[f] != Prepared::kCollapsed)
      fail(ErrorKind::Input, "shards do not cover triangle {}", f);
}

void Merge::collectEdgeVertices() {
  for (std::uint32_t f = 0; f < where.size(); ++f) {
    if (where[f].first == kNone) continue;
    const auto [b, e] = where[f];
    const PieceBlock& blk = block(b);
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
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (i == 0 || entries[i].edge != entries[i - 1].edge) groupStart.push_back(i);
  groupStart.push_back(entries.size());
}

void Merge::sortAlongEdges(CutStats& stats) {
  // Each edge's group sorted along it, in parallel: groups are independent.
  unionCount.assign(groupStart.size() - 1, 0);
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
}

void Merge::numberVertices() {
  // Vertices are welded later only within one connected surface of the input, so
  // surfaces that merely touch stay apart, as they were.
  const std::vector<std::uint32_t>& component = scene.component;
  pointCount = std::uint32_t(prep.edges.positions().size());
  groupBase.assign(unionCount.size() + 1, pointCount);
  for (std::size_t gi = 0; gi < unionCount.size(); ++gi) groupBase[gi + 1] = groupBase[gi] + unionCount[gi];
  precise.resize(groupBase.back());
  defs.resize(groupBase.back());
  vertexComponent.assign(groupBase.back(), kNone);
  for (std::uint32_t i = 0; i < pointCount; ++i) {
    precise[i] = g.point(i);
    defs[i] = exact::VertexDef{.kind = exact::VertexKind::Point, .a = i};
  }
  for (std::uint32_t f = 0; f < scene.triangles.size(); ++f)
    for (std::uint32_t c : scene.triangles[f])
      if (vertexComponent[c] == kNone) vertexComponent[c] = component[f];
  edgeGroup.assign(prep.edges.edges().size(), kNone);
  for (std::size_t gi = 0; gi + 1 < groupStart.size(); ++gi) {
    edgeGroup[entries[groupStart[gi]].edge] = std::uint32_t(gi);
    const std::uint32_t c = component[prep.edges.faces(prep.edges.edges()[entries[groupStart[gi]].edge])[0].face];
    for (std::size_t i = groupStart[gi + 1]; i-- > groupStart[gi];) {  // the first entry's position wins
      precise[groupBase[gi] + entries[i].unionIndex] = posOf(entries[i]);
      defs[groupBase[gi] + entries[i].unionIndex] = defOf(entries[i]);
      vertexComponent[groupBase[gi] + entries[i].unionIndex] = c;
    }
  }
  // Per (block, entry): its edge entries sorted by local vertex, to look them up.
  byReceiver.resize(entries.size());
  std::iota(byReceiver.begin(), byReceiver.end(), 0);
  std::sort(byReceiver.begin(), byReceiver.end(), [&](std::size_t x, std::size_t y) {
    return std::tie(entries[x].block, entries[x].entry, entries[x].local) <
           std::tie(entries[y].block, entries[y].entry, entries[y].local);
  });
  polygons.polygonStart.push_back(0);
}

void Merge::receiverIds(std::uint32_t f, std::vector<std::uint32_t>& localId,
                        std::vector<std::pair<std::uint32_t, std::uint32_t>>& edgeOf) {
  const auto [b, e] = where[f];
  const PieceBlock& blk = block(b);
  const std::uint32_t v0 = blk.vertexStart[e], v1 = blk.vertexStart[e + 1];
  localId.assign(v1 - v0, kNone);
  edgeOf.assign(v1 - v0, {kNone, kNone});
  // The receiver's edge entries. Several edges can't share a LinePlane vertex.
  auto lo = std::lower_bound(byReceiver.begin(), byReceiver.end(), std::make_pair(b, e),
                             [&](std::size_t x, const std::pair<std::uint32_t, std::uint32_t>& key) {
                               return std::tie(entries[x].block, entries[x].entry) < std::tie(key.first, key.second);
                             });
  for (auto it = lo; it != byReceiver.end() && entries[*it].block == b && entries[*it].entry == e; ++it) {
    const EdgeEntry& x = entries[*it];
    const std::uint32_t gi = edgeGroup[x.edge];
    edgeOf[x.local] = {gi, x.unionIndex};
    localId[x.local] = groupBase[gi] + x.unionIndex;
  }
  // Corners of the triangle keep their point's id; interior vertices get new ones.
  for (std::uint32_t v = 0; v < v1 - v0; ++v) {
    if (localId[v] != kNone) continue;
    const exact::VertexDef& d = blk.vertices[v0 + v];
    if (d.kind == exact::VertexKind::Point) {
      localId[v] = d.a;
    } else {
      localId[v] = std::uint32_t(precise.size());
      precise.push_back(blk.positions[v0 + v]);
      defs.push_back(d);
      vertexComponent.push_back(scene.component[f]);
    }
  }
}

void Merge::addPolygons(std::uint32_t f) {
  std::vector<std::uint32_t> localId;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edgeOf;  ///< edge vertex local → (group, union index)
  receiverIds(f, localId, edgeOf);
  const auto [b, e] = where[f];
  const PieceBlock& blk = block(b);
  const std::uint32_t v0 = blk.vertexStart[e];
  CutMesh& out = polygons;
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

CutMesh Merge::rounded(std::uint64_t& droppedSlivers) const {
  std::vector<vec3> rounded(precise.size());
  for (std::size_t i = 0; i < precise.size(); ++i)
    rounded[i] = i < pointCount ? prep.edges.positions()[i] : vec3(precise[i]);
  // Ids by (rounded position, surface): equal neighbours become the lowest id of the run.
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
  const CutMesh& out = polygons;
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
      ++droppedSlivers;
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
  return final;
}

/// count: the output's size, and its polygons and areas per light.
void countOutput(const CutMesh& m, CutStats& stats) {
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
}

}  // namespace

void checkMergeGroups(const Mesh& mesh, const CutOptions& options) {
  if (!options.mergeGroups.empty() && options.mergeGroups.size() != mesh.triangleCount())
    fail(ErrorKind::Usage, "merge groups: {} given for {} triangles", options.mergeGroups.size(), mesh.triangleCount());
}

CutResult mergeShards(const Mesh& mesh, std::vector<Shard> shards, const CutOptions& options) {
  if (shards.empty()) fail(ErrorKind::Usage, "nothing to merge: no shards");
  checkMergeGroups(mesh, options);
  checkShardLights(options.lights, shards.front().lights);
  const auto start = Clock::now();
  const Prepared prep = prepare(mesh, shards.front().lights, false);
  checkShards(shards, prep);
  CutResult result = shardTotals(shards, prep);
  result.lights = shards.front().lights;

  Merge merge(prep);
  merge.locate(shards);
  merge.collectEdgeVertices();
  merge.sortAlongEdges(result.stats);
  throwIfCancelled(options);
  merge.numberVertices();
  merge.polygonFirst.reserve(merge.where.size() + 1);
  for (std::uint32_t f = 0; f < merge.where.size(); ++f) {
    merge.polygonFirst.push_back(std::uint32_t(merge.polygons.polygonCount()));
    if (merge.where[f].first != kNone) merge.addPolygons(f);
  }
  merge.polygonFirst.push_back(std::uint32_t(merge.polygons.polygonCount()));
  throwIfCancelled(options);
  const CoplanarInput coplanar{prep, merge.polygonFirst, merge.defs, options.mergeGroups};
  std::vector<std::uint32_t> patch = coplanarPatches(coplanar);
  merge.polygons = mergeCoplanar(coplanar, patch, merge.polygons, result.stats.mergedPatches);
  throwIfCancelled(options);
  result.mesh = merge.rounded(result.stats.droppedSlivers);
  result.mesh.trianglePatch = patch;
  countOutput(result.mesh, result.stats);
  result.stats.assembleSeconds = since(start);
  if (result.stats.droppedSlivers > 0) {
    result.warnings.push_back(
        fmt::format("{} sliver piece(s) thinner than float precision dropped", result.stats.droppedSlivers));
    log::warn("cut: {}", result.warnings.back());
  }
  return result;
}

}  // namespace glint::cut
