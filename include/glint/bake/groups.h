#pragma once
// glint/bake/groups.h — bakes of named parts: bake groups matched by name, and the maps that
// need the high poly's materials or vertex colours (material ID, vertex colour).
//
// Contents
//   GroupNaming, matchGroups   pair low and high parts by name (`body_low` ↔ `body_high`, `body_high_*`)
//   GroupMatch                 the pairing: groups, per-triangle group indices, unmatched parts
//   materialColor              the material ID map's colour for a material name
//   bake                       bake() for meshes read as parts (glint/mesh/parts.h)
//   toJson                     the groups in a report (`glint bake --json`: "groups")
//
// Bake groups
//   Several low and high meshes in one or two files are paired by name, the convention
//   Substance and Marmoset use: a low part `<name><lowSuffix>` bakes against every high part
//   `<name><highSuffix>` or `<name><highSuffix>_<anything>` (with the default suffixes
//   `body_low` ↔ `body_high`, `body_high_1`, `body_high_bolts`). A low part's rays only see
//   its own group's high parts, so parts that sit close together or interpenetrate bake as
//   if exploded, without exploding them. Each group gets its own BVH, built in turn while
//   its low triangles are baked (one BVH alive at a time); dilation runs once over the
//   whole map afterwards.
//   - When no low part's name ends with the low suffix the bake is one group, whatever the
//     high parts are called: exactly the plain bake().
//   - A low part without a high part is reported by name and not baked: its texels stay
//     empty (filled by dilation like any unused texel). A high part without a low part is
//     reported and ignored. No matched group at all is Error(Input).
//   - Distances given as a share of the model (5%) are the whole low poly's diagonal in
//     every group.
//
// Material ID (Map::MaterialId in BakeOptions::maps)
//   A flat colour per high-poly material: the colour of the material the majority of a
//   texel's hitting samples landed on (ties: the earliest sample), so every texel holds
//   exactly one material's colour — no averaging across materials, and dilation copies
//   the nearest texel's colour instead of averaging. materialColor() is a stable function
//   of the name: the top 32 bits of FNV-1a 64 of its bytes times the golden ratio (mod 1) is the hue, with
//   saturation 0.7 and value 0.95, rounded to 8 bits per channel (the float image holds
//   exactly k/255). A high poly without materials bakes one colour (the colour of ""),
//   with a warning. Texels none of whose samples hit are black.
//
// Vertex colour (Map::VertexColor in BakeOptions::maps)
//   The high poly's vertex colour (RGB, as the file stores it) interpolated at each hit,
//   averaged over the texel's hitting samples; black where none hit. Error(Input) when the
//   high poly has no vertex colours.
//
/// ```cpp
/// #include <glint/bake/groups.h>
/// const glint::MeshParts low = glint::loadMeshParts("parts_low.fbx");
/// const glint::MeshParts high = glint::loadMeshParts("parts_high.fbx", {.joinVertices = false});
/// const glint::bake::GroupMatch match = glint::bake::matchGroups(low, high);  // {"_low", "_high"}
/// glint::bake::BakeOptions options;
/// options.maps.add(glint::bake::Map::MaterialId);
/// const glint::bake::BakeResult result = glint::bake::bake(low, high, match, options);
/// ```

#include "glint/bake/baker.h"
#include "glint/mesh/parts.h"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace glint::bake {

struct GroupNaming {
  std::string lowSuffix = "_low";    ///< a low part is `<group><lowSuffix>`
  std::string highSuffix = "_high";  ///< a high part is `<group><highSuffix>` or `<group><highSuffix>_<anything>`
};

struct BakeGroup {
  std::string name;                    ///< the name without the suffix ("body")
  std::vector<std::string> lowParts;   ///< in file order
  std::vector<std::string> highParts;
  std::size_t lowTriangles = 0, highTriangles = 0;
};

struct GroupMatch {
  static constexpr std::uint32_t kNone = ~0u;
  std::vector<BakeGroup> groups;  ///< empty: the names use no suffix, one group (a plain bake)
  std::vector<std::uint32_t> lowTriangleGroup;   ///< per low triangle: index into groups, or kNone
  std::vector<std::uint32_t> highTriangleGroup;  ///< per high triangle: index into groups, or kNone
  std::vector<std::string> unmatchedLow;   ///< low parts with no high part (not baked)
  std::vector<std::string> unmatchedHigh;  ///< high parts with no low part (ignored)
  bool grouped() const { return !groups.empty(); }
};

/// The group a part's name belongs to: its name without the suffix, or empty when the name
/// does not follow the convention for `suffix` (`high`: also `<group><suffix>_*`).
std::string groupName(std::string_view part, std::string_view suffix, bool high);

/// Pairs the parts by name (see "Bake groups" above). Error(Usage) for an empty suffix or
/// equal suffixes; Error(Input) when names use the convention but no group has both sides.
GroupMatch matchGroups(const MeshParts& low, const MeshParts& high, const GroupNaming& naming = {});

/// The material ID colour of a material name (linear 0..1, each channel k/255).
vec3 materialColor(std::string_view name);

/// bake() for parts: groups as `match` says (matchGroups(low, high)), the material ID and
/// vertex colour maps from high's materials and colours. With an ungrouped match and no
/// such map it is bake(low.mesh, high.mesh, options).
BakeResult bake(const MeshParts& low, const MeshParts& high, const GroupMatch& match, const BakeOptions& options);

/// "groups": [{name, low_parts, high_parts, low_triangles, high_triangles}], and
/// "unmatched_low"/"unmatched_high" lists of names.
nlohmann::ordered_json toJson(const GroupMatch& match);

}  // namespace glint::bake
