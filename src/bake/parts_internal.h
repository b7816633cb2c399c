#pragma once
// Private to the baker: bake groups and the maps of the high poly's parts (parts.cpp),
// hooked into the bake loop (baker.cpp) through Context's parts fields (trace.h).
#include "glint/bake/groups.h"
#include "trace.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace glint::bake::detail {

/// What the material ID and vertex colour maps read at a hit.
struct PartsTables {
  /// Per material index; the last one is the colour of "" (triangles without a material).
  std::vector<vec3> materialColors;
  const std::vector<std::uint32_t>* triangleMaterial = nullptr;  ///< per high triangle (null: none)
  const std::vector<vec4>* colors = nullptr;                     ///< per high vertex (null: none)
  const std::vector<std::uint32_t>* highIndices = nullptr;       ///< the high poly's indices
};

/// What bake(MeshParts...) adds to a plain bake.
struct PartsInput {
  const GroupMatch* match = nullptr;  ///< groups, when grouped()
  const MeshParts* high = nullptr;    ///< materials and colours
};

/// The bake of baker.cpp, with parts (null: a plain bake).
BakeResult bakeWith(const Mesh& low, const Mesh& high, const BakeOptions& options, const PartsInput* parts);

/// The material and colour tables of the high poly; Error(Input) when vertex colours are
/// asked and it has none; a warning when a material ID map is asked and it has no materials.
PartsTables makePartsTables(const BakeOptions& options, const Mesh& high, const MeshParts* parts,
                            std::vector<std::string>& warnings);

/// Group `group`'s high-poly triangles as a mesh of their own (corners in order, positions
/// and normals only); `ids` receives each triangle's index in `high`.
Mesh groupHighMesh(const Mesh& high, const std::vector<std::uint32_t>& highTriangleGroup, std::uint32_t group,
                   std::vector<std::uint32_t>& ids);

/// ctx.texelMaterial of a texel on a UV island whose samples all missed: black, like the
/// other maps' missed texels, and not an empty texel that dilation fills (dilation fills
/// the texels outside the islands only, as it does for every other map).
inline constexpr std::uint32_t kMaterialMissed = 0xFFFFFFFFu;

/// A texel's material (into ctx.texelMaterial: index + 1, kMaterialMissed where no sample
/// hit) and vertex colour (into out[colorChannel]) from its samples `results`.
void storePartsMaps(Context& ctx, std::size_t texel, std::span<const SampleResult> results, float* out);

/// Grows texelMaterial into empty (0: off the islands) texels: each pass copies the first
/// filled 8-neighbour (left, right, below, above, then the diagonals) of the previous pass
/// (kMaterialMissed included, so a missed border texel spreads black, as the other maps
/// spread their missed texels' values).
/// `passes` < 0: until nothing changes.
void dilateMaterials(std::vector<std::uint32_t>& ids, int width, int height, int passes);

/// The material ID map (row 0 on top) from ctx.texelMaterial; black where there is none
/// (0 or kMaterialMissed).
Image materialImage(const Context& ctx);

}  // namespace glint::bake::detail
