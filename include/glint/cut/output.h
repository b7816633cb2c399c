#pragma once
// glint/cut/output.h — reading a cut's scene and the lights glTF files carry, and writing
// the cut mesh.
//
// Formats, from the file name's extension:
//   .glb .gltf  one mesh, one primitive per light mask: the mask is the primitive's
//               extras {"light_mask": m, "lit_by": [names]} (m an unsigned integer, the
//               names [] when no light reaches the faces; glTF has no per-face
//               attributes; a primitive holds the faces of one mask). COLOR_0 shows it
//               (grey = the share of lights that reach the face; maskColor). Vertices on
//               mask borders are repeated per primitive, as glTF needs for the colours.
//               The lights go along as KHR_lights_punctual point lights. The JSON is
//               written by tinygltf (Debian's libtinygltf), the extras, the buffer and
//               the file around them by glint; .gltf embeds its buffer (base64).
//   .ply        binary PLY with the convex polygons as they are (shared vertices, so a
//               watertight input stays watertight in the file), per face the properties
//               `light_mask` (uint), `source` (the input triangle, uint) and red/green/blue
//               (maskColor); the lights in comments. Each polygon starts at a corner a reader's
//               fan triangulation can start from. No Debian writer takes per-face properties
//               (Assimp's PLY exporter writes none), so this one is glint's (~60 lines).
//
// Every file is written atomically (core/file.h). Error(Usage) for another extension,
// Error(Output) when the file cannot be written.
//
/// ```cpp
/// std::vector<glint::cut::Light> lights;  // room.glb's KHR_lights_punctual lights
/// const glint::Mesh scene = glint::cut::loadScene({"walls.obj", "room.glb"}, &lights);
/// glint::cut::CutOptions options;
/// options.lights = lights;
/// const glint::cut::CutResult result = glint::cut::cut(scene, options);
/// glint::cut::saveCutMesh(result.mesh, result.lights, "room_cut.glb");
/// glint::cut::saveCutMesh(result.mesh, result.lights, "room_cut.ply");
/// ```

#include "glint/cut/cutter.h"

#include <filesystem>
#include <vector>

namespace glint::cut {

/// Writes the cut mesh (format from the extension: .glb, .gltf, .ply).
void saveCutMesh(const CutMesh& mesh, const std::vector<Light>& lights, const std::filesystem::path& path);

/// Error(Usage) unless the extension is one saveCutMesh writes.
void checkOutputFormat(const std::filesystem::path& path);

/// The viewing colour of a mask: grey 0.2 + 0.8 × (lights reaching the face / lights).
vec3 maskColor(LightMask mask, int lightCount);

/// The scene of a cut: the meshes in `paths` joined in order (Error(Input) for one that
/// cannot be read), read for their positions: no normals are generated for meshes without
/// (nor warned about; MeshLoadOptions::generateNormals). The loader's other warnings are
/// logged (`glint cut` lists them in its report through log::WarningCapture). When `gltfLights` is given, the lights of the glTF files among them
/// (loadGltfLights) are appended to it, file by file: `glint cut` uses them when no --light
/// is given.
Mesh loadScene(const std::vector<std::filesystem::path>& paths, std::vector<Light>* gltfLights = nullptr);

/// The KHR_lights_punctual point (and spot) lights of a .gltf/.glb file, at their nodes'
/// world positions (default scene); empty for other formats or files without lights.
/// Error(Input) when a glTF file's JSON cannot be parsed.
std::vector<Light> loadGltfLights(const std::filesystem::path& path);

/// A PLY written by saveCutMesh, read back: its polygons' masks in file order (tests,
/// tools that post-process). Error(Input) for another file.
std::vector<LightMask> loadPlyMasks(const std::filesystem::path& path);

}  // namespace glint::cut
