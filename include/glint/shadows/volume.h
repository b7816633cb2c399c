#pragma once
// glint/shadows/volume.h — shadow volume geometry from an edge map (no GL).
//
// Contents
//   CasterMode          how a caster's triangles bound its volume (closed, two-sided, naive)
//   ShadowVolume        CPU-built volume: side quads and caps as homogeneous triangles
//   buildShadowVolume   silhouette extraction by edge multiplicity, extrusion to infinity
//   ExtrusionMesh       the static mesh a vertex shader extrudes (WWDC 2003 session 212, ATI's method)
//   buildExtrusionMesh  every face with its own vertices and face normal, a degenerate
//                       quad on every edge
//
// Extrusion to infinity: a vertex p pushed away from the light L becomes the
// homogeneous point (p − L, 0), a direction, which the projection maps to the
// vanishing point of that direction. No "far enough" distance to choose, and with an
// infinite-far projection (or depth clamp) nothing is clipped.
//
// Robustness (the method, and why)
//   Each triangle on its own bounds a closed volume: itself as near cap, its
//   extrusion as far cap, three side quads. Summing those volumes gives a stencil
//   count equal to the number of triangles between the light and a point — right
//   for *any* triangle soup. Summing their side quads edge by edge, quads of faces on
//   both sides of an edge cancel, so each edge (a, b) keeps a multiplicity
//       m = Σ over its faces f of  o_f · s_f,
//   o_f = +1 if f runs a → b, −1 if b → a;  s_f is how the face counts:
//     Closed    s_f = 1 for light-facing faces, 0 for the others. On a closed mesh
//               m = ±1 exactly on the silhouette (the classic volume). On an open or
//               non-manifold mesh it is still watertight (hole and fin edges get a
//               quad), but light passing through a hole past back faces is missed.
//     TwoSided  s_f = +1 for light-facing, −1 for back-facing faces (which are
//               flipped): every triangle occludes. Silhouette edges of a closed
//               mesh get m = ±2 (stencil counts reach 2 per closed caster), open
//               edges ±1. Right for every mesh; twice the fill of Closed on closed ones.
//     Naive     the textbook rule: a quad on manifold edges whose two faces differ in
//               facing, nothing on open or non-manifold edges. Leaks (streaks across
//               the screen) on open meshes — shown on purpose by shadows/bunny/naive.
//   An edge with |m| > 1 gets |m| quads, oriented by the sign of m.
//   (Aldridge & Woods 2004, "Robust, geometry-independent shadow volumes".)
//   Caps: the counted faces (flipped if back-facing) as near caps, their extrusions
//   reversed as far caps.

#include "glint/core/math.h"
#include "glint/mesh/adjacency.h"

#include <cstdint>
#include <vector>

namespace glint::shadows {

enum class CasterMode {
  Auto,      ///< Closed for closed 2-manifold meshes, TwoSided for anything else
  Closed,    ///< light-facing faces only; exact for closed meshes, watertight for any
  TwoSided,  ///< every face occludes (back faces flipped); right for open/non-manifold meshes
  Naive      ///< textbook silhouettes that ignore open and non-manifold edges: leaks
};

/// Auto resolved for a mesh's edge map; other modes are returned unchanged.
CasterMode resolveCasterMode(CasterMode mode, const EdgeMap& map);

/// A CPU-built shadow volume in the caster's object space: triangles of 3 vertices,
/// w = 1 for points on the caster, w = 0 for directions to infinity. Front faces
/// (counter-clockwise) face out of the volume.
struct ShadowVolume {
  std::vector<vec4> vertices;      ///< side triangles first, then near caps, then far caps
  std::size_t sideTriangles = 0;   ///< 2 per side quad
  std::size_t capTriangles = 0;    ///< near + far caps (0 when caps were not requested)
  std::size_t silhouetteEdges = 0; ///< edges with a non-zero multiplicity
  std::size_t triangles() const { return vertices.size() / 3; }
};

/// Builds the volume of `map`'s mesh for a point light at `light` (same space as the
/// mesh). `caps`: also near and far caps (z-fail needs them; z-pass does not).
/// Faces exactly edge-on to the light count as back-facing. `mode` Auto is resolved.
ShadowVolume buildShadowVolume(const EdgeMap& map, vec3 light, CasterMode mode, bool caps);

/// The GPU method's static mesh: no light needed to build it. Vertex shader
/// (shaders/shadows/extrude.vert) leaves faces that face the light in place and
/// extrudes the others to infinity; the degenerate quads on edges between a kept
/// and an extruded face stretch into the volume's sides, the kept faces are the near
/// cap and the extruded ones the far cap — a closed volume, caps included.
struct ExtrusionMesh {
  std::vector<vec3> positions;     ///< 3 per face (faces do not share vertices)
  std::vector<vec3> faceNormals;   ///< the face normal, stored in each of its vertices
  std::vector<std::uint32_t> indices;  ///< faces and quads interleaved: each quad after its later face
  std::size_t faceTriangles = 0;   ///< faces (doubled, reversed copies included, when two-sided)
  std::size_t quadTriangles = 0;   ///< 2 per degenerate quad
  bool twoSided = false;
};

/// `twoSided` false needs a closed 2-manifold mesh (Error(Input) otherwise): faces and
/// one quad per edge. `twoSided` true adds a reversed copy of every face (normal
/// negated) — a closed thin shell around any surface — with quads joining the two
/// copies along open, non-manifold and inconsistently wound edges. Degenerate faces
/// are skipped.
ExtrusionMesh buildExtrusionMesh(const EdgeMap& map, bool twoSided);

}  // namespace glint::shadows
