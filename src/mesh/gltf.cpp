// glTF 2.0 files (mesh/gltf.h): the .glb container and the .gltf with its buffer embedded.
#include "glint/mesh/gltf.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/json.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string_view>

namespace glint::gltf {

namespace {

/// A .glb: the header, the JSON chunk (padded with spaces) and the binary chunk (padded with
/// zeros), all lengths little-endian.
void writeGlb(std::ostream& out, std::string json, const std::vector<unsigned char>& bin, const std::filesystem::path& path) {
  static_assert(std::endian::native == std::endian::little, "GLB is written little-endian");
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const std::size_t binPadded = (bin.size() + 3) / 4 * 4;
  const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + binPadded);
  if (total > 0xFFFFFFFFu) fail(ErrorKind::Output, "cannot write '{}': {} bytes do not fit a .glb (4 GiB at most)", path.string(), total);
  const std::uint32_t header[5] = {0x46546C67u /* glTF */, 2u, std::uint32_t(total), std::uint32_t(json.size()),
                                   0x4E4F534Au /* JSON */};
  out.write(reinterpret_cast<const char*>(header), sizeof header);
  out.write(json.data(), std::streamsize(json.size()));
  if (bin.empty()) return;
  const std::uint32_t chunk[2] = {std::uint32_t(binPadded), 0x004E4942u /* BIN */};
  out.write(reinterpret_cast<const char*>(chunk), sizeof chunk);
  out.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
  out.write("\0\0\0", std::streamsize(binPadded - bin.size()));
}

}  // namespace

void writeBase64(std::ostream& out, const std::vector<unsigned char>& data) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  constexpr std::size_t kPiece = 3 << 14;
  for (std::size_t start = 0; start < data.size(); start += kPiece) {
    text.clear();
    const std::size_t end = std::min(data.size(), start + kPiece);
    for (std::size_t i = start; i < end; i += 3) {
      const std::size_t n = std::min<std::size_t>(3, end - i);
      const std::uint32_t v = std::uint32_t(data[i]) << 16 | (n > 1 ? std::uint32_t(data[i + 1]) << 8 : 0u) |
                              (n > 2 ? std::uint32_t(data[i + 2]) : 0u);
      text += kDigits[(v >> 18) & 63];
      text += kDigits[(v >> 12) & 63];
      text += n > 1 ? kDigits[(v >> 6) & 63] : '=';
      text += n > 2 ? kDigits[v & 63] : '=';
    }
    out.write(text.data(), std::streamsize(text.size()));
  }
}

void saveFile(const std::filesystem::path& path, nlohmann::json json, const std::vector<unsigned char>& bin, bool binary) {
  // A .gltf embeds its buffer where this stands: the first string of the JSON that can hold
  // it ("accessors", "asset" and "bufferViews", the keys before "buffers", hold none that is given).
  constexpr std::string_view kHole = "\"glint: the buffer goes here\"";
  json["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
  if (!binary) json["buffers"][0]["uri"] = std::string(kHole.substr(1, kHole.size() - 2));
  const std::string text = jsonText(json, -1);  // names that are not UTF-8 escaped (core/json.h)
  const std::size_t hole = text.find(kHole);
  if (!binary && hole == std::string::npos) fail(ErrorKind::Output, "cannot write '{}': no place for the buffer", path.string());
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (binary) {
      writeGlb(out, text, bin, path);
    } else {
      out.write(text.data(), std::streamsize(hole + 1));
      out << "data:application/octet-stream;base64,";
      writeBase64(out, bin);
      out.write(text.data() + hole + kHole.size() - 1, std::streamsize(text.size() - hole - kHole.size() + 1));
    }
    if (!out) fail(ErrorKind::Output, "cannot write '{}'", path.string());
  });
}

Document::Document(const std::string& generator) {
  json["asset"] = {{"version", "2.0"}, {"generator", generator}};
}

int Document::addView(const void* data, std::size_t bytes, int target) {
  m_buffer.resize((m_buffer.size() + 3) / 4 * 4, 0);
  const std::size_t offset = m_buffer.size();
  const auto* b = static_cast<const unsigned char*>(data);
  m_buffer.insert(m_buffer.end(), b, b + bytes);
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
  if (target) view["target"] = target;
  json["bufferViews"].push_back(std::move(view));
  return int(json["bufferViews"].size() - 1);
}

int Document::addAccessor(const void* data, std::size_t count, int componentType, const char* type, int target,
                          nlohmann::json min, nlohmann::json max) {
  const std::string_view t = type;
  const std::size_t components = t == "SCALAR" ? 1 : t == "VEC2" ? 2 : t == "VEC3" ? 3 : t == "VEC4" ? 4 : 0;
  if (components == 0) fail(ErrorKind::Internal, "gltf: accessor type '{}' is not written", t);
  const int view = addView(data, count * components * 4, target);
  nlohmann::json accessor = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", t}};
  if (!min.is_null()) accessor["min"] = std::move(min);
  if (!max.is_null()) accessor["max"] = std::move(max);
  json["accessors"].push_back(std::move(accessor));
  return int(json["accessors"].size() - 1);
}

int Document::addImage(const std::vector<unsigned char>& png, const std::string& name) {
  const int view = addView(png.data(), png.size());
  json["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}, {"name", name}});
  return int(json["images"].size() - 1);
}

int Document::addTexture(int image) {
  if (!json.contains("samplers")) {
    // LINEAR_MIPMAP_LINEAR, LINEAR, REPEAT (the defaults, said once).
    json["samplers"].push_back({{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}});
  }
  json["textures"].push_back({{"sampler", 0}, {"source", image}});
  return int(json["textures"].size() - 1);
}

std::vector<unsigned char> Document::glb() const {
  nlohmann::json doc = json;
  doc["buffers"] = nlohmann::json::array({{{"byteLength", m_buffer.size()}}});
  std::ostringstream out;
  writeGlb(out, jsonText(doc, -1), m_buffer, "a .glb");
  const std::string bytes = std::move(out).str();
  return {bytes.begin(), bytes.end()};
}

void Document::save(const std::filesystem::path& path) const {
  const std::string ext = lowerExtension(path);
  if (ext != ".glb" && ext != ".gltf") fail(ErrorKind::Usage, "'{}': a glTF file ends in .glb or .gltf", path.string());
  saveFile(path, json, m_buffer, ext == ".glb");
}

}  // namespace glint::gltf
