// Pieces of coplanar neighbours merged across input triangles (coplanar.h).
#include "coplanar.h"

#include "regions.h"

#include "glint/core/union_find.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <memory>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <utility>

namespace glint::cut {

namespace {

constexpr std::uint32_t kNoPiece = 0xFFFFFFFFu;

/// One patch's pieces after merging, before they take their place in the mesh.
struct PatchPieces {
  std::vector<std::uint32_t> polygonStart{0}, corners;
  std::vector<std::uint8_t> straight;
  std::vector<LightMask> masks;
  void add(std::span<const std::uint32_t> ids, std::span<const std::uint8_t> flags, LightMask mask) {
    corners.insert(corners.end(), ids.begin(), ids.end());
    straight.insert(straight.end(), flags.begin(), flags.end());
    polygonStart.push_back(std::uint32_t(corners.size()));
    masks.push_back(mask);
  }
};

/// Merges one patch (its triangles ascending); nullopt when nothing changes (no vertex to
/// drop) or a region cannot be triangulated again (then every piece stays as it was).
class PatchMerger {
public:
  PatchMerger(const CoplanarInput& in, const CutMesh& polygons)
      : m_in(in), m_polygons(polygons), m_triangulator(in.prep.scene->geometry) {}

  std::optional<PatchPieces> merge(std::span<const std::uint32_t> triangles);

private:
  /// Copies the pieces of the patch's triangles into the local corner arrays.
  void gatherCorners(std::span<const std::uint32_t> triangles);
  /// Pairs each side with its twin, the side running the other way.
  void findTwins();
  /// Marks outline vertices and counts the region outline edges meeting at each vertex.
  void collectVertexInfo();
  /// Sets the triangulator's plane from the given triangle, once per patch.
  void setPlane(std::uint32_t triangle);
  /// Marks the vertices that go; true when there is any.
  bool markDrops(std::uint32_t lowest);
  /// Joins polygons into regions across sides whose polygons have the same mask.
  void joinRegions();
  /// Lists region r's polygons from p on; true when any of their vertices goes.
  bool collectRegion(std::uint32_t p, std::uint32_t r);
  /// Adds the region's polygons as they are, less the corners that go.
  void keepRegionPolygons(PatchPieces& out);
  /// Triangulates the region's outlines again with polygon p's mask; false when that fails.
  bool retriangulateRegion(std::uint32_t p, PatchPieces& out);
  struct VertexInfo {
    bool outline = false;           ///< on the patch's outline: stays
    std::uint8_t degree = 0;        ///< region outline edges meeting here
    std::uint32_t ends[2] = {kNoPiece, kNoPiece};  ///< the other ends of the first two
    bool drop = false;
  };
  bool boundary(std::uint32_t i) const {
    return m_twin[i] == kNoPiece || m_mask[m_poly[i]] != m_mask[m_poly[m_twin[i]]];
  }
  std::uint32_t findRegion(std::uint32_t p) {
    while (m_region[p] != p) p = m_region[p] = m_region[m_region[p]];
    return p;
  }

  const CoplanarInput& m_in;
  const CutMesh& m_polygons;
  RegionTriangulator m_triangulator;
  // The patch's corners, polygon by polygon (local indices).
  std::vector<std::uint32_t> m_polyStart, m_vertex, m_next, m_poly, m_twin, m_region, m_sorted;
  std::vector<LightMask> m_mask;
  std::vector<std::uint8_t> m_straight, m_visited, m_flags;
  std::unordered_map<std::uint32_t, VertexInfo> m_info;
  std::vector<std::uint32_t> m_loopVertices, m_loopStart, m_regionPolys;
  ConvexPieces m_pieces;
  bool m_plane = false;  ///< the triangulator's plane is set for this patch
};

void PatchMerger::gatherCorners(std::span<const std::uint32_t> triangles) {
  const CutMesh& src = m_polygons;
  m_polyStart.assign(1, 0);
  m_vertex.clear();
  m_next.clear();
  m_poly.clear();
  m_mask.clear();
  m_straight.clear();
  for (std::uint32_t f : triangles)
    for (std::uint32_t p = m_in.polygonFirst[f]; p < m_in.polygonFirst[f + 1]; ++p) {
      const std::uint32_t local = std::uint32_t(m_mask.size()), s = src.polygonStart[p], e = src.polygonStart[p + 1];
      const std::uint32_t base = std::uint32_t(m_vertex.size());
      for (std::uint32_t c = s; c < e; ++c) {
        m_vertex.push_back(src.corners[c]);
        m_next.push_back(c + 1 < e ? base + (c - s) + 1 : base);
        m_poly.push_back(local);
        m_straight.push_back(src.straight[c]);
      }
      m_mask.push_back(src.polygonMask[p]);
      m_polyStart.push_back(std::uint32_t(m_vertex.size()));
    }
}

void PatchMerger::findTwins() {
  const std::uint32_t n = std::uint32_t(m_vertex.size());
  // Twins: the side v → u of side u → v.
  m_sorted.resize(n);
  std::iota(m_sorted.begin(), m_sorted.end(), 0u);
  const auto key = [&](std::uint32_t i) { return std::pair(m_vertex[i], m_vertex[m_next[i]]); };
  std::sort(m_sorted.begin(), m_sorted.end(), [&](std::uint32_t x, std::uint32_t y) { return key(x) < key(y); });
  m_twin.assign(n, kNoPiece);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::pair want(m_vertex[m_next[i]], m_vertex[i]);
    const auto it = std::lower_bound(m_sorted.begin(), m_sorted.end(), want,
                                     [&](std::uint32_t x, const std::pair<std::uint32_t, std::uint32_t>& k) { return key(x) < k; });
    if (it != m_sorted.end() && key(*it) == want) m_twin[i] = *it;
  }
}

void PatchMerger::collectVertexInfo() {
  const std::uint32_t n = std::uint32_t(m_vertex.size());
  // Outline, region outline degrees and their ends.
  m_info.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t u = m_vertex[i], v = m_vertex[m_next[i]];
    VertexInfo& a = m_info[u];
    VertexInfo& b = m_info[v];
    if (m_twin[i] == kNoPiece) a.outline = b.outline = true;
    if (!boundary(i) || (m_twin[i] != kNoPiece && m_twin[i] < i)) continue;
    if (a.degree < 2) a.ends[a.degree] = v;
    if (b.degree < 2) b.ends[b.degree] = u;
    a.degree = std::uint8_t(std::min(a.degree + 1, 255));
    b.degree = std::uint8_t(std::min(b.degree + 1, 255));
  }
}

void PatchMerger::setPlane(std::uint32_t triangle) {
  if (m_plane) return;
  m_plane = true;
  const auto& corners = m_in.prep.scene->triangles[triangle];
  const exact::Geometry& g = m_in.prep.scene->geometry;
  const dvec3 a = g.point(corners[0]), b = g.point(corners[1]), c = g.point(corners[2]);
  const dvec3 an = glm::abs(glm::cross(b - a, c - a));
  const int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  std::array<exact::VertexDef, 3> defs;
  for (std::size_t k = 0; k < 3; ++k) defs[k] = exact::VertexDef{.kind = exact::VertexKind::Point, .a = corners[k]};
  m_triangulator.reset((axis + 1) % 3, (axis + 2) % 3, defs,
                       [this](std::uint32_t v) -> const exact::VertexDef& { return m_in.defs[v]; });
}

bool PatchMerger::markDrops(std::uint32_t lowest) {
  bool any = false;
  for (auto& [id, info] : m_info) {
    // On the outline only where no other patch has the vertex (an open edge of the
    // surface), and then only on a straight outline.
    if (info.outline && (m_in.shared[id] || info.degree != 2)) continue;
    if (info.degree != 0 && info.degree != 2) continue;
    if (info.degree == 2) {
      setPlane(lowest);
      if (!m_triangulator.collinear(info.ends[0], id, info.ends[1])) continue;
    }
    info.drop = true;
    any = true;
  }
  return any;
}

void PatchMerger::joinRegions() {
  const std::uint32_t n = std::uint32_t(m_vertex.size());
  // Regions: polygons joined across sides whose polygons have the same mask.
  const std::uint32_t polys = std::uint32_t(m_mask.size());
  m_region.resize(polys);
  std::iota(m_region.begin(), m_region.end(), 0u);
  for (std::uint32_t i = 0; i < n; ++i)
    if (m_twin[i] != kNoPiece && !boundary(i)) {
      const std::uint32_t a = findRegion(m_poly[i]), b = findRegion(m_poly[m_twin[i]]);
      if (a != b) m_region[std::max(a, b)] = std::min(a, b);
    }
}

bool PatchMerger::collectRegion(std::uint32_t p, std::uint32_t r) {
  const std::uint32_t polys = std::uint32_t(m_mask.size());
  m_regionPolys.clear();
  bool drops = false;
  for (std::uint32_t q = p; q < polys; ++q)
    if (findRegion(q) == r) {
      m_regionPolys.push_back(q);
      for (std::uint32_t i = m_polyStart[q]; i < m_polyStart[q + 1]; ++i) drops |= m_info[m_vertex[i]].drop;
    }
  return drops;
}

void PatchMerger::keepRegionPolygons(PatchPieces& out) {
  // As they are, less their straight corners that go (a single convex piece stays one).
  for (std::uint32_t q : m_regionPolys) {
    m_loopVertices.clear();
    m_flags.clear();
    for (std::uint32_t i = m_polyStart[q]; i < m_polyStart[q + 1]; ++i) {
      if (m_info[m_vertex[i]].drop) continue;
      m_loopVertices.push_back(m_vertex[i]);
      m_flags.push_back(m_straight[i]);
    }
    out.add(m_loopVertices, m_flags, m_mask[q]);
  }
}

bool PatchMerger::retriangulateRegion(std::uint32_t p, PatchPieces& out) {
  // The region's outlines, kept corners only, and its triangles.
  m_loopVertices.clear();
  m_loopStart.clear();
  for (std::uint32_t q : m_regionPolys)
    for (std::uint32_t i0 = m_polyStart[q]; i0 < m_polyStart[q + 1]; ++i0) {
      if (!boundary(i0) || m_visited[i0]) continue;
      m_loopStart.push_back(std::uint32_t(m_loopVertices.size()));
      std::uint32_t i = i0;
      do {
        m_visited[i] = 1;
        if (!m_info[m_vertex[i]].drop) m_loopVertices.push_back(m_vertex[i]);
        std::uint32_t x = m_next[i];
        while (!boundary(x)) x = m_next[m_twin[x]];
        i = x;
      } while (i != i0);
    }
  m_loopStart.push_back(std::uint32_t(m_loopVertices.size()));
  m_pieces.clear();
  if (!m_triangulator.triangulate(m_loopVertices, m_loopStart, m_pieces)) return false;
  for (std::size_t q = 0, s = 0; q < m_pieces.end.size(); s = m_pieces.end[q++])
    out.add(std::span(m_pieces.corners).subspan(s, m_pieces.end[q] - s),
            std::span(m_pieces.straight).subspan(s, m_pieces.end[q] - s), m_mask[p]);
  return true;
}

std::optional<PatchPieces> PatchMerger::merge(std::span<const std::uint32_t> triangles) {
  gatherCorners(triangles);
  const std::uint32_t n = std::uint32_t(m_vertex.size());
  findTwins();
  collectVertexInfo();
  // Which vertices go: inside the patch, inside a region or on a straight outline.
  // The patch's plane for exact tests: its lowest triangle, projected along the dominant
  // axis of its normal (once, when first needed).
  m_plane = false;
  if (!markDrops(triangles.front())) return std::nullopt;
  setPlane(triangles.front());
  joinRegions();
  const std::uint32_t polys = std::uint32_t(m_mask.size());
  PatchPieces out;
  m_visited.assign(n, 0);
  std::vector<std::uint8_t> done(polys, 0);
  for (std::uint32_t p = 0; p < polys; ++p) {
    const std::uint32_t r = findRegion(p);
    if (done[r]) continue;
    done[r] = 1;
    const bool drops = collectRegion(p, r);
    if (!drops || m_regionPolys.size() == 1) {
      keepRegionPolygons(out);
      continue;
    }
    if (!retriangulateRegion(p, out)) return std::nullopt;
  }
  return out;
}

}  // namespace

std::vector<std::uint32_t> coplanarPatches(const CoplanarInput& in) {
  const Prepared& prep = in.prep;
  const SceneData& scene = *prep.scene;
  const exact::Geometry& g = scene.geometry;
  const std::size_t n = scene.triangles.size();
  UnionFind sets(n);
  exact::PredicateStats stats;
  for (const Edge& e : prep.edges.edges()) {
    if (e.faceCount != 2) continue;
    const auto faces = prep.edges.faces(e);
    const std::uint32_t f0 = faces[0].face, f1 = faces[1].face;
    if (faces[0].orientation == faces[1].orientation) continue;  // wound against each other
    if (prep.state[f0] != Prepared::kUsable || prep.state[f1] != Prepared::kUsable) continue;
    if (in.polygonFirst[f0] == in.polygonFirst[f0 + 1] || in.polygonFirst[f1] == in.polygonFirst[f1 + 1]) continue;
    if (!in.groups.empty() && in.groups[f0] != in.groups[f1]) continue;
    const auto& t0 = scene.triangles[f0];
    const auto& t1 = scene.triangles[f1];
    std::uint32_t d = kNoPiece;
    for (std::uint32_t c : t1)
      if (c != e.a && c != e.b) d = c;
    if (d == kNoPiece) continue;
    const exact::PlaneDef p0{{t0[0], t0[1], t0[2]}}, p1{{t1[0], t1[1], t1[2]}};
    if (g.side(d, p0, stats) != 0 || g.normalsDot(p0, p1) <= 0) continue;
    sets.unite(f0, f1);
  }
  std::vector<std::uint32_t> patch(n);
  for (std::uint32_t f = 0; f < n; ++f) patch[f] = sets.find(f);
  return patch;
}

CutMesh mergeCoplanar(CoplanarInput in, std::vector<std::uint32_t>& patch, const CutMesh& polygons,
                      std::uint64_t& merged) {
  const std::size_t n = patch.size();
  // Vertices that pieces of two or more patches use.
  std::vector<std::uint32_t> owner(in.defs.size(), kNoPiece);
  std::vector<std::uint8_t> shared(in.defs.size(), 0);
  for (std::uint32_t f = 0; f < n; ++f)
    for (std::uint32_t q = in.polygonFirst[f]; q < in.polygonFirst[f + 1]; ++q)
      for (std::uint32_t c = polygons.polygonStart[q]; c < polygons.polygonStart[q + 1]; ++c) {
        std::uint32_t& o = owner[polygons.corners[c]];
        if (o == kNoPiece) o = patch[f];
        else if (o != patch[f]) shared[polygons.corners[c]] = 1;
      }
  in.shared = shared;
  // Patches of two or more triangles, their triangles ascending.
  std::vector<std::uint32_t> size(n, 0);
  for (std::uint32_t r : patch) ++size[r];
  std::vector<std::uint32_t> roots, start(n, kNoPiece);
  std::vector<std::uint32_t> members;
  for (std::uint32_t f = 0; f < n; ++f)
    if (patch[f] == f && size[f] > 1) {
      start[f] = std::uint32_t(roots.size());
      roots.push_back(f);
    }
  std::vector<std::uint32_t> memberStart(roots.size() + 1, 0);
  for (std::size_t i = 0; i < roots.size(); ++i) memberStart[i + 1] = memberStart[i] + size[roots[i]];
  members.resize(memberStart.back());
  std::vector<std::uint32_t> fill(memberStart.begin(), memberStart.end() - 1);
  for (std::uint32_t f = 0; f < n; ++f)
    if (start[patch[f]] != kNoPiece) members[fill[start[patch[f]]]++] = f;

  std::vector<std::optional<PatchPieces>> results(roots.size());
  tbb::enumerable_thread_specific<std::unique_ptr<PatchMerger>> mergers;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, roots.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
    auto& m = mergers.local();
    if (!m) m = std::make_unique<PatchMerger>(in, polygons);
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      results[i] = m->merge(std::span(members).subspan(memberStart[i], memberStart[i + 1] - memberStart[i]));
  });

  // A patch that did not change is its triangles, each on its own.
  for (std::uint32_t f = 0; f < n; ++f)
    if (start[patch[f]] != kNoPiece && !results[start[patch[f]]]) patch[f] = f;
  CutMesh out;
  out.polygonStart.push_back(0);
  const auto append = [&](std::span<const std::uint32_t> ids, std::span<const std::uint8_t> flags, std::uint32_t source,
                          LightMask mask) {
    out.corners.insert(out.corners.end(), ids.begin(), ids.end());
    out.straight.insert(out.straight.end(), flags.begin(), flags.end());
    out.polygonStart.push_back(std::uint32_t(out.corners.size()));
    out.polygonSource.push_back(source);
    out.polygonMask.push_back(mask);
  };
  merged = 0;
  for (std::uint32_t f = 0; f < n; ++f) {
    const std::uint32_t i = start[patch[f]];
    if (i != kNoPiece && results[i]) {
      if (patch[f] != f) continue;
      const PatchPieces& p = *results[i];
      ++merged;
      for (std::size_t q = 0; q < p.masks.size(); ++q) {
        const std::uint32_t s = p.polygonStart[q], e = p.polygonStart[q + 1];
        append(std::span(p.corners).subspan(s, e - s), std::span(p.straight).subspan(s, e - s), f, p.masks[q]);
      }
      continue;
    }
    for (std::uint32_t q = in.polygonFirst[f]; q < in.polygonFirst[f + 1]; ++q) {
      const std::uint32_t s = polygons.polygonStart[q], e = polygons.polygonStart[q + 1];
      append(std::span(polygons.corners).subspan(s, e - s), std::span(polygons.straight).subspan(s, e - s), f,
             polygons.polygonMask[q]);
    }
  }
  return out;
}

}  // namespace glint::cut
