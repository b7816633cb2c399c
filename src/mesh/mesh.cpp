// Mesh operations that do not create geometry: bounds, validation, merging,
// transforms and normal generation.
#include "glint/mesh/mesh.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <utility>

namespace glint {

Bounds Mesh::bounds() const {
  if (positions.empty()) return Bounds{};
  Bounds b{positions.front(), positions.front()};
  for (const vec3& p : positions) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  return b;
}

void Mesh::validate(const std::string& what) const {
  // Checked in this order so the message names the most fundamental problem: a
  // ragged index list makes "triangle N" meaningless, and out-of-range indices
  // would make any later per-triangle check read out of bounds.
  if (indices.size() % 3 != 0) {
    fail(ErrorKind::Input, "{}: index count {} is not a multiple of 3", what, indices.size());
  }
  if (indices.empty()) fail(ErrorKind::Input, "{}: has no triangles", what);
  const std::size_t n = positions.size();
  // The largest index first, in a branch-free loop (meshes of millions of triangles are
  // checked on every load: 1.8 ms for 786k corners); the offender is looked for only then.
  std::uint32_t largest = 0;
  for (const std::uint32_t index : indices) largest = std::max(largest, index);
  for (std::size_t i = 0; largest >= n && i < indices.size(); ++i) {
    if (indices[i] >= n) {
      fail(ErrorKind::Input, "{}: index {} (triangle {}) is {}, out of range for {} vertices", what, i,
           i / 3, indices[i], n);
    }
  }
  const auto checkSize = [&](std::size_t size, const char* name) {
    if (size != 0 && size != n) {
      fail(ErrorKind::Input, "{}: {} {} for {} vertices (must be 0 or one per vertex)", what, size, name,
           n);
    }
  };
  checkSize(normals.size(), "normals");
  checkSize(uvs.size(), "uvs");
  checkSize(tangents.size(), "tangents");
  // Likewise: |x| ≤ FLT_MAX is false for infinities and NaN.
  bool finite = true;
  for (const vec3& p : positions) {
    finite &= (std::fabs(p.x) <= FLT_MAX) & (std::fabs(p.y) <= FLT_MAX) & (std::fabs(p.z) <= FLT_MAX);
  }
  for (std::size_t i = 0; !finite && i < n; ++i) {
    const vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      fail(ErrorKind::Input, "{}: position {} is not finite ({}, {}, {})", what, i, p.x, p.y, p.z);
    }
  }
}

void Mesh::append(const Mesh& other) {
  // Appending to an empty mesh is how meshes get accumulated (the importer does
  // it), so an empty mesh takes the other's attributes instead of dropping them.
  if (positions.empty() && indices.empty()) {
    *this = other;
    return;
  }
  const auto base = static_cast<std::uint32_t>(positions.size());
  // An attribute survives only if both sides have it; padding the missing side
  // with made-up values would silently produce wrong shading.
  const auto merge = [](auto& mine, const auto& theirs) {
    if (mine.empty() || theirs.empty()) {
      mine.clear();
    } else {
      mine.insert(mine.end(), theirs.begin(), theirs.end());
    }
  };
  merge(normals, other.normals);
  merge(uvs, other.uvs);
  merge(tangents, other.tangents);
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  indices.reserve(indices.size() + other.indices.size());
  for (std::uint32_t i : other.indices) indices.push_back(i + base);
}

void Mesh::transform(const mat4& m) {
  const mat3 linear(m);
  // Normals are covectors: they stay perpendicular to the surface only under the
  // inverse transpose. Tangents lie in the surface, so they take the linear part
  // itself (which keeps dot(T, N) = 0 under non-uniform scale).
  const mat3 normalMatrix = glm::transpose(glm::inverse(linear));
  const float det = glm::determinant(linear);
  const bool mirrored = det < 0.0f;

  for (vec3& p : positions) p = vec3(m * vec4(p, 1.0f));
  for (vec3& n : normals) {
    const vec3 t = normalMatrix * n;
    const float len = glm::length(t);
    n = len > 0.0f ? t / len : n;
  }
  for (vec4& t : tangents) {
    const vec3 v = linear * vec3(t);
    const float len = glm::length(v);
    // A mirror flips the handedness of the (T, B, N) frame; the sign in w
    // reconstructs the bitangent, so it must flip too.
    t = vec4(len > 0.0f ? v / len : vec3(t), mirrored ? -t.w : t.w);
  }
  // A mirror also turns counter-clockwise triangles clockwise; swapping two
  // corners keeps front faces pointing the same way as the normals.
  if (mirrored) {
    for (std::size_t i = 0; i + 2 < indices.size(); i += 3) std::swap(indices[i + 1], indices[i + 2]);
  }
}

void computeNormals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), vec3(0.0f));
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const std::uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
    // The unnormalized cross product has length 2 * area, so summing it weights
    // each face by its area for free (small slivers barely count).
    const vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    mesh.normals[a] += n;
    mesh.normals[b] += n;
    mesh.normals[c] += n;
  }
  for (vec3& n : mesh.normals) {
    const float len = glm::length(n);
    // Unreferenced vertices or ones whose faces cancel out still need a unit
    // normal (the attribute contract); +Y is as good as any and is harmless.
    n = len > 0.0f ? n / len : vec3(0.0f, 1.0f, 0.0f);
  }
}

}  // namespace glint
