#pragma once
// glint/scenes/model.h — any model file as a scene: `glint view FILE` and `glint render FILE`
// for .glb/.gltf/.obj/.ply/.fbx. The model is lit by a studio rig (key, fill and rim lights
// that follow the camera, and the courtyard environment from glint's data as ambient and
// reflections) and framed as `glint bake --preview`'s page frames it (the same camera for
// the same yaw and pitch). Its options are one toggle per map the file carries, so a
// bake's asset (`glint bake --asset`) shows where the bake went wrong:
//
//   normal-map (N)  the material's normal map on/off
//   ao (O)          the occlusion map on/off
//   show (M)        0: shaded; k: the file's k-th map as a colour (a bake asset's glint_maps,
//                   in the bake's table order: normal, ao, ..., miss mask)
//   wireframe (W), uv-seams (U), hard-edges (H)   lines over the model: every triangle edge;
//                   edges whose two faces disagree on UVs (or that have one face); edges whose
//                   faces disagree on normals (where a bake's rays fan apart)
//   misses (X)      texels whose rays missed (a bake asset's miss mask) tinted red
//   yaw, pitch, zoom  the camera (degrees; a distance factor), as `--camera` sets them
//   frame           another model file whose bounding sphere the camera frames instead (a
//                   high poly shown at its low poly's camera)
//
// glint cut's GLB shows each piece in its light mask's tint (its COLOR_0).
//
/// ```cpp
/// if (glint::scenes::isModelFile("crate.glb")) {
///   const glint::scenes::ModelFile model = glint::scenes::loadModelFile("crate.glb");
///   // model.parts[i].mesh: positions, normals, UVs (v up), tangents; model.materials[...].maps
/// }
/// ```
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"
#include "glint/scenes/scene.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint::scenes {

/// A material as the viewer uses it. Images keep row 0 at the top; meshes' UVs are v-up.
struct ModelMaterial {
  std::string name;
  vec4 baseColor{0.8f, 0.8f, 0.8f, 1.0f};
  float roughness = 0.55f;
  Image baseColorMap, normalMap, occlusionMap;  ///< empty: none
  /// Every map to show as a colour, in order: a bake asset's glint_maps (their report keys:
  /// "normal", "ao", "curvature", "miss_mask", ...), else the material's own textures.
  std::vector<std::pair<std::string, Image>> maps;
};

struct ModelPart {
  Mesh mesh;                  ///< world space (node transforms applied); tangents when it has a normal map
  std::vector<vec4> colors;   ///< empty, or one per vertex (glTF COLOR_0)
  int material = -1;          ///< index into ModelFile::materials; -1: a plain grey
};

struct ModelFile {
  std::string name;                    ///< the file's name
  std::vector<ModelPart> parts;
  std::vector<ModelMaterial> materials;
  nlohmann::json bake;                 ///< a `glint bake --asset`'s extras.glint_bake (an object); null otherwise
  std::vector<std::string> dropped;    ///< what the file has and glint does not read (gltf::Model::dropped)
  Bounds bounds() const;
  /// The names of every map some material shows (the "show" option's list, 1-based).
  std::vector<std::string> mapNames() const;
};

/// Whether `name` names a file glint opens as a model (.glb .gltf .obj .ply .fbx,
/// whatever the case), whether or not it exists.
bool isModelFile(std::string_view name);

/// Reads a model: glTF through glint's reader, mesh/gltf.h (materials, textures, a bake's
/// extras, node transforms, COLOR_0, TANGENT; MikkTSpace tangents made where a normal map
/// has none), the others through mesh/parts.h (geometry and UVs). Either way the file may
/// reference only files in its own folder (mesh/fence.h). Error(Input), one line, for a
/// missing, corrupt or empty file.
ModelFile loadModelFile(const std::filesystem::path& path);

/// The model as the bytes of a .glb (what `glint view FILE --export-web DIR` puts in its page
/// for a file that is not a .glb already): its parts, vertex colours, materials and maps.
std::vector<unsigned char> modelGlb(const ModelFile& model);

/// A registry with one scene, "model/<file name>" (variant "view"), that shows the file.
/// Error(Input) as loadModelFile, before any window or context exists.
Registry modelRegistry(const std::filesystem::path& path);

/// The registry a command's scene argument names: a model file's own (kept in `storage`,
/// and `name` set to its scene) or the built-in scenes.
const Registry& registryFor(std::string& name, Registry& storage);

}  // namespace glint::scenes
