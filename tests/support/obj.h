#pragma once
// Meshes written as OBJ files for the command-line tests, and the bumpy sphere several of
// them bake from.
#include "glint/mesh/mesh.h"

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

namespace glint::testing {

/// Writes a mesh's OBJ lines (positions, and UVs / normals when present), its vertex numbers
/// starting after `base` vertices already in the file.
inline void writeObjLines(std::ostream& out, const Mesh& m, std::size_t base = 0) {
  for (const vec3& p : m.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const vec2& t : m.uvs) out << "vt " << t.x << ' ' << t.y << '\n';
  for (const vec3& n : m.normals) out << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    out << 'f';
    for (int k = 0; k < 3; ++k) {
      const std::size_t v = base + m.indices[i + std::size_t(k)] + 1;
      out << ' ' << v;
      if (m.hasUvs() || m.hasNormals()) out << '/' << (m.hasUvs() ? std::to_string(v) : "");
      if (m.hasNormals()) out << '/' << v;
    }
    out << '\n';
  }
}

/// Writes a mesh as OBJ.
inline void writeObj(const Mesh& m, const std::filesystem::path& path) {
  std::ofstream out(path);
  writeObjLines(out, m);
}

/// A unit sphere with bumps and pits of `depth` (9 waves each way): a high poly whose detail
/// a normal map of a plain sphere holds.
inline Mesh bumpySphere(float depth = 0.04f) {
  Mesh m = makeUvSphere(1.0f, 96, 48);
  for (vec3& p : m.positions) {
    const vec3 d = glm::normalize(p);
    p = d * (1.0f + depth * std::sin(9.0f * d.x) * std::sin(9.0f * d.y) * std::sin(9.0f * d.z));
  }
  computeNormals(m);
  return m;
}

}  // namespace glint::testing
