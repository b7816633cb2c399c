#pragma once
// glint/mesh/adjacency.h — the edge map: every edge of a mesh and the faces around it.
//
// Contents
//   EdgeKind        manifold, open, non-manifold, inconsistently oriented
//   Edge, EdgeFace  one undirected edge and one face using it (with the direction it runs)
//   EdgeMap         built from a Mesh: welded vertices, edges, faces per edge, edges per face
//
// Shadow volumes (render/shadows) find silhouettes here, and `glint mesh-info`
// reports what it finds. A mesh's vertices are split wherever normals or UVs
// differ (a cube has 24), so the map first *welds* vertices with bit-identical
// positions: topology is a property of positions only. glint's generators make
// coincident seam vertices bit-identical for this reason; an imported mesh whose
// seams differ in the last bit shows up here as open edges.
//
/// ```cpp run
/// #include <glint/core/log.h>
/// const glint::Mesh mesh = glint::makeTorus(1.0f, 0.35f, 16, 8);
/// const glint::EdgeMap map = glint::EdgeMap::build(mesh);
/// if (!map.isClosedManifold()) glint::log::warn("{} open edges", map.count(glint::EdgeKind::Open));
/// for (const glint::Edge& e : map.edges())
///   for (const glint::EdgeFace& f : map.faces(e)) {
///     const auto corners = map.corners(f.face);  // f.face runs e.a → e.b when f.orientation > 0
///   }
/// ```
//
// Edge cases
//   - A triangle with two corners at one welded position is *degenerate*: it has no
//     edges in the map (degenerateFaces() counts them) and its faceEdges are kNone.
//   - Faces keep the mesh's triangle numbering (face f = indices 3f .. 3f+2).

#include "glint/mesh/mesh.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace glint {

enum class EdgeKind {
  Manifold,     ///< exactly two faces, running the edge in opposite directions
  Open,         ///< one face: a border (hole) edge
  NonManifold,  ///< three or more faces meet here
  Inconsistent  ///< two faces running the edge in the same direction (flipped winding)
};

/// One face using an edge.
struct EdgeFace {
  std::uint32_t face = 0;  ///< triangle index in the mesh
  int orientation = 0;     ///< +1: the face's corners run a → b; −1: b → a
};

/// One undirected edge between two welded vertices.
struct Edge {
  std::uint32_t a = 0;          ///< welded vertex index, a < b
  std::uint32_t b = 0;          ///< welded vertex index
  std::uint32_t firstFace = 0;  ///< index of its first EdgeFace (use EdgeMap::faces)
  std::uint32_t faceCount = 0;  ///< faces using this edge (1 open, 2 manifold, 3+ non-manifold)
};

class EdgeMap {
public:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;  ///< "no edge" in faceEdges()

  EdgeMap() = default;
  /// Welds positions and builds the map. O(n log n) in the number of triangles.
  /// Error(Input) when mesh.validate() fails.
  static EdgeMap build(const Mesh& mesh);

  /// Welded positions (each distinct position once).
  const std::vector<vec3>& positions() const { return m_positions; }
  /// Welded index of every mesh vertex.
  const std::vector<std::uint32_t>& weld() const { return m_weld; }
  /// Welded corners of a face, in the mesh's winding order.
  std::array<std::uint32_t, 3> corners(std::uint32_t face) const { return m_corners[face]; }
  /// Unit geometric normal of a face (counter-clockwise front); zero for degenerate faces.
  vec3 faceNormal(std::uint32_t face) const;

  std::span<const Edge> edges() const { return m_edges; }
  /// The faces around an edge, each with the direction it runs along the edge.
  std::span<const EdgeFace> faces(const Edge& edge) const {
    return std::span<const EdgeFace>(m_edgeFaces).subspan(edge.firstFace, edge.faceCount);
  }
  /// The three edges of a face: edge k joins corners k and (k+1) % 3. kNone for degenerate faces.
  std::array<std::uint32_t, 3> faceEdges(std::uint32_t face) const { return m_faceEdges[face]; }
  EdgeKind kind(const Edge& edge) const;

  std::size_t faceCount() const { return m_corners.size(); }
  /// Edges of one kind.
  std::size_t count(EdgeKind kind) const { return m_counts[std::size_t(kind)]; }
  /// Triangles skipped because two corners weld to one vertex.
  std::size_t degenerateFaces() const { return m_degenerate; }
  /// Every edge manifold (no holes, no fins, consistent winding) and no degenerate faces.
  bool isClosedManifold() const;
  /// Connected chains of open edges: the number of holes (a loop of border edges each).
  std::size_t borderLoops() const;

private:
  std::vector<vec3> m_positions;
  std::vector<std::uint32_t> m_weld;
  std::vector<std::array<std::uint32_t, 3>> m_corners;
  std::vector<Edge> m_edges;
  std::vector<EdgeFace> m_edgeFaces;
  std::vector<std::array<std::uint32_t, 3>> m_faceEdges;
  std::array<std::size_t, 4> m_counts{};
  std::size_t m_degenerate = 0;
};

}  // namespace glint
