#pragma once
// glint/bake/asset.h — a bake as a glTF 2.0 asset (`glint bake --asset OUT.glb`) and as a
// web page that shows it (`glint bake --preview DIR`): the low poly with the baker's own
// MikkTSpace tangents and its maps wired into a PBR material, so the bake can be seen where
// it will be used.
//
// What the asset holds (docs/bake.md, "The asset"):
//   - one mesh, one primitive per UDIM tile or bake group, each with its own material;
//     POSITION, NORMAL, TEXCOORD_0 and TANGENT (xyz the unit MikkTSpace tangent the baker
//     used, w = ±1 the bitangent sign): three.js and Blender read the tangents from the file
//     instead of deriving their own, so the map decodes exactly as it was baked;
//   - the normal map as the material's normalTexture, in OpenGL's convention (+Y, as glTF
//     requires) whatever --directx did to the loose file; the AO map as its
//     occlusionTexture (red channel);
//   - every other map as an 8-bit PNG image with a texture, named in the material's
//     extras: {"glint_maps": {"curvature": {"texture": 3, "color_space": "linear", ...}}};
//     colour maps (vertex colour, material ID) are "srgb", data maps "linear".
// UVs are written as glTF's (u, 1 − v) (image row 0 at the top), UDIM tiles' moved into
// 0..1, and the tangents with them unchanged, as Blender's glTF exporter writes them.
//
/// ```cpp
/// glint::bake::Asset asset;
/// asset.name = "crate";
/// auto maps = std::make_shared<glint::bake::AssetMaps>();
/// (*maps)[std::size_t(glint::bake::Map::Normal)] = glint::Image(64, 64, 3);  // 8-bit, OpenGL +Y
/// asset.materials.push_back({"crate", maps});
/// glint::Mesh low = glint::makeCube(1.0f);
/// asset.parts.push_back({glint::bake::frameLowPoly(low), 0});
/// // glint::bake::saveAsset(asset, "crate.glb");
/// ```
#include "glint/bake/maps.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace glint::bake {

/// A material's maps, by Map: 8-bit images as an 8-bit file of the map holds them (the normal
/// map in OpenGL's +Y convention); an empty image: not baked.
using AssetMaps = std::array<Image, kMapCount>;

struct AssetMaterial {
  std::string name;                         ///< the tile ("1001"), the bake group, or the low poly's name
  std::shared_ptr<const AssetMaps> maps;    ///< shared by the groups of one bake (one image in the file)
};

/// Triangles of the low poly that share a material.
struct AssetPart {
  Mesh mesh;         ///< positions, unit normals, UVs in 0..1 (v up), MikkTSpace tangents (frameLowPoly)
  int material = 0;  ///< index into Asset::materials
};

struct Asset {
  std::string name;                     ///< the node's and the mesh's name (the low poly's file name)
  std::vector<AssetMaterial> materials;
  std::vector<AssetPart> parts;
  nlohmann::json extras = nlohmann::json::object();  ///< the asset's "extras.glint_bake": what was baked, from what
};

/// The low poly's tangent frame as the baker builds it: smooth normals where it has none,
/// unit normals, MikkTSpace tangents (vertices split where corners' frames differ).
/// Error(Input) as generateTangents.
Mesh frameLowPoly(Mesh low);

/// The asset as a .glb or .gltf (the buffer embedded), written atomically. Error(Usage) for
/// another extension, Error(Input) for an asset without parts or without a normal map.
void saveAsset(const Asset& asset, const std::filesystem::path& path);

/// The files `--preview DIR` writes, relative to DIR: the page, its script, the asset as a
/// .glb and as a script (a page opened from disk, file://, may not fetch a .glb beside it),
/// three.js's files, and the marker kPageMarker.
std::vector<std::string> previewFiles();

/// The file that marks a folder as a page glint wrote: glint writes a page only into a new
/// folder, an empty one, or one that holds this marker, never over a user's own files.
inline constexpr const char* kPageMarker = ".glint-page";

/// A page folder as an option names it (`--preview`, `--export-web`), checked before any
/// work: "prev/" is "prev"; Error(Output), one line, when it is a file, when its parent is
/// missing or not writable, or when it is a folder that holds files and no kPageMarker
/// (naming up to three of them). Returns the folder's path without a trailing separator.
std::filesystem::path checkPageFolder(const std::string& dir, std::string_view option);

/// A page that shows the asset in a browser, written into `dir` (created, checked with
/// checkPageFolder; inside a run's OutputSet a folder it made goes again if the run fails): index.html with
/// orbit controls, a studio light rig and one toggle per map (normal map, AO, each extra map
/// as a colour, wireframe and UV seams), and three.js (copied from glint's data, where
/// scripts/setup installs it from npm) beside it, so it opens offline from disk or from any
/// static web server. Each file is written atomically. Error(Internal) when three.js is not
/// installed, naming the command that installs it.
void savePreview(const Asset& asset, const std::filesystem::path& dir);

/// The same page for any glTF file's bytes (a .glb, or a .gltf whose buffers are inside it):
/// `glint view FILE --export-web DIR`. `title` heads the page.
void savePreviewPage(const std::vector<unsigned char>& gltf, const std::string& title, const std::filesystem::path& dir);

}  // namespace glint::bake
