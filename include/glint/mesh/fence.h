#pragma once
// glint/mesh/fence.h — what a model file may reference: files inside its own folder.
//
// A model file names other files: a glTF's buffers and images (`uri`), an OBJ's material
// library (`mtllib`). A file from a stranger may name anything ("../../.ssh/id_rsa",
// "/etc/passwd", "http://example.com/x.png"), and what glint reads can end up in what it
// writes (a web page made to be published). So a reference is read only when it stays
// inside the model's folder (the fence):
//   - `data:` URIs are read from the file itself (base64 or percent-encoded), up to
//     kMaxDataUriBytes decoded;
//   - a reference is percent-decoded first (RFC 3986, as glTF's `uri` requires), then
//     refused when it has a scheme (http:, file:, ...), is absolute, is empty, holds a NUL,
//     or leaves the folder: by `..` (encoded or not) or by a symbolic link that points out;
//   - the file it names must be a regular file of at most kMaxReferencedBytes.
// Every model reader goes through this header: glint's glTF reader (mesh/gltf.h) for
// buffers and images, and Assimp's file system (OBJ's `mtllib`, FBX and the other formats'
// side files) through ModelFence::allows.
//
/// ```cpp
/// const glint::ModelFence fence("assets/crate/crate.gltf");
/// const std::filesystem::path texture = fence.resolve("textures/wood%20grain.png", "image 0");
/// // assets/crate/textures/wood grain.png; "../secret.png" or "http://x/y.png" would be Error(Input)
/// std::string mime;
/// const std::vector<unsigned char> bytes = glint::decodeDataUri("data:text/plain;base64,aGk=", mime);  // "hi"
/// ```
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// The most bytes a `data:` URI may decode to (a model's own embedded buffer or image).
inline constexpr std::uint64_t kMaxDataUriBytes = std::uint64_t(1) << 30;
/// The largest file a model may reference (a .bin buffer or a texture).
inline constexpr std::uint64_t kMaxReferencedBytes = std::uint64_t(4) << 30;

class ModelFence {
public:
  /// The fence of `modelFile`: its folder, symbolic links resolved.
  explicit ModelFence(const std::filesystem::path& modelFile);

  /// The file `reference` names, inside the folder: Error(Input) "'<model>': <what>'s uri
  /// '<reference>' <why>" otherwise (the reference quoted on one line).
  std::filesystem::path resolve(std::string_view reference, std::string_view what) const;
  /// Whether `path` (absolute, or relative to the current directory, as a library asks
  /// for it) lies inside the folder, links resolved (it need not exist).
  bool allows(const std::filesystem::path& path) const;
  /// A resolved file's bytes (at most kMaxReferencedBytes); Error(Input) naming `what`.
  std::vector<unsigned char> read(const std::filesystem::path& resolved, std::string_view what) const;

  const std::filesystem::path& folder() const { return m_folder; }
  const std::filesystem::path& model() const { return m_model; }

private:
  std::filesystem::path m_model;   ///< as given
  std::filesystem::path m_folder;  ///< canonical
};

/// Whether `uri` is a `data:` URI.
bool isDataUri(std::string_view uri);
/// A `data:` URI's bytes (";base64" or percent-encoded) and its media type ("image/png";
/// "text/plain" when it names none); Error(Input) for a malformed one or one over maxBytes.
std::vector<unsigned char> decodeDataUri(std::string_view uri, std::string& mediaType,
                                         std::uint64_t maxBytes = kMaxDataUriBytes);
/// RFC 3986 percent-decoding ("a%20b" → "a b"); Error(Input) for a '%' not followed by two
/// hex digits.
std::string percentDecode(std::string_view text);

}  // namespace glint
