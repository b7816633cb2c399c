// Cut polygons as triangles, and their areas: what renderers, glTF and the reports need.
#include "glint/cut/cutter.h"

#include <cstdint>
#include <span>
#include <vector>

namespace glint::cut {

double polygonArea(const CutMesh& mesh, std::size_t polygon) {
  const std::uint32_t s = mesh.polygonStart[polygon], e = mesh.polygonStart[polygon + 1];
  const dvec3& o = mesh.precisePositions[mesh.corners[s]];
  dvec3 sum(0.0);
  for (std::uint32_t c = s + 1; c + 1 < e; ++c)
    sum += glm::cross(mesh.precisePositions[mesh.corners[c]] - o, mesh.precisePositions[mesh.corners[c + 1]] - o);
  return 0.5 * glm::length(sum);
}

namespace {

/// One convex polygon's triangles, appended to `out` (see triangulate() in cutter.h).
void triangulatePolygon(std::span<const std::uint32_t> corners, std::span<const std::uint8_t> straight,
                        std::vector<std::uint32_t>& out) {
  // Ear clipping at corners that turn: the ear (prev, v, next) then has area, and prev and
  // next turn afterwards (they were on v's two sides, which are different lines). An ear
  // is taken only when at least three turning corners remain, so what is left keeps its
  // area: n − 2 triangles, none of zero area, no extra vertex.
  std::vector<std::uint32_t> v(corners.begin(), corners.end());
  std::vector<std::uint8_t> st(straight.begin(), straight.end());
  while (v.size() > 3) {
    const std::size_t n = v.size();
    std::size_t turning = 0;
    for (std::uint8_t x : st) turning += !x;
    std::size_t ear = n;
    for (std::size_t i = 0; i < n && ear == n; ++i) {
      if (st[i]) continue;
      const std::size_t left = turning - 1 + st[(i + n - 1) % n] + st[(i + 1) % n];
      if (left >= 3) ear = i;
    }
    if (ear == n) ear = 0;  // not reached for a convex polygon with area (cutter.h)
    const std::size_t prev = (ear + n - 1) % n, next = (ear + 1) % n;
    out.insert(out.end(), {v[prev], v[ear], v[next]});
    st[prev] = st[next] = 0;
    v.erase(v.begin() + std::ptrdiff_t(ear));
    st.erase(st.begin() + std::ptrdiff_t(ear));
  }
  out.insert(out.end(), v.begin(), v.end());
}

}  // namespace

Triangles triangulate(const CutMesh& mesh) {
  Triangles t;
  t.mesh.positions = mesh.positions;
  for (std::size_t p = 0; p < mesh.polygonCount(); ++p) {
    const std::uint32_t s = mesh.polygonStart[p];
    const std::size_t n = mesh.cornerCount(p), before = t.mesh.indices.size();
    triangulatePolygon(std::span(mesh.corners).subspan(s, n), std::span(mesh.straight).subspan(s, n), t.mesh.indices);
    for (std::size_t i = before; i < t.mesh.indices.size(); i += 3) t.trianglePolygon.push_back(std::uint32_t(p));
  }
  return t;
}

}  // namespace glint::cut
