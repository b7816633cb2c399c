// MikkTSpace-compatible tangents, written from the algorithm's description (see
// tangents.h). The steps and their order follow the reference closely where the
// order can change a result (edge pairing, group growth, summation order), so
// that glint's frames agree with other MikkTSpace implementations to float
// rounding. Quads are not handled: glint meshes are triangles.
#include "glint/mesh/tangents.h"

#include "glint/core/error.h"
#include "glint/core/hash.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <tuple>
#include <unordered_map>
#include <utility>

namespace glint {
namespace {

constexpr int kOrientPreserving = 1;  ///< UV winding is counter-clockwise (not mirrored)
constexpr int kGroupWithAny = 2;      ///< no usable UV mapping: joins any group that reaches it
constexpr int kDegenerate = 4;        ///< two corners coincide: takes its frame from neighbours

bool notZero(float x) { return std::fabs(x) > FLT_MIN; }
bool notZero(const vec3& v) { return notZero(v.x) || notZero(v.y) || notZero(v.z); }
vec3 normalizedOrZero(const vec3& v) { return notZero(v) ? v / glm::length(v) : v; }
vec3 projectOnPlane(const vec3& v, const vec3& n) { return normalizedOrZero(v - glm::dot(n, v) * n); }

struct TriInfo {
  vec3 os{0.0f};  ///< unit dP/du (zero when undefined)
  vec3 ot{0.0f};  ///< unit dP/dv (zero when undefined)
  int flags = kGroupWithAny;
  std::array<int, 3> neighbor{-1, -1, -1};  ///< triangle across edge (k, k+1)
  std::array<int, 3> group{-1, -1, -1};     ///< group of corner k
};

struct Group {
  std::uint32_t vertex = 0;  ///< welded vertex index the group is around
  bool orientPreserving = true;
  std::vector<int> faces;
};

/// Welded index per vertex: the first vertex with the same position, normal and UV (by
/// value: +0 and -0 are equal, as with float ==).
std::vector<std::uint32_t> weldVertices(const Mesh& mesh) {
  struct Key {
    std::array<float, 8> v;
    bool operator==(const Key& o) const { return v == o.v; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::size_t(Fnv1a().add(k.v).value());
    }
  };
  const auto canon = [](float f) { return f == 0.0f ? 0.0f : f; };
  std::unordered_map<Key, std::uint32_t, KeyHash> first;
  first.reserve(mesh.vertexCount());
  std::vector<std::uint32_t> weld(mesh.vertexCount());
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    const vec3& p = mesh.positions[i];
    const vec3& n = mesh.normals[i];
    const vec2& t = mesh.uvs[i];
    const Key key{{canon(p.x), canon(p.y), canon(p.z), canon(n.x), canon(n.y), canon(n.z), canon(t.x), canon(t.y)}};
    weld[i] = first.try_emplace(key, std::uint32_t(i)).first->second;
  }
  return weld;
}

TriInfo initTriangle(const Mesh& mesh, const std::uint32_t* tri, const std::uint32_t* welded) {
  TriInfo info;
  const vec3 &p0 = mesh.positions[tri[0]], &p1 = mesh.positions[tri[1]], &p2 = mesh.positions[tri[2]];
  if (welded[0] == welded[1] || welded[0] == welded[2] || welded[1] == welded[2] || p0 == p1 || p0 == p2 ||
      p1 == p2) {
    info.flags |= kDegenerate;
  }
  const vec2 &t0 = mesh.uvs[tri[0]], &t1 = mesh.uvs[tri[1]], &t2 = mesh.uvs[tri[2]];
  const float t21x = t1.x - t0.x, t21y = t1.y - t0.y, t31x = t2.x - t0.x, t31y = t2.y - t0.y;
  const vec3 d1 = p1 - p0, d2 = p2 - p0;
  const float signedAreaUv2 = t21x * t31y - t21y * t31x;
  // dP/du and dP/dv, each times the signed UV area.
  const vec3 os = t31y * d1 - t21y * d2;
  const vec3 ot = -t31x * d1 + t21x * d2;
  if (signedAreaUv2 > 0.0f) info.flags |= kOrientPreserving;
  if (notZero(signedAreaUv2)) {
    const float absArea = std::fabs(signedAreaUv2);
    const float lenOs = glm::length(os), lenOt = glm::length(ot);
    const float sign = signedAreaUv2 > 0.0f ? 1.0f : -1.0f;
    if (notZero(lenOs)) info.os = (sign / lenOs) * os;
    if (notZero(lenOt)) info.ot = (sign / lenOt) * ot;
    if (notZero(lenOs / absArea) && notZero(lenOt / absArea)) info.flags &= ~kGroupWithAny;
  }
  return info;
}

/// Pairs triangles across edges they traverse in opposite directions (consistent
/// winding). Edges are visited sorted by (min vertex, max vertex, triangle); with more
/// than two triangles on an edge, the first unpaired match wins.
void findNeighbors(const std::vector<std::uint32_t>& tris, const std::vector<int>& good, std::vector<TriInfo>& info) {
  struct Edge {
    std::uint32_t lo, hi;
    int tri;
  };
  std::vector<Edge> edges;
  edges.reserve(good.size() * 3);
  for (int t : good) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tris[3 * std::size_t(t) + std::size_t(k)];
      const std::uint32_t b = tris[3 * std::size_t(t) + std::size_t((k + 1) % 3)];
      edges.push_back({std::min(a, b), std::max(a, b), t});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return std::tie(x.lo, x.hi, x.tri) < std::tie(y.lo, y.hi, y.tri);
  });
  // Edge number k of triangle t joining a and b, and its direction in the triangle.
  const auto edgeOf = [&](int t, std::uint32_t a, std::uint32_t b, std::uint32_t& from, std::uint32_t& to) {
    const std::uint32_t* v = &tris[3 * std::size_t(t)];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t x = v[k], y = v[(k + 1) % 3];
      if ((x == a && y == b) || (x == b && y == a)) {
        from = x;
        to = y;
        return k;
      }
    }
    return -1;
  };
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    std::uint32_t fromA = 0, toA = 0;
    const int kA = edgeOf(e.tri, e.lo, e.hi, fromA, toA);
    if (kA < 0 || info[std::size_t(e.tri)].neighbor[std::size_t(kA)] != -1) continue;
    for (std::size_t j = i + 1; j < edges.size() && edges[j].lo == e.lo && edges[j].hi == e.hi; ++j) {
      std::uint32_t fromB = 0, toB = 0;
      const int kB = edgeOf(edges[j].tri, e.lo, e.hi, fromB, toB);
      if (kB >= 0 && fromB == toA && toB == fromA && info[std::size_t(edges[j].tri)].neighbor[std::size_t(kB)] == -1) {
        info[std::size_t(e.tri)].neighbor[std::size_t(kA)] = edges[j].tri;
        info[std::size_t(edges[j].tri)].neighbor[std::size_t(kB)] = e.tri;
        break;
      }
    }
  }
}

int cornerOf(const std::vector<std::uint32_t>& tris, int t, std::uint32_t vertex) {
  const std::uint32_t* v = &tris[3 * std::size_t(t)];
  return v[0] == vertex ? 0 : v[1] == vertex ? 1 : v[2] == vertex ? 2 : -1;
}

/// Grows a group around its vertex across shared edges, depth first (the edge after the
/// corner, then the edge before it), stopping at triangles of the other orientation.
void growGroup(const std::vector<std::uint32_t>& tris, std::vector<TriInfo>& info, std::vector<Group>& groups,
               int groupId, int start) {
  std::vector<int> stack{start};
  while (!stack.empty()) {
    const int t = stack.back();
    stack.pop_back();
    Group& group = groups[std::size_t(groupId)];
    TriInfo& ti = info[std::size_t(t)];
    const int k = cornerOf(tris, t, group.vertex);
    if (k < 0 || ti.group[std::size_t(k)] != -1) continue;
    if (ti.flags & kGroupWithAny) {
      // The first group to reach a UV-less triangle decides its orientation.
      if (ti.group[0] == -1 && ti.group[1] == -1 && ti.group[2] == -1) {
        ti.flags = (ti.flags & ~kOrientPreserving) | (group.orientPreserving ? kOrientPreserving : 0);
      }
    }
    if (((ti.flags & kOrientPreserving) != 0) != group.orientPreserving) continue;
    group.faces.push_back(t);
    ti.group[std::size_t(k)] = groupId;
    const int after = ti.neighbor[std::size_t(k)];
    const int before = ti.neighbor[std::size_t((k + 2) % 3)];
    if (before >= 0) stack.push_back(before);
    if (after >= 0) stack.push_back(after);  // popped first
  }
}

/// Angle-weighted average of the members' tangents at `vertex`.
vec3 evalTangent(const Mesh& mesh, const std::vector<std::uint32_t>& tris, const std::vector<TriInfo>& info,
                 const std::vector<int>& members, std::uint32_t vertex) {
  vec3 sum(0.0f);
  for (int t : members) {
    const TriInfo& ti = info[std::size_t(t)];
    if (ti.flags & kGroupWithAny) continue;
    const int k = cornerOf(tris, t, vertex);
    const vec3& n = mesh.normals[vertex];
    const vec3 os = projectOnPlane(ti.os, n);
    const std::uint32_t* v = &tris[3 * std::size_t(t)];
    const vec3& p0 = mesh.positions[v[(k + 2) % 3]];
    const vec3& p1 = mesh.positions[v[k]];
    const vec3& p2 = mesh.positions[v[(k + 1) % 3]];
    const vec3 e1 = projectOnPlane(p0 - p1, n), e2 = projectOnPlane(p2 - p1, n);
    const float angle = std::acos(std::clamp(glm::dot(e1, e2), -1.0f, 1.0f));
    sum += angle * os;
  }
  return normalizedOrZero(sum);
}

vec3 anyTangent(const vec3& n) {
  const vec3 axis = std::fabs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  const vec3 t = axis - glm::dot(axis, n) * n;
  return notZero(t) ? glm::normalize(t) : vec3(1.0f, 0.0f, 0.0f);
}

/// The groups: one per vertex and connected same-orientation fan, grown from the good
/// triangles in order; UV-less triangles never start a group but join the first one that
/// reaches them.
std::vector<Group> buildGroups(const std::vector<std::uint32_t>& tris, const std::vector<int>& good,
                               std::vector<TriInfo>& info) {
  std::vector<Group> groups;
  for (int t : good) {
    for (int k = 0; k < 3; ++k) {
      TriInfo& ti = info[std::size_t(t)];
      if ((ti.flags & kGroupWithAny) || ti.group[std::size_t(k)] != -1) continue;
      const int id = int(groups.size());
      groups.push_back({tris[3 * std::size_t(t) + std::size_t(k)], (ti.flags & kOrientPreserving) != 0, {}});
      growGroup(tris, info, groups, id, t);
    }
  }
  return groups;
}

/// Sets the frame of each group's corners from its subgroup's averaged tangent: within a
/// group, triangles whose tangents point exactly opposite form separate subgroups, and
/// identical member lists share a result.
void assignGroupTangents(const Mesh& mesh, const std::vector<std::uint32_t>& tris, const std::vector<TriInfo>& info,
                         const std::vector<Group>& groups, std::vector<vec4>& corners, std::vector<char>& assigned) {
  std::vector<int> members;
  std::vector<std::pair<std::vector<int>, vec3>> subgroups;
  for (const Group& group : groups) {
    subgroups.clear();
    const vec3& n = mesh.normals[group.vertex];
    for (int f : group.faces) {
      const vec3 os = projectOnPlane(info[std::size_t(f)].os, n), ot = projectOnPlane(info[std::size_t(f)].ot, n);
      members.clear();
      for (int g : group.faces) {
        const bool any = ((info[std::size_t(f)].flags | info[std::size_t(g)].flags) & kGroupWithAny) != 0;
        const vec3 os2 = projectOnPlane(info[std::size_t(g)].os, n);
        const vec3 ot2 = projectOnPlane(info[std::size_t(g)].ot, n);
        if (any || f == g || (glm::dot(os, os2) > -1.0f && glm::dot(ot, ot2) > -1.0f)) members.push_back(g);
      }
      std::sort(members.begin(), members.end());
      auto found = std::find_if(subgroups.begin(), subgroups.end(), [&](const auto& s) { return s.first == members; });
      if (found == subgroups.end()) {
        subgroups.emplace_back(members, evalTangent(mesh, tris, info, members, group.vertex));
        found = subgroups.end() - 1;
      }
      const std::size_t corner = 3 * std::size_t(f) + std::size_t(cornerOf(tris, f, group.vertex));
      const vec3 n0 = mesh.normals[mesh.indices[corner]];
      corners[corner] = vec4(notZero(found->second) ? found->second : anyTangent(n0), group.orientPreserving ? 1.0f : -1.0f);
      assigned[corner] = 1;
    }
  }
}

/// Frames for the corners no group set: a degenerate triangle's corner copies the first
/// good corner on the same vertex; any other gets an arbitrary tangent.
void fillUnassigned(const Mesh& mesh, const std::vector<std::uint32_t>& tris, const std::vector<TriInfo>& info,
                    const std::vector<int>& good, std::vector<vec4>& corners, const std::vector<char>& assigned) {
  std::unordered_map<std::uint32_t, std::size_t> firstGoodCorner;
  for (int t : good) {
    for (std::size_t k = 0; k < 3; ++k) firstGoodCorner.try_emplace(tris[3 * std::size_t(t) + k], 3 * std::size_t(t) + k);
  }
  for (std::size_t c = 0; c < corners.size(); ++c) {
    if (assigned[c]) continue;
    if (info[c / 3].flags & kDegenerate) {
      const auto it = firstGoodCorner.find(tris[c]);
      if (it != firstGoodCorner.end() && assigned[it->second]) {
        corners[c] = corners[it->second];
        continue;
      }
    }
    // Unreached UV-less corners and isolated degenerate triangles.
    corners[c] = vec4(anyTangent(mesh.normals[mesh.indices[c]]), 1.0f);
  }
}

}  // namespace

std::vector<vec4> computeCornerTangents(const Mesh& mesh) {
  mesh.validate("mesh for tangents");
  if (!mesh.hasNormals()) fail(ErrorKind::Input, "mesh for tangents: has no normals");
  if (!mesh.hasUvs()) fail(ErrorKind::Input, "mesh for tangents: has no UVs");

  const std::vector<std::uint32_t> weld = weldVertices(mesh);
  const std::size_t triCount = mesh.triangleCount();
  std::vector<std::uint32_t> tris(mesh.indices.size());
  for (std::size_t i = 0; i < tris.size(); ++i) tris[i] = weld[mesh.indices[i]];

  std::vector<TriInfo> info(triCount);
  std::vector<int> good;
  good.reserve(triCount);
  for (std::size_t t = 0; t < triCount; ++t) {
    info[t] = initTriangle(mesh, &mesh.indices[3 * t], &tris[3 * t]);
    if (!(info[t].flags & kDegenerate)) good.push_back(int(t));
  }
  findNeighbors(tris, good, info);

  // Groups: one per vertex and connected same-orientation fan; UV-less triangles never
  // start a group but join the first one that reaches them.
  const std::vector<Group> groups = buildGroups(tris, good, info);

  std::vector<vec4> corners(mesh.indices.size(), vec4(0.0f));
  std::vector<char> assigned(mesh.indices.size(), 0);
  // Within a group, triangles whose tangents point exactly opposite would form separate
  // subgroups (MikkTSpace's 180° threshold: cos > -1); identical member lists share a result.
  assignGroupTangents(mesh, tris, info, groups, corners, assigned);

  // Degenerate triangles copy the frame of the first good corner on the same vertex.
  fillUnassigned(mesh, tris, info, good, corners, assigned);
  return corners;
}

std::size_t generateTangents(Mesh& mesh) {
  const std::vector<vec4> corners = computeCornerTangents(mesh);
  const std::size_t original = mesh.vertexCount();
  mesh.tangents.assign(original, vec4(0.0f));
  std::vector<char> set(original, 0);
  // Extra copies of a vertex, by the frame they carry: (vertex, frame) -> new index.
  std::vector<std::vector<std::pair<vec4, std::uint32_t>>> copies(original);
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const std::uint32_t v = mesh.indices[c];
    if (!set[v]) {
      mesh.tangents[v] = corners[c];
      set[v] = 1;
      continue;
    }
    if (mesh.tangents[v] == corners[c]) continue;
    auto& list = copies[v];
    const auto it = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == corners[c]; });
    if (it != list.end()) {
      mesh.indices[c] = it->second;
      continue;
    }
    const auto copy = std::uint32_t(mesh.positions.size());
    mesh.positions.push_back(mesh.positions[v]);
    mesh.normals.push_back(mesh.normals[v]);
    mesh.uvs.push_back(mesh.uvs[v]);
    mesh.tangents.push_back(corners[c]);
    list.emplace_back(corners[c], copy);
    mesh.indices[c] = copy;
  }
  // Vertices no triangle uses still get a valid frame.
  for (std::size_t v = 0; v < original; ++v) {
    if (!set[v]) mesh.tangents[v] = vec4(anyTangent(mesh.normals[v]), 1.0f);
  }
  return mesh.vertexCount() - original;
}

vec3 TangentFrame::decode(const vec3& m) const {
  const vec3 v = m.x * tangent + m.y * bitangent + m.z * normal;
  const float len = glm::length(v);
  return len > 0.0f ? v / len : normal;
}

}  // namespace glint
