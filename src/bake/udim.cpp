#include "glint/bake/udim.h"

#include "glint/core/error.h"

#include <cmath>
#include <map>

namespace glint::bake {

namespace {
// UVs exactly on a tile's upper edge (u = 1.0 of tile 1001) belong to that tile: a
// triangle's extent is tested with this slack, its tile chosen by its centroid.
constexpr float kEdgeSlack = 1e-5f;
}  // namespace

bool spansUdimTiles(const Mesh& low) {
  for (const vec2& uv : low.uvs)
    if (uv.x < -kEdgeSlack || uv.y < -kEdgeSlack || uv.x > 1.0f + kEdgeSlack || uv.y > 1.0f + kEdgeSlack) return true;
  return false;
}

UdimSplit splitUdimTiles(const Mesh& low) {
  if (!low.hasUvs()) fail(ErrorKind::Input, "the low poly has no UVs: nothing to split into UDIM tiles");
  struct Building {
    Mesh mesh;
    std::vector<std::uint32_t> remap;  // low vertex → tile vertex (+1; 0: not yet)
    std::size_t triangles = 0;
    std::vector<std::uint32_t> lowTriangles, lowVertices;
  };
  std::map<int, Building> tiles;
  UdimSplit split;
  for (std::size_t t = 0; t + 2 < low.indices.size(); t += 3) {
    const std::uint32_t i0 = low.indices[t], i1 = low.indices[t + 1], i2 = low.indices[t + 2];
    const vec2 centroid = (low.uvs[i0] + low.uvs[i1] + low.uvs[i2]) / 3.0f;
    const float fu = std::floor(centroid.x), fv = std::floor(centroid.y);
    if (!(fu >= 0.0f && fu < 10.0f && fv >= 0.0f && fv < 100000.0f)) {  // NaN fails too
      ++split.outOfRangeTriangles;
      continue;
    }
    const int u = int(fu), v = int(fv);
    bool spans = false;
    for (const std::uint32_t i : {i0, i1, i2}) {
      const vec2 local = low.uvs[i] - vec2(fu, fv);
      if (local.x < -kEdgeSlack || local.y < -kEdgeSlack || local.x > 1.0f + kEdgeSlack || local.y > 1.0f + kEdgeSlack)
        spans = true;
    }
    if (spans) ++split.spanningTriangles;
    Building& tile = tiles[1001 + u + 10 * v];
    if (tile.remap.empty()) tile.remap.assign(low.vertexCount(), 0);
    for (const std::uint32_t i : {i0, i1, i2}) {
      if (tile.remap[i] == 0) {
        Mesh& m = tile.mesh;
        m.positions.push_back(low.positions[i]);
        if (low.hasNormals()) m.normals.push_back(low.normals[i]);
        m.uvs.push_back(low.uvs[i] - vec2(fu, fv));
        if (low.hasTangents()) m.tangents.push_back(low.tangents[i]);
        tile.remap[i] = std::uint32_t(m.positions.size());
        tile.lowVertices.push_back(i);
      }
      tile.mesh.indices.push_back(tile.remap[i] - 1);
    }
    tile.lowTriangles.push_back(std::uint32_t(t / 3));
    ++tile.triangles;
  }
  for (auto& [number, tile] : tiles)
    split.tiles.push_back({number, std::move(tile.mesh), tile.triangles, std::move(tile.lowTriangles), std::move(tile.lowVertices)});
  return split;
}

std::string udimPath(const std::string& pattern, int tile) {
  std::string path = pattern;
  const std::string number = std::to_string(tile);
  for (std::size_t at = path.find(kUdimToken); at != std::string::npos; at = path.find(kUdimToken, at + number.size()))
    path.replace(at, std::string(kUdimToken).size(), number);
  return path;
}

bool hasUdimToken(const std::string& path) { return path.find(kUdimToken) != std::string::npos; }

}  // namespace glint::bake
