#pragma once
// glint/mesh/tangents.h — MikkTSpace-compatible tangent frames: the one tangent space
// of glint, shared by the normal-map baker and the renderer's normal-mapping shader.
//
// Contents
//   computeCornerTangents   one tangent per triangle corner (3 per triangle)
//   generateTangents        per-vertex tangents in a Mesh, splitting vertices where needed
//   TangentFrame            the per-pixel basis, and the exact encode/decode pair
//
// Why this matters. A tangent-space normal map stores normals relative to a frame
// (T, B, N) that the baking tool and the engine both derive from the low-poly mesh.
// If the two derivations differ in any detail the map decodes to wrong normals and
// seams and smudges appear (the ATI normal-mapper team lost a week to one float
// conversion). glint uses the convention of Morten Mikkelsen's MikkTSpace — the
// standard of Blender, Unity, Unreal, xNormal and glTF — so maps baked by glint
// work in those engines and maps baked by them work in glint.
//
// The algorithm (re-implemented here from its published description):
//   1. Vertices with bit-identical position, normal and UV are treated as one.
//   2. Each triangle gets a tangent dP/du and bitangent dP/dv from its UV mapping;
//      its UV-space winding says whether the mapping preserves orientation
//      (mirrored UVs do not).
//   3. Around every vertex, the triangles reached across shared edges that have the
//      same orientation form a group (a mirror seam or a UV-less gap splits groups).
//   4. A group's tangent is the average of its triangles' tangents, each projected
//      onto the plane of the vertex normal, normalized, and weighted by the
//      triangle's corner angle at the vertex; then normalized.
//   5. The bitangent sign is +1 for orientation-preserving groups, −1 for mirrored ones.
//   Degenerate triangles (two equal corners) copy the frame of another triangle at
//   the same vertex; triangles with zero UV area join whatever group reaches them.
//
// Reconstruction, in the shader and in the baker alike (MikkTSpace's "per pixel"
// rule): interpolate the vertex normal n and tangent t linearly WITHOUT normalizing,
// take b = sign · cross(n, t), and map a tangent-space normal m to
// normalize(m.x·t + m.y·b + m.z·n). The baker stores the exact inverse of that map
// (TangentFrame::encode), so decoding returns the baked normal to float precision.

#include "glint/core/math.h"
#include "glint/mesh/mesh.h"

#include <cstddef>
#include <vector>

namespace glint {

/// MikkTSpace tangents for every triangle corner: element 3·t + k belongs to corner k of
/// triangle t. xyz is the unit tangent (orthogonal to the corner's vertex normal), w = ±1 the
/// bitangent sign (bitangent = w · cross(normal, tangent)). Error(Input) when the mesh has no
/// normals or no UVs, or fails Mesh::validate(). A corner whose group has no usable UV
/// mapping at all gets a tangent orthogonal to its normal (MikkTSpace would leave it zero).
std::vector<vec4> computeCornerTangents(const Mesh& mesh);

/// Replaces mesh.tangents with MikkTSpace tangents, one per vertex. Where corners sharing a
/// vertex get different frames (mirrored UVs, UV-area-less regions, hard edges in UV space)
/// that vertex is duplicated, as glTF exporters do; positions, normals and UVs are copied,
/// so the mesh renders the same. Returns how many vertices were added. Same errors as
/// computeCornerTangents.
std::size_t generateTangents(Mesh& mesh);

/// The per-pixel tangent frame, built from interpolated (not normalized) vertex normal and
/// tangent, exactly as glint's normal-mapping shader builds it.
struct TangentFrame {
  vec3 tangent{1.0f, 0.0f, 0.0f};
  vec3 bitangent{0.0f, 1.0f, 0.0f};
  vec3 normal{0.0f, 0.0f, 1.0f};

  /// b = sign · cross(n, t), with sign = tangent.w (≥ 0 counts as +1).
  static TangentFrame fromInterpolated(const vec3& normal, const vec4& tangent) {
    const vec3 t(tangent);
    const float sign = tangent.w < 0.0f ? -1.0f : 1.0f;
    return {t, sign * glm::cross(normal, t), normal};
  }
  /// Tangent-space normal → unit normal in the frame's space: normalize(m.x t + m.y b + m.z n).
  vec3 decode(const vec3& m) const;
  /// The inverse of decode: the unit tangent-space vector m with decode(m) = normalize(v), for
  /// frames built by fromInterpolated (bitangent = ±cross(normal, tangent)). Exact even when
  /// the frame is not orthonormal (it solves the 3×3 system). For a singular
  /// frame (zero tangent, tangent parallel to the normal) it returns (0, 0, 1), which any
  /// decoder maps to the interpolated normal.
  vec3 encode(const vec3& v) const {
    // Solve [t b n] m = v. With b = ±cross(n, t) (fromInterpolated), Cramer's rule reduces to
    // dot products: m ∝ (|n|²(v·t) − (n·t)(v·n),  v·b,  |t|²(v·n) − (n·t)(v·t)), divided by
    // the Gram determinant |n|²|t|² − (n·t)² ≥ 0, which normalizing removes. Exact for the
    // skewed frames interpolation produces (tests/mesh/tangents_test.cpp). Inline: the baker
    // calls it once per sample.
    const float nn = glm::dot(normal, normal), tt = glm::dot(tangent, tangent), nt = glm::dot(normal, tangent);
    const float gram = nn * tt - nt * nt;
    if (!(gram > 1e-12f * nn * tt)) return vec3(0.0f, 0.0f, 1.0f);
    const float vt = glm::dot(v, tangent), vn = glm::dot(v, normal);
    const vec3 m(nn * vt - nt * vn, glm::dot(v, bitangent), tt * vn - nt * vt);
    const float len = glm::length(m);
    return len > 0.0f ? m * (1.0f / len) : vec3(0.0f, 0.0f, 1.0f);
  }
};

}  // namespace glint
