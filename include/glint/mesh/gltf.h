#pragma once
// glint/mesh/gltf.h — writing glTF 2.0 files: a document's JSON and its one binary buffer,
// as a .glb (the binary container) or a .gltf (the JSON with the buffer embedded as base64:
// one file, so the write stays atomic). glint cut's GLB and glint bake's asset are written
// through it; the Khronos glTF-Validator passes both (tests/bake/asset_test.cpp).
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
#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace glint::gltf {

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
