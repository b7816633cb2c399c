#pragma once
// glint/mesh/parts.h — a mesh file read as named parts: which object each triangle came
// from, its material, and the vertex colours when the file has them.
//
// Contents
//   MeshParts       the flattened Mesh (as loadMesh gives it) plus per-triangle part and
//                   material indices and optional per-vertex colours
//   loadMeshParts   read a file as parts (Assimp: OBJ `o`/`g`/`usemtl` and `v x y z r g b`,
//                   PLY red/green/blue, glTF/FBX node and mesh names, materials, colours)
//
// loadMesh stays the fast way to read geometry; loadMeshParts always goes through Assimp
// (the fast OBJ/PLY parsers do not keep names), so `glint bake` only calls it when a map
// or the naming convention needs the parts (see bake/groups.h).

#include "glint/mesh/mesh.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

struct MeshParts {
  Mesh mesh;                                  ///< every part, flattened (node transforms applied)
  std::vector<std::string> partNames;         ///< one per part: the node's name, else the mesh's;
                                              ///< parts of the same name are one part
  std::vector<std::uint32_t> trianglePart;    ///< per triangle of `mesh`: index into partNames
  std::vector<std::string> materialNames;     ///< the materials triangles use (Assimp's default
                                              ///< material, "DefaultMaterial", is not listed)
  /// Per triangle: index into materialNames, or kNoMaterial. Empty when no triangle has a material.
  std::vector<std::uint32_t> triangleMaterial;
  /// Empty, or one linear RGBA colour per vertex (the file's first colour set; parts without
  /// colours in a file where others have them are white).
  std::vector<vec4> colors;

  static constexpr std::uint32_t kNoMaterial = ~0u;
  bool hasColors() const { return !colors.empty(); }
  bool hasMaterials() const { return !triangleMaterial.empty(); }
};

/// Reads every triangle mesh in a file as parts, through Assimp, with the same options as
/// loadMesh (joinVertices, generateNormals; `parser` is ignored). Error(Input) like loadMesh.
MeshParts loadMeshParts(const std::filesystem::path& path, const MeshLoadOptions& options = {});

}  // namespace glint
