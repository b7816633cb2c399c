#pragma once
// One receiver (an input triangle A) cut by the far beams of its occluders, for every
// light: WWDC 2003 session 212's inner loop, kept exact.
//
// A is held as a planar subdivision (half-edges) of convex faces. Each face edge lies on
// a *line*: one of A's three edges or a plane met with A's plane. Every vertex is named by
// the lines that meet there (exact.h), so a split is decided by the exact side of each
// vertex against the cutting plane — the original planes of B and the light, never a
// rounded vertex of an earlier split. Splitting a face also inserts the new vertex into
// the neighbouring face's edge, so the subdivision has no T-junctions inside A.
//
// For each light and each occluder B (from the BVH query of A's near beam), B's far beam
// on A is the intersection of four open half-spaces: inside the three planes through the
// light and B's edges, and beyond B's plane. A face that meets all four with positive
// area is split along those of them that cross it; the part inside is shadowed for that
// light. Faces already shadowed for a light are not cut again by its occluders. Finally
// adjacent faces with the same light mask are merged while their union stays convex (the
// talk's "optimization step"), and each region of one mask is triangulated again with
// only the vertices where its outline turns or meets another outline (regions.h).
#include "candidates.h"
#include "exact.h"
#include "regions.h"

#include <array>
#include <atomic>
#include <span>
#include <cstdint>
#include <utility>
#include <vector>

namespace glint::cut {

using LightMask = std::uint32_t;

/// The scene as the receivers see it, shared read-only.
struct SceneData {
  SceneData(std::vector<dvec3> points) : geometry(std::move(points)) {}
  exact::Geometry geometry;                                ///< welded input points, then the lights
  std::vector<std::array<std::uint32_t, 3>> triangles;     ///< welded corners, counter-clockwise
  std::vector<std::uint8_t> usable;                        ///< 1: positive area (cut as receiver, casts shadows)
  std::vector<std::uint32_t> component;                    ///< connected surface of each triangle (edge-joined)
  /// Per surface: bit l set when the surface is the closed boundary of a convex solid and
  /// light l lies outside it. Then only its faces that face the light can shadow anything
  /// (a segment leaving the solid towards the light exits through one of them), and its
  /// faces turned away are wholly in its own shadow.
  std::vector<LightMask> convexOutside;
  TriangleBvh bvh;                                         ///< over the usable triangles
  std::uint32_t lightBase = 0;                             ///< point id of light 0
  int lightCount = 0;
  double radius = 1.0;                                     ///< bounds |coordinate| of every point (relaxations)
};

/// Corner flags in ReceiverPieces::cornerFlags.
enum CornerFlag : std::uint8_t {
  kEdgeMask = 3,       ///< bits 0–1: the edge of A the polygon edge leaving this corner lies on; 3: inside A
  kInterior = 3,
  kStraight = 4,       ///< the corner lies on a straight line between its neighbours (no turn)
};

/// A receiver's pieces after merging, before shared edges are made consistent.
struct ReceiverPieces {
  std::vector<exact::VertexDef> vertices;   ///< the vertices the polygons use
  std::vector<dvec3> positions;             ///< their positions, to about a double's precision
  std::vector<std::uint32_t> polygonStart;  ///< polygon p: corners[polygonStart[p] .. polygonStart[p+1])
  std::vector<std::uint32_t> corners;       ///< indices into vertices, counter-clockwise
  std::vector<std::uint8_t> cornerFlags;    ///< CornerFlag bits per corner
  std::vector<LightMask> masks;             ///< per polygon: bit l set when light l reaches it
  void clear();
};

struct ReceiverStats {
  std::uint64_t candidates = 0;  ///< triangles from the near-beam query
  std::uint64_t occluders = 0;   ///< candidates whose far beam may reach the receiver
  std::uint64_t clippedPairs = 0;  ///< (face, far beam) pairs tested exactly
  std::uint64_t cuts = 0;        ///< of those, the ones that shadowed a part of a face
  std::uint64_t splits = 0;      ///< face splits
  std::uint64_t facesBeforeMerge = 0;
  std::uint64_t grazing = 0;     ///< (receiver, light) pairs with the light in the receiver's plane
  std::uint64_t selfShadowed = 0;  ///< (receiver, light) pairs in their convex solid's own shadow
  exact::PredicateStats predicates;
  void add(const ReceiverStats& o);
};

class ReceiverCutter {
public:
  explicit ReceiverCutter(const SceneData& scene, const std::atomic<bool>* cancel = nullptr);
  /// Cuts input triangle `face` (usable) for every light.
  void cut(std::uint32_t face, ReceiverPieces& out, ReceiverStats& stats);

private:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  struct HalfEdge {
    std::uint32_t origin = 0, next = 0, prev = 0, twin = kNone, face = 0;
    std::int32_t line = 0;  ///< < 0: edge −1−line of A; ≥ 0: index into m_planes
    std::int8_t inside = 0; ///< sign of the line's plane on this edge's face side
    bool alive = true;
  };
  struct Face {
    std::uint32_t edge = 0;
    LightMask mask = 0;
    glm::dvec2 lo{0.0}, hi{0.0};  ///< box of the face in A's projection (rigorous: vertex boxes)
    bool alive = true;
  };
  struct HalfSpace {
    std::uint32_t plane = 0;
    int sign = 0;  ///< inside: sign of plane value == sign
  };
  struct Occluder {
    std::uint32_t triangle = 0;
    std::array<HalfSpace, 4> halfSpaces;
    std::array<glm::dvec4, 4> approx;  ///< the four planes in double, outside positive, relaxed
    glm::dvec2 lo, hi;
    double area = 0.0;
  };
  /// An index of the planes or vertices of one receiver by name: open addressing over
  /// (hash, index) slots. Cleared in time proportional to what it holds, not to its size:
  /// a receiver clears it, and most receivers hold a few dozen names.
  class NameIndex {
  public:
    /// The index of the entry equal to the one hashed, by `equal(index)`; else `fresh`,
    /// which is recorded.
    template <typename Equal>
    std::uint32_t find(std::uint64_t hash, Equal&& equal, std::uint32_t fresh);
    void clear();

  private:
    void grow();
    std::vector<std::pair<std::uint32_t, std::uint32_t>> m_slots;  ///< (hash, index + 1); 0: empty
    std::vector<std::uint32_t> m_used;
  };

  void reset(std::uint32_t face);
  std::uint32_t planeIndex(const exact::PlaneDef& def, int& orientation);
  std::uint32_t vertexIndex(const exact::VertexDef& def);
  exact::VertexDef meet(std::int32_t line, std::uint32_t plane) const;
  glm::dvec2 project(const exact::Range* box, bool upper) const;
  void updateBox(std::uint32_t face);
  void classify(const std::vector<std::uint32_t>& vertices, const HalfSpace& h, std::vector<int>& out);
  bool findOccluders(int light, std::vector<Occluder>& out, ReceiverStats& stats);
  /// Shadows the part of face f inside all half-spaces (for light bit `bit`); true when
  /// it had one.
  bool cutFace(std::uint32_t f, const Occluder& o, LightMask bit, ReceiverStats& stats);
  bool separated(std::uint32_t f, const Occluder& o) const;
  std::uint32_t splitFace(std::uint32_t f, const HalfSpace& h, ReceiverStats& stats);
  std::uint32_t splitEdge(std::uint32_t e, std::uint32_t vertex);
  void merge();
  bool convexAt(std::uint32_t e);
  void dropStraightVertex(std::uint32_t incoming);
  bool straight(std::uint32_t incoming, std::uint32_t outgoing);
  void emit(ReceiverPieces& out);
  /// Appends a polygon: corners (vertex ids) with their CornerFlags.
  void emitPolygon(ReceiverPieces& out, LightMask mask, std::span<const std::uint32_t> vertices,
                   std::span<const std::uint8_t> flags);
  /// The faces as they are, every vertex kept (when a region cannot be triangulated).
  void emitFaces(ReceiverPieces& out);
  bool boundary(std::uint32_t e) const;

  const SceneData& m_scene;
  const exact::Geometry& m_g;
  const std::atomic<bool>* m_cancel;
  exact::PredicateStats* m_pstats = nullptr;

  std::uint32_t m_face = 0;
  std::array<std::uint32_t, 3> m_corner{};
  exact::PlaneRec m_plane;
  int m_axisU = 0, m_axisV = 1;
  std::vector<exact::PlaneRec> m_planes;
  NameIndex m_planeIndex;
  std::vector<exact::VertexRec> m_vertices;
  NameIndex m_vertexIndex;
  std::vector<HalfEdge> m_edges;
  std::vector<Face> m_faces;
  // scratch
  std::vector<std::uint32_t> m_candidates, m_polyV, m_nextV;
  std::vector<std::int32_t> m_polyLine, m_nextLine;
  std::vector<int> m_signs;
  std::vector<const exact::VertexRec*> m_recs;
  std::vector<Occluder> m_occluders;
  std::vector<std::uint32_t> m_lit, m_nextLit;  ///< faces still lit by the current light
  // emit: regions and their outlines
  RegionTriangulator m_triangulator;
  std::vector<std::uint32_t> m_local, m_region, m_regionFaces, m_regionStart, m_stack;
  std::vector<std::uint8_t> m_degree, m_onEdge, m_visited;
  std::vector<std::uint32_t> m_loopEdges, m_loopVertices, m_loopStart;
  ConvexPieces m_pieces;
  std::vector<std::uint8_t> m_polygonFlags;
};

}  // namespace glint::cut
