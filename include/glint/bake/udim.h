#pragma once
// glint/bake/udim.h — UDIM tiles: a low poly whose UVs span several unit squares bakes one
// image per occupied square ("tile").
//
// The convention (Mari, Substance, Marmoset, Blender): tile (i, j) is the UV square
// [i, i+1) × [j, j+1) with 0 ≤ i < 10 and j ≥ 0, numbered 1001 + i + 10 j; a file name
// holds the token <UDIM> where the number goes (`normal.<UDIM>.png` → `normal.1001.png`,
// `normal.1002.png`, ...).
//
// splitUdimTiles() gives each occupied tile as a mesh of its own: the low poly's triangles
// in that tile, their UVs moved into [0, 1]. Baking that mesh is baking the tile — `--size`
// is per tile, padding stays inside it, and the tile's image is byte for byte the bake of
// the same triangles drawn in the unit square. A triangle belongs to the tile that holds its
// UV centroid; one reaching into a neighbour is counted (spanning) and baked in its own
// tile, clipped at the tile's edge. Triangles with UVs outside the UDIM range (u < 0,
// u ≥ 10 or v < 0) are counted and left out.
//
/// ```cpp
/// glint::Mesh low = glint::makePlane(2.0f, 2.0f);  // UVs 0..2: tiles 1001, 1002, 1011, 1012
/// const glint::bake::UdimSplit split = glint::bake::splitUdimTiles(low);
/// for (const glint::bake::UdimTile& tile : split.tiles) {
///   const std::string file = glint::bake::udimPath("normal.<UDIM>.png", tile.number);  // normal.1001.png, ...
///   (void)file;
/// }
/// ```
#include "glint/mesh/mesh.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace glint::bake {

/// One occupied tile: its number and its triangles as a mesh of their own, UVs in [0, 1].
struct UdimTile {
  int number = 1001;      ///< 1001 + u + 10 v
  Mesh low;               ///< the tile's triangles (every attribute kept), UVs moved by (−u, −v)
  std::size_t triangles = 0;
  std::vector<std::uint32_t> lowTriangles;  ///< per triangle of `low`: its index in the low poly
  std::vector<std::uint32_t> lowVertices;   ///< per vertex of `low`: its index in the low poly (a cage's
                                            ///< vertices are the low poly's: the tile's cage is these)
};

struct UdimSplit {
  std::vector<UdimTile> tiles;      ///< ascending by number
  std::size_t spanningTriangles = 0;   ///< reach past their tile's edges (baked clipped)
  std::size_t outOfRangeTriangles = 0; ///< UVs outside u ∈ [0, 10), v ≥ 0 (left out)
};

/// The token a file name carries for the tile number.
inline constexpr const char* kUdimToken = "<UDIM>";

/// Whether any UV of `low` lies outside the unit square [0, 1]² (then a bake is a UDIM
/// bake and its file names need kUdimToken).
bool spansUdimTiles(const Mesh& low);

/// The low poly split into its occupied tiles. Error(Input) when it has no UVs.
UdimSplit splitUdimTiles(const Mesh& low);

/// `pattern` with every <UDIM> replaced by `tile` ("n.<UDIM>.png", 1002 → "n.1002.png").
std::string udimPath(const std::string& pattern, int tile);

/// Whether `path` contains <UDIM>.
bool hasUdimToken(const std::string& path);

}  // namespace glint::bake
