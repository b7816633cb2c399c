// The edge map: weld positions, then sort half-edges by their undirected key so the
// faces of each edge are adjacent in one array (no per-edge allocations, which
// matters for the 1M-triangle meshes the shadow benchmark builds).
#include "glint/mesh/adjacency.h"
#include "glint/core/union_find.h"

#include "glint/core/hash.h"

#include <algorithm>
#include <bit>
#include <numeric>
#include <unordered_map>

namespace glint {
namespace {

struct PositionKey {
  std::uint32_t x, y, z;
  bool operator==(const PositionKey&) const = default;
};

struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    return std::size_t(hashKey(k.x, k.y, k.z));
  }
};

// +0.0f turns −0.0 into +0.0, so the two zeros weld.
PositionKey keyOf(const vec3& p) {
  return {std::bit_cast<std::uint32_t>(p.x + 0.0f), std::bit_cast<std::uint32_t>(p.y + 0.0f),
          std::bit_cast<std::uint32_t>(p.z + 0.0f)};
}

struct HalfEdge {
  std::uint64_t key;  // (min << 32) | max
  std::uint32_t face;
  std::int32_t orientation;
  std::uint32_t slot;  // which edge of the face (0..2)
};

}  // namespace

EdgeMap EdgeMap::build(const Mesh& mesh) {
  mesh.validate("edge map");
  EdgeMap map;
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> ids;
  ids.reserve(mesh.vertexCount());
  map.m_weld.resize(mesh.vertexCount());
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    auto [it, inserted] = ids.try_emplace(keyOf(mesh.positions[i]), std::uint32_t(map.m_positions.size()));
    if (inserted) map.m_positions.push_back(mesh.positions[i]);
    map.m_weld[i] = it->second;
  }

  const std::size_t faces = mesh.triangleCount();
  map.m_corners.resize(faces);
  map.m_faceEdges.assign(faces, {kNone, kNone, kNone});
  std::vector<HalfEdge> halves;
  halves.reserve(3 * faces);
  for (std::uint32_t f = 0; f < faces; ++f) {
    auto& c = map.m_corners[f];
    for (int k = 0; k < 3; ++k) c[std::size_t(k)] = map.m_weld[mesh.indices[3 * f + std::size_t(k)]];
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      ++map.m_degenerate;
      continue;
    }
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t from = c[k], to = c[(k + 1) % 3];
      const std::uint64_t lo = std::min(from, to), hi = std::max(from, to);
      halves.push_back({(lo << 32) | hi, f, from < to ? 1 : -1, k});
    }
  }
  std::sort(halves.begin(), halves.end(), [](const HalfEdge& l, const HalfEdge& r) {
    return l.key != r.key ? l.key < r.key : l.face < r.face;
  });

  map.m_edgeFaces.reserve(halves.size());
  for (std::size_t i = 0; i < halves.size();) {
    std::size_t j = i;
    Edge edge{std::uint32_t(halves[i].key >> 32), std::uint32_t(halves[i].key & 0xFFFFFFFFu),
              std::uint32_t(map.m_edgeFaces.size()), 0};
    const auto index = std::uint32_t(map.m_edges.size());
    for (; j < halves.size() && halves[j].key == halves[i].key; ++j) {
      map.m_edgeFaces.push_back({halves[j].face, halves[j].orientation});
      map.m_faceEdges[halves[j].face][halves[j].slot] = index;
    }
    edge.faceCount = std::uint32_t(j - i);
    map.m_edges.push_back(edge);
    ++map.m_counts[std::size_t(map.kind(edge))];
    i = j;
  }
  return map;
}

vec3 EdgeMap::faceNormal(std::uint32_t face) const {
  const auto& c = m_corners[face];
  const vec3 n = glm::cross(m_positions[c[1]] - m_positions[c[0]], m_positions[c[2]] - m_positions[c[0]]);
  const float len = glm::length(n);
  return len > 0.0f ? n / len : vec3(0.0f);
}

EdgeKind EdgeMap::kind(const Edge& edge) const {
  if (edge.faceCount == 1) return EdgeKind::Open;
  if (edge.faceCount > 2) return EdgeKind::NonManifold;
  const auto f = faces(edge);
  return f[0].orientation != f[1].orientation ? EdgeKind::Manifold : EdgeKind::Inconsistent;
}

bool EdgeMap::isClosedManifold() const {
  return m_degenerate == 0 && !m_edges.empty() && count(EdgeKind::Manifold) == m_edges.size();
}

std::size_t EdgeMap::borderLoops() const {
  // Union-find over the vertices of open edges: each connected chain is one hole.
  UnionFind sets(m_positions.size());
  const auto root = [&](std::uint32_t v) { return sets.find(v); };
  std::vector<bool> onBorder(m_positions.size(), false);
  for (const Edge& e : m_edges) {
    if (e.faceCount != 1) continue;
    onBorder[e.a] = onBorder[e.b] = true;
    sets.attach(root(e.a), root(e.b));
  }
  std::size_t loops = 0;
  for (std::uint32_t v = 0; v < sets.size(); ++v)
    if (onBorder[v] && root(v) == v) ++loops;
  return loops;
}

}  // namespace glint
