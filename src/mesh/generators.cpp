// Procedural meshes. All are centred at the origin, counter-clockwise seen from
// outside, with unit normals. Generators with UVs also emit tangents (xyz = dP/du,
// w = bitangent sign) so normal maps work on them without a separate pass.
//
// Seam and pole vertices are computed from the same wrapped angle as their twins,
// so coincident positions are bit-identical: no cracks when rendering, and the
// meshes are closed once positions are welded.
#include "glint/mesh/mesh.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace glint {
namespace {

/// Bitangent sign such that cross(n, t) * w points along dP/dv.
float bitangentSign(const vec3& n, const vec3& t, const vec3& dpdv) {
  return glm::dot(glm::cross(n, t), dpdv) < 0.0f ? -1.0f : 1.0f;
}

/// Two triangles for the quad a-b-c-d, given counter-clockwise seen from its front.
void addQuad(Mesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
}

std::uint32_t index(std::size_t i) { return static_cast<std::uint32_t>(i); }

}  // namespace

Mesh makePlane(float size, float uvScale) { return makeGrid(1, 1, size, uvScale); }

Mesh makeGrid(int cellsX, int cellsZ, float size, float uvScale) {
  if (cellsX < 1 || cellsZ < 1) fail(ErrorKind::Usage, "grid needs at least 1x1 cells, got {}x{}", cellsX, cellsZ);
  Mesh mesh;
  const float half = 0.5f * size;
  // Seen from above (+Y) with -Z up the screen, u runs along +X and v along -Z,
  // so a texture appears unmirrored and upright, origin at the near-left corner.
  for (int iz = 0; iz <= cellsZ; ++iz) {
    const float fz = float(iz) / float(cellsZ);
    for (int ix = 0; ix <= cellsX; ++ix) {
      const float fx = float(ix) / float(cellsX);
      mesh.positions.emplace_back(-half + size * fx, 0.0f, half - size * fz);
      mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
      mesh.uvs.emplace_back(uvScale * fx, uvScale * fz);
      mesh.tangents.emplace_back(1.0f, 0.0f, 0.0f, 1.0f);  // cross(+Y, +X) = -Z = dP/dv
    }
  }
  const auto at = [&](int ix, int iz) { return index(std::size_t(iz) * std::size_t(cellsX + 1) + std::size_t(ix)); };
  for (int iz = 0; iz < cellsZ; ++iz)
    for (int ix = 0; ix < cellsX; ++ix) addQuad(mesh, at(ix, iz), at(ix + 1, iz), at(ix + 1, iz + 1), at(ix, iz + 1));
  return mesh;
}

Mesh makeCube(float size) {
  struct Face {
    vec3 normal, right, up;  // right = dP/du, up = dP/dv, seen from outside
  };
  // Side faces keep +Y up; the top's "up" is -Z and the bottom's +Z, as if the
  // cube were unfolded around the front (+Z) face.
  static constexpr Face kFaces[] = {
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},    // +Z front
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},   // +X right
      {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},  // -Z back
      {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},   // -X left
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},   // +Y top
      {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},   // -Y bottom
  };
  static constexpr vec2 kCorners[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // counter-clockwise
  Mesh mesh;
  const float half = 0.5f * size;
  for (const Face& f : kFaces) {
    const auto base = index(mesh.positions.size());
    for (const vec2& uv : kCorners) {
      mesh.positions.push_back(half * (f.normal + (2.0f * uv.x - 1.0f) * f.right + (2.0f * uv.y - 1.0f) * f.up));
      mesh.normals.push_back(f.normal);
      mesh.uvs.push_back(uv);
      mesh.tangents.emplace_back(f.right, bitangentSign(f.normal, f.right, f.up));
    }
    addQuad(mesh, base, base + 1, base + 2, base + 3);
  }
  return mesh;
}

Mesh makeUvSphere(float radius, int segments, int rings) {
  if (segments < 3 || rings < 2) {
    fail(ErrorKind::Usage, "UV sphere needs at least 3 segments and 2 rings, got {} and {}", segments, rings);
  }
  Mesh mesh;
  // Longitude phi starts at +Z and turns towards +X, so with v pointing north the
  // surface frame (dP/du, dP/dv, outward normal) is right-handed: quads listed in
  // (u, v) order are counter-clockwise from outside and textures are unmirrored.
  const auto direction = [&](int ring, int seg) {
    const float theta = kPi * float(ring) / float(rings);  // 0 at the south pole
    const float phi = 2.0f * kPi * float(seg % segments) / float(segments);
    // Exact zeros at the poles so their vertices coincide bit for bit.
    const float s = (ring == 0 || ring == rings) ? 0.0f : std::sin(theta);
    const float c = ring == 0 ? -1.0f : ring == rings ? 1.0f : -std::cos(theta);
    return vec3(s * std::sin(phi), c, s * std::cos(phi));
  };
  const auto tangentAt = [&](float u) {
    const float phi = 2.0f * kPi * u;
    return vec3(std::cos(phi), 0.0f, -std::sin(phi));
  };
  const auto addVertex = [&](int ring, int seg, float u) {
    const vec3 n = direction(ring, seg);
    const float v = float(ring) / float(rings);
    const vec3 t = tangentAt(u);
    // dP/dv is the northward meridian direction; at the poles it is the limit
    // along this vertex's longitude u (meaningful because each pole vertex
    // belongs to exactly one column).
    const float theta = kPi * v, phi = 2.0f * kPi * u;
    const vec3 north(std::cos(theta) * std::sin(phi), std::sin(theta), std::cos(theta) * std::cos(phi));
    mesh.positions.push_back(radius * n);
    mesh.normals.push_back(n);
    mesh.uvs.emplace_back(u, v);
    mesh.tangents.emplace_back(t, bitangentSign(n, t, north));
  };

  // Layout: one vertex per column at each pole (u at the column centre, which
  // halves the texture shear there and avoids degenerate triangles), then
  // (segments + 1) vertices on each of the (rings - 1) inner rings, the last of
  // which duplicates the first at u = 1 for the texture seam.
  //   vertices  = 2 * segments + (rings - 1) * (segments + 1)
  //   triangles = 2 * segments * (rings - 1)
  for (int s = 0; s < segments; ++s) addVertex(0, s, (float(s) + 0.5f) / float(segments));
  const auto ringBase = index(mesh.positions.size());
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s <= segments; ++s) addVertex(r, s, float(s) / float(segments));
  const auto northBase = index(mesh.positions.size());
  for (int s = 0; s < segments; ++s) addVertex(rings, s, (float(s) + 0.5f) / float(segments));

  const auto at = [&](int r, int s) { return ringBase + index(std::size_t(r - 1) * std::size_t(segments + 1) + std::size_t(s)); };
  for (int s = 0; s < segments; ++s) {
    mesh.indices.insert(mesh.indices.end(), {index(std::size_t(s)), at(1, s + 1), at(1, s)});
    mesh.indices.insert(mesh.indices.end(), {at(rings - 1, s), at(rings - 1, s + 1), northBase + index(std::size_t(s))});
  }
  for (int r = 1; r < rings - 1; ++r)
    for (int s = 0; s < segments; ++s) addQuad(mesh, at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s));
  return mesh;
}

Mesh makeIcosphere(float radius, int subdivisions) {
  if (subdivisions < 0) fail(ErrorKind::Usage, "icosphere subdivisions must be >= 0, got {}", subdivisions);
  // Icosahedron from three orthogonal golden rectangles; faces counter-clockwise
  // seen from outside. Directions are kept unit length and only scaled by the
  // radius at the end, so every vertex is one rounding away from the sphere.
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<vec3> dirs = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                            {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (vec3& d : dirs) d = glm::normalize(d);
  std::vector<std::uint32_t> faces = {0, 11, 5, 0, 5,  1,  0,  1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                      4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9,  4,  3, 4,  2,  3, 2, 6, 3,
                                      6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};

  for (int level = 0; level < subdivisions; ++level) {
    // Each edge is split once and its midpoint shared by both neighbouring faces
    // (keyed by the sorted vertex pair), which keeps the mesh watertight.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const std::pair<std::uint32_t, std::uint32_t> key = std::minmax(a, b);
      const auto [it, inserted] = midpoints.try_emplace(key, index(dirs.size()));
      if (inserted) dirs.push_back(glm::normalize(dirs[a] + dirs[b]));
      return it->second;
    };
    std::vector<std::uint32_t> next;
    next.reserve(faces.size() * 4);
    for (std::size_t i = 0; i < faces.size(); i += 3) {
      const std::uint32_t a = faces[i], b = faces[i + 1], c = faces[i + 2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    faces = std::move(next);
  }
  // vertices = 10 * 4^n + 2, triangles = 20 * 4^n
  Mesh mesh;
  mesh.positions.reserve(dirs.size());
  for (const vec3& d : dirs) mesh.positions.push_back(radius * d);
  mesh.normals = std::move(dirs);
  mesh.indices = std::move(faces);
  return mesh;
}

Mesh makeTorus(float majorRadius, float minorRadius, int segments, int sides) {
  if (segments < 3 || sides < 3) {
    fail(ErrorKind::Usage, "torus needs at least 3 segments and 3 sides, got {} and {}", segments, sides);
  }
  Mesh mesh;
  // u goes around +Y (phi, from +Z towards +X, like the UV sphere), v around the
  // tube (theta, starting at the outer equator and rising first). At the outer
  // equator dP/du = +X, dP/dv = +Y, normal +Z: a right-handed frame, so (u, v)
  // ordered quads are counter-clockwise from outside.
  // vertices = (segments + 1) * (sides + 1), triangles = 2 * segments * sides
  for (int j = 0; j <= sides; ++j) {
    const float v = float(j) / float(sides);
    const float theta = 2.0f * kPi * float(j % sides) / float(sides);
    const float ct = std::cos(theta), st = std::sin(theta);
    for (int i = 0; i <= segments; ++i) {
      const float u = float(i) / float(segments);
      const float phi = 2.0f * kPi * float(i % segments) / float(segments);
      const float cp = std::cos(phi), sp = std::sin(phi);
      const vec3 n(ct * sp, st, ct * cp);
      const vec3 tangent(cp, 0.0f, -sp);
      const vec3 dpdv(-st * sp, ct, -st * cp);
      mesh.positions.push_back(vec3(majorRadius * sp, 0.0f, majorRadius * cp) + minorRadius * n);
      mesh.normals.push_back(n);
      mesh.uvs.emplace_back(u, v);
      mesh.tangents.emplace_back(tangent, bitangentSign(n, tangent, dpdv));
    }
  }
  const auto at = [&](int i, int j) { return index(std::size_t(j) * std::size_t(segments + 1) + std::size_t(i)); };
  for (int j = 0; j < sides; ++j)
    for (int i = 0; i < segments; ++i) addQuad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  return mesh;
}

}  // namespace glint
