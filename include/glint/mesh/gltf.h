#pragma once
// glint/mesh/gltf.h — reading and writing glTF 2.0 files.
//
// Reading: gltf::read is the one reader of every glTF file glint opens (glint render, view,
// bake, cut, mesh-info, glint.load_mesh, the Blender add-on's files): geometry in world
// space, materials, the images they use (their encoded bytes), KHR_lights_punctual lights
// and the file's extras. It is written for files from strangers: the JSON's nesting is
// bounded before it is parsed, every value's type is checked where it is read, every
// offset, length, stride and count is checked in 64-bit arithmetic against what it points
// into, every index against its array, the node graph for cycles and second parents
// (walked without recursion), and every external `uri` through the model's fence
// (mesh/fence.h). A file that breaks a rule is Error(Input), one line naming the file, the
// JSON path and the rule ("cannot read 'x.glb': accessors[3].byteOffset: ...").
//
/// ```cpp
/// const glint::gltf::Model model = glint::gltf::read("crate.glb");
/// for (const glint::gltf::Primitive& p : model.primitives) {
///   // p.positions (the primitive's own space), p.world, p.indices (triangles), p.material
/// }
/// ```
//
// Writing: a document's JSON and its one binary buffer, as a .glb (the binary container)
// or a .gltf (the JSON with the buffer embedded as base64: one file, so the write stays
// atomic). glint cut's GLB and glint bake's asset are written through it; the Khronos
// glTF-Validator passes both (tests/bake/asset_test.cpp).
//
/// ```cpp
/// glint::gltf::Document doc("my tool");
/// const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
/// const int position = doc.addAccessor(positions, 3, glint::gltf::kFloat, "VEC3", glint::gltf::kVertices,
///                                      {0, 0, 0}, {1, 1, 0});
/// nlohmann::json mesh, node, scene;
/// mesh["primitives"][0]["attributes"]["POSITION"] = position;
/// doc.json["meshes"].push_back(mesh);
/// node["mesh"] = 0;
/// doc.json["nodes"].push_back(node);
/// scene["nodes"].push_back(0);
/// doc.json["scenes"].push_back(scene);
/// doc.json["scene"] = 0;
/// doc.save("triangle.glb");  // or "triangle.gltf"
/// ```
#include "glint/core/math.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint::gltf {

// ----------------------------------------------------------------------------- reading

/// The most vertices a file's scene may make once its instances are flattened.
inline constexpr std::uint64_t kMaxVertices = std::uint64_t(1) << 28;

/// One triangle primitive of one node (a mesh used by three nodes gives three).
struct Primitive {
  std::vector<vec3> positions;        ///< the primitive's own space; `world` places it
  std::vector<vec3> normals;          ///< empty, or one per vertex, as the file has them
  std::vector<vec2> uvs;              ///< TEXCOORD_0 with v up (glTF's t flipped); empty or one per vertex
  std::vector<vec4> tangents;         ///< empty, or one per vertex (w = ±1)
  std::vector<vec4> colors;           ///< COLOR_0 (RGB gets alpha 1); empty or one per vertex
  std::vector<std::uint32_t> indices; ///< triangles (strips and fans turned into triangles)
  mat4 world{1.0f};                   ///< the node's world transform
  int material = -1;                  ///< index into Model::materials; -1 for none
  std::string node, mesh;             ///< the node's and the mesh's names (may be empty)
};

struct Material {
  std::string name;  ///< may be empty
  vec4 baseColor{1.0f};
  float metallic = 1.0f, roughness = 1.0f;
  /// Indices into Model::images; -1 for none.
  int baseColorImage = -1, normalImage = -1, occlusionImage = -1;
  /// A glint bake asset's maps (extras.glint_maps), in the bake's order: name → image.
  std::vector<std::pair<std::string, int>> maps;
};

/// An image's encoded bytes (PNG or JPEG), read only when a material uses it.
struct ImageBytes {
  std::vector<unsigned char> bytes;  ///< empty: not used, or left out (outside the fence)
  std::string mimeType;              ///< as the file says (may be empty)
  std::string name;
};

/// A KHR_lights_punctual point or spot light (directional lights have no position).
struct Light {
  vec3 position{0.0f};
  std::string name;
};

struct Model {
  std::vector<Primitive> primitives;  ///< the default scene's triangles, depth first, in node order
  std::vector<Material> materials;
  std::vector<ImageBytes> images;
  std::vector<Light> lights;
  nlohmann::json extras;              ///< the file's top-level extras, unchecked: test types before use
  /// What glint does not read and a copy made from this Model lacks ("materials[0].emissiveTexture",
  /// "images[2] ('../x.png')"): what `glint view --export-web` warns it drops.
  std::vector<std::string> dropped;
};

struct ReadOptions {
  bool images = true;  ///< read the images materials use; false: geometry, materials and lights only
};

/// Whether `path` ends in .gltf or .glb (any case).
bool isGltf(const std::filesystem::path& path);

/// Reads a .gltf (with its buffers and images, inside its folder, or data: URIs) or a .glb.
/// Error(Input), one line, for a file that is missing, is not glTF 2.0, breaks a rule above,
/// or needs an extension glint does not read (extensionsRequired). Points and lines are
/// skipped; a file without triangles gives a Model without primitives (the caller decides).
Model read(const std::filesystem::path& path, const ReadOptions& options = {});

// ----------------------------------------------------------------------------- writing

/// Accessor component types and buffer view targets, as glTF numbers them.
inline constexpr int kFloat = 5126;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kVertices = 34962;  ///< ARRAY_BUFFER: vertex attributes
inline constexpr int kIndices = 34963;   ///< ELEMENT_ARRAY_BUFFER: triangle indices

/// A glTF document being built: `json` (asset, scenes, nodes, meshes, materials, ...) and the
/// buffer that holds every accessor's and image's bytes. "asset" is filled in; "buffers" is
/// written by save().
class Document {
public:
  explicit Document(const std::string& generator);

  nlohmann::json json;

  /// Appends bytes to the buffer (at a 4-byte boundary) as a new buffer view; its index.
  /// `target`: kVertices, kIndices, or 0 for none (images).
  int addView(const void* data, std::size_t bytes, int target = 0);
  /// A new view of `count` elements of `type` ("SCALAR", "VEC2", "VEC3", "VEC4") and an
  /// accessor over it; the accessor's index. min/max: give them for POSITION (glTF requires them).
  int addAccessor(const void* data, std::size_t count, int componentType, const char* type, int target,
                  nlohmann::json min = nullptr, nlohmann::json max = nullptr);
  /// A PNG file's bytes as an image of the document (in the buffer); the image's index.
  int addImage(const std::vector<unsigned char>& png, const std::string& name);
  /// A texture of image `image`, sampled linearly with mipmaps and repeat; its index.
  int addTexture(int image);

  const std::vector<unsigned char>& buffer() const { return m_buffer; }
  /// The document as the bytes of a .glb file.
  std::vector<unsigned char> glb() const;
  /// Writes the document atomically: .glb binary, .gltf text (Error(Usage) for another
  /// extension; Error(Output) when it cannot be written, or is over 4 GiB as a .glb).
  void save(const std::filesystem::path& path) const;

private:
  std::vector<unsigned char> m_buffer;
};

/// Writes `json` with `buffer` as its only buffer: a .glb when `binary`, else a .gltf with
/// the buffer embedded as a base64 data URI. Sets "buffers"; writes atomically.
void saveFile(const std::filesystem::path& path, nlohmann::json json, const std::vector<unsigned char>& buffer,
              bool binary);

/// `data` as base64 text (RFC 4648, with padding), written in pieces.
void writeBase64(std::ostream& out, const std::vector<unsigned char>& data);

}  // namespace glint::gltf
