// Shadow volume construction: CPU silhouettes by edge multiplicity, and the static
// mesh for GPU extrusion (see volume.h for the method).
#include "glint/shadows/volume.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace glint::shadows {

CasterMode resolveCasterMode(CasterMode mode, const EdgeMap& map) {
  if (mode != CasterMode::Auto) return mode;
  return map.isClosedManifold() ? CasterMode::Closed : CasterMode::TwoSided;
}

ShadowVolume buildShadowVolume(const EdgeMap& map, vec3 light, CasterMode requested, bool caps) {
  const CasterMode mode = resolveCasterMode(requested, map);
  const auto& pos = map.positions();
  const std::size_t faces = map.faceCount();

  // Facing per face: +1 towards the light, −1 away (edge-on counts as away), 0 degenerate.
  std::vector<std::int8_t> facing(faces, 0);
  for (std::uint32_t f = 0; f < faces; ++f) {
    if (map.faceEdges(f)[0] == EdgeMap::kNone) continue;
    const vec3 n = map.faceNormal(f);
    facing[f] = glm::dot(n, light - pos[map.corners(f)[0]]) > 0.0f ? 1 : -1;
  }
  // How a face counts (s_f in volume.h).
  const auto weight = [&](std::uint32_t f) -> int {
    if (mode == CasterMode::TwoSided) return facing[f];
    return facing[f] > 0 ? 1 : 0;
  };
  const auto extruded = [&](vec3 p) { return vec4(p - light, 0.0f); };

  ShadowVolume volume;
  std::vector<vec4>& out = volume.vertices;
  // Side quad for an edge run from → to by a light-facing face: (from, from∞, to∞), (from, to∞, to).
  const auto emitQuad = [&](vec3 from, vec3 to) {
    const vec4 f(from, 1.0f), t(to, 1.0f), fi = extruded(from), ti = extruded(to);
    out.insert(out.end(), {f, fi, ti, f, ti, t});
  };
  for (const Edge& e : map.edges()) {
    int m = 0;
    if (mode == CasterMode::Naive) {
      if (map.kind(e) != EdgeKind::Manifold) continue;
      const auto fs = map.faces(e);
      if (facing[fs[0].face] == facing[fs[1].face]) continue;
      m = facing[fs[0].face] > 0 ? fs[0].orientation : fs[1].orientation;
    } else {
      for (const EdgeFace& f : map.faces(e)) m += f.orientation * weight(f.face);
    }
    if (m == 0) continue;
    ++volume.silhouetteEdges;
    const vec3 a = pos[e.a], b = pos[e.b];
    for (int k = 0; k < std::abs(m); ++k) m > 0 ? emitQuad(a, b) : emitQuad(b, a);
  }
  volume.sideTriangles = out.size() / 3;
  if (!caps) return volume;

  // Near caps, then far caps (reversed so they face away from the light, out of the volume).
  for (int pass = 0; pass < 2; ++pass) {
    for (std::uint32_t f = 0; f < faces; ++f) {
      const int w = mode == CasterMode::Naive ? (facing[f] > 0 ? 1 : 0) : weight(f);
      if (w == 0) continue;
      auto c = map.corners(f);
      if (w < 0) std::swap(c[1], c[2]);  // a counted back face, flipped to face the light
      const vec3 p0 = pos[c[0]], p1 = pos[c[1]], p2 = pos[c[2]];
      if (pass == 0) out.insert(out.end(), {vec4(p0, 1.0f), vec4(p1, 1.0f), vec4(p2, 1.0f)});
      else out.insert(out.end(), {extruded(p0), extruded(p2), extruded(p1)});
    }
  }
  volume.capTriangles = out.size() / 3 - volume.sideTriangles;
  return volume;
}

namespace {

/// Every face's three vertices with its normal (vertex of face f's corner k: 3·slot(f) + k;
/// the reversed copy's vertices follow all faces, with the normal negated). Returns the
/// faces' slots (kNone for a face without edges) and sets `used` to how many faces have one.
std::vector<std::uint32_t> addFaces(const EdgeMap& map, bool twoSided, ExtrusionMesh& mesh, std::uint32_t& used) {
  const std::size_t faces = map.faceCount();
  // Vertex of face f's corner k: 3·slot(f) + k; the reversed copy's vertices follow all faces.
  std::vector<std::uint32_t> slot(faces, EdgeMap::kNone);
  used = 0;
  for (std::uint32_t f = 0; f < faces; ++f)
    if (map.faceEdges(f)[0] != EdgeMap::kNone) slot[f] = used++;
  const int copies = twoSided ? 2 : 1;
  mesh.positions.resize(std::size_t(3) * used * std::size_t(copies));
  mesh.faceNormals.resize(mesh.positions.size());
  for (std::uint32_t f = 0; f < faces; ++f) {
    if (slot[f] == EdgeMap::kNone) continue;
    const vec3 n = map.faceNormal(f);
    for (std::uint32_t k = 0; k < 3; ++k) {
      const vec3 p = map.positions()[map.corners(f)[k]];
      mesh.positions[3 * slot[f] + k] = p;
      mesh.faceNormals[3 * slot[f] + k] = n;
      if (twoSided) {
        mesh.positions[3 * (used + slot[f]) + k] = p;
        mesh.faceNormals[3 * (used + slot[f]) + k] = -n;
      }
    }
    const std::uint32_t v = 3 * slot[f];
    mesh.indices.insert(mesh.indices.end(), {v, v + 1, v + 2});
    if (twoSided) {
      const std::uint32_t r = 3 * (used + slot[f]);
      mesh.indices.insert(mesh.indices.end(), {r, r + 2, r + 1});
    }
  }
  return slot;
}

/// A degenerate quad on every edge between the two faces that share it (a manifold edge;
/// the reversed sheet's too), or between a face and its reversed copy (any other edge,
/// reached only when two-sided).
void addQuads(const EdgeMap& map, bool twoSided, const std::vector<std::uint32_t>& slot, std::uint32_t used,
              ExtrusionMesh& mesh) {
  // The vertex of (copy of) face f at welded vertex w.
  const auto vertexOf = [&](std::uint32_t f, std::uint32_t w, bool reversed) {
    const auto c = map.corners(f);
    const std::uint32_t k = c[0] == w ? 0 : c[1] == w ? 1 : 2;
    return 3 * ((reversed ? used : 0) + slot[f]) + k;
  };
  // A degenerate quad between face A (running from → to) and face B on the same edge.
  const auto quad = [&](std::uint32_t aFrom, std::uint32_t aTo, std::uint32_t bFrom, std::uint32_t bTo) {
    mesh.indices.insert(mesh.indices.end(), {aFrom, bFrom, bTo, aFrom, bTo, aTo});
  };
  for (const Edge& e : map.edges()) {
    const auto fs = map.faces(e);
    if (map.kind(e) == EdgeKind::Manifold) {
      // A runs the edge from → to; B runs it back.
      const EdgeFace A = fs[0].orientation > 0 ? fs[0] : fs[1];
      const EdgeFace B = fs[0].orientation > 0 ? fs[1] : fs[0];
      quad(vertexOf(A.face, e.a, false), vertexOf(A.face, e.b, false), vertexOf(B.face, e.a, false),
           vertexOf(B.face, e.b, false));
      // The reversed sheet: B' runs a → b, A' runs b → a.
      if (twoSided)
        quad(vertexOf(B.face, e.a, true), vertexOf(B.face, e.b, true), vertexOf(A.face, e.a, true),
             vertexOf(A.face, e.b, true));
      continue;
    }
    // Open, non-manifold or inconsistent (only reached when two-sided): close each face
    // against its own reversed copy along this edge.
    for (const EdgeFace& f : fs) {
      const std::uint32_t from = f.orientation > 0 ? e.a : e.b, to = f.orientation > 0 ? e.b : e.a;
      quad(vertexOf(f.face, from, false), vertexOf(f.face, to, false), vertexOf(f.face, from, true),
           vertexOf(f.face, to, true));
    }
  }
}

/// For the vertex cache: each quad right after the later of its two faces, so that the
/// four vertices it uses were shaded a few triangles before (vertices are numbered by
/// face, faces keep the mesh's order). Counting in the stencil is order-free; the picture
/// is the same. Without this the quads come after every face and re-shade each vertex.
void orderForVertexCache(std::uint32_t used, ExtrusionMesh& mesh) {
  const std::size_t triangles = mesh.indices.size() / 3;
  if (used == 0) return;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order(triangles);  // (face slot, triangle)
  for (std::size_t t = 0; t < triangles; ++t) {
    std::uint32_t face = 0;
    for (int k = 0; k < 3; ++k) face = std::max(face, (mesh.indices[3 * t + std::size_t(k)] / 3) % used);
    order[t] = {face, std::uint32_t(t)};
  }
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::uint32_t> indices(mesh.indices.size());
  for (std::size_t i = 0; i < triangles; ++i)
    for (int k = 0; k < 3; ++k) indices[3 * i + std::size_t(k)] = mesh.indices[3 * std::size_t(order[i].second) + std::size_t(k)];
  mesh.indices = std::move(indices);
}

}  // namespace

ExtrusionMesh buildExtrusionMesh(const EdgeMap& map, bool twoSided) {
  if (!twoSided && !map.isClosedManifold())
    fail(ErrorKind::Input, "GPU extrusion without two-sided casters needs a closed 2-manifold mesh "
                           "({} open, {} non-manifold, {} inconsistent edges)",
         map.count(EdgeKind::Open), map.count(EdgeKind::NonManifold), map.count(EdgeKind::Inconsistent));
  ExtrusionMesh mesh;
  mesh.twoSided = twoSided;
  std::uint32_t used = 0;
  const std::vector<std::uint32_t> slot = addFaces(map, twoSided, mesh, used);
  mesh.faceTriangles = mesh.indices.size() / 3;
  addQuads(map, twoSided, slot, used, mesh);
  mesh.quadTriangles = mesh.indices.size() / 3 - mesh.faceTriangles;
  orderForVertexCache(used, mesh);
  return mesh;
}

}  // namespace glint::shadows
