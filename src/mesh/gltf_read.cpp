// glint's one glTF reader (mesh/gltf.h: gltf::read). Every value is checked where it is
// read, in 64-bit arithmetic, against what it points into; nothing is trusted because the
// file says it. See docs/reliability.md, "The model fence and the limits".
#include "glint/mesh/gltf.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/json.h"
#include "glint/core/log.h"
#include "glint/core/text.h"
#include "glint/mesh/fence.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint::gltf {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123;

/// Reads one file's JSON into glint's structures; `bad` is every error's one line.
class Reader {
public:
  Reader(const fs::path& path, const ReadOptions& options)
      : m_path(path), m_name(printable(path.string())), m_options(options), m_fence(path) {}

  Model read();

private:
  // ------------------------------------------------------------------ JSON, checked
  [[noreturn]] void bad(const std::string& where, std::string_view why) const {
    fail(ErrorKind::Input, "cannot read '{}': {}{}{}", m_name, where, where.empty() ? "" : ": ", why);
  }
  static std::string at(const std::string& array, std::size_t i) { return fmt::format("{}[{}]", array, i); }
  static std::string field(const std::string& where, const char* key) { return where.empty() ? key : where + "." + key; }

  /// `object[key]` or nullptr; `object` must be a JSON object.
  const json* member(const json& object, const char* key, const std::string& where) const {
    if (!object.is_object()) bad(where, fmt::format("is {}, not an object", typeName(object)));
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }
  static std::string typeName(const json& v) {
    if (v.is_number()) return "a number";
    return fmt::format("a{} {}", v.is_array() || v.is_object() ? "n" : "", v.type_name());
  }
  const json& array(const json& root, const char* key) const {
    static const json empty = json::array();
    const json* a = member(root, key, "");
    if (!a) return empty;
    if (!a->is_array()) bad(key, fmt::format("is {}, not an array", typeName(*a)));
    return *a;
  }
  /// A non-negative integer (an index, a count, an offset); `absent` when missing.
  std::optional<std::uint64_t> integer(const json& object, const char* key, const std::string& where,
                                       const char* kind = "a non-negative integer") const {
    const json* v = member(object, key, where);
    if (!v) return std::nullopt;
    if (!v->is_number_unsigned()) bad(field(where, key), fmt::format("is {}, not {}", printable(v->dump()), kind));
    return v->get<std::uint64_t>();
  }
  std::uint64_t integerOr(const json& object, const char* key, const std::string& where, std::uint64_t fallback) const {
    return integer(object, key, where).value_or(fallback);
  }
  std::uint64_t required(const json& object, const char* key, const std::string& where) const {
    const auto v = integer(object, key, where);
    if (!v) bad(where, fmt::format("has no \"{}\"", key));
    return *v;
  }
  /// An index into an array of `count` items.
  std::optional<std::size_t> index(const json& object, const char* key, const std::string& where, std::size_t count,
                                   const char* into) const {
    const auto v = integer(object, key, where, "an index (a non-negative integer)");
    if (!v) return std::nullopt;
    if (*v >= count) bad(field(where, key), fmt::format("is {}, but the file has {} {}", *v, count, into));
    return std::size_t(*v);
  }
  double number(const json& object, const char* key, const std::string& where, double fallback) const {
    const json* v = member(object, key, where);
    if (!v) return fallback;
    if (!v->is_number() || !std::isfinite(v->get<double>())) bad(field(where, key), fmt::format("is {}, not a finite number", printable(v->dump())));
    return v->get<double>();
  }
  std::string string(const json& object, const char* key, const std::string& where) const {
    const json* v = member(object, key, where);
    if (!v) return {};
    if (!v->is_string()) bad(field(where, key), fmt::format("is {}, not a string", printable(v->dump())));
    return v->get<std::string>();
  }
  /// `n` finite numbers, or empty when the key is missing.
  std::vector<double> numbers(const json& object, const char* key, const std::string& where, std::size_t n) const {
    const json* v = member(object, key, where);
    if (!v) return {};
    if (!v->is_array() || v->size() != n) bad(field(where, key), fmt::format("must be an array of {} numbers", n));
    std::vector<double> out;
    for (const json& x : *v) {
      if (!x.is_number() || !std::isfinite(x.get<double>())) bad(field(where, key), fmt::format("must be an array of {} finite numbers", n));
      out.push_back(x.get<double>());
    }
    return out;
  }

  // ------------------------------------------------------------------ the file
  void parse();
  void readBuffers();
  void checkViews();
  const std::vector<unsigned char>& bufferOf(std::size_t view) const { return m_buffers[m_views[view].buffer]; }

  struct View {
    std::size_t buffer = 0;
    std::uint64_t offset = 0, length = 0, stride = 0;
  };
  struct AccessorInfo {
    int componentType = 0;
    int components = 0;  // per element
    bool normalized = false;
    std::uint64_t count = 0;
  };
  AccessorInfo accessorInfo(std::size_t accessor) const;
  /// An accessor's elements as floats (`accepted` components per element).
  std::vector<float> floats(std::size_t accessor, std::initializer_list<int> accepted, const std::string& what, int& components) const;
  std::vector<std::uint32_t> indices(std::size_t accessor, std::uint64_t vertexCount, const std::string& where) const;
  void readElements(std::size_t accessor, const AccessorInfo& info, std::vector<double>& out) const;

  void readMaterials(Model& model);
  void readNodes(Model& model);
  /// Each node's children and parent, checked: every child in range, no node with two parents.
  void linkNodes(const json& nodes, std::vector<std::vector<std::size_t>>& children,
                 std::vector<std::size_t>& parent) const;
  /// Fails when a node is its own ancestor.
  void checkAcyclic(const std::vector<std::size_t>& parent) const;
  /// The nodes to walk from: the default scene's (or the first scene's), else every parentless node.
  std::vector<std::size_t> rootNodes(std::size_t nodeCount, const std::vector<std::size_t>& parent) const;
  /// The lights nodes may carry (KHR_lights_punctual): name, directional.
  std::vector<std::pair<std::string, bool>> lightDefinitions() const;
  void readPrimitive(Model& model, std::size_t meshIndex, std::size_t p, const mat4& world, const std::string& nodeName);
  /// Reads a primitive's optional attributes (NORMAL, TEXCOORD_0, TANGENT, COLOR_0), each of `vertices` elements.
  void readAttributes(Primitive& out, const json& attributes, const std::string& aw, std::size_t accessors,
                      std::size_t vertices) const;
  /// A primitive's corners: its indices, else its vertices in order.
  std::vector<std::uint32_t> primitiveCorners(const json& g, const std::string& where, std::size_t accessors,
                                              std::size_t vertices) const;
  int imageOfTexture(const json& textureInfo, const std::string& where);
  void readImages(Model& model);

  fs::path m_path;
  std::string m_name;
  ReadOptions m_options;
  ModelFence m_fence;
  std::vector<unsigned char> m_file;
  json m_json;
  std::vector<unsigned char> m_bin;  // a .glb's BIN chunk
  bool m_glb = false;
  std::vector<std::vector<unsigned char>> m_buffers;
  std::vector<View> m_views;
  std::vector<int> m_imageUse;  // images materials reference (1) or not (0)
  std::uint64_t m_instancedVertices = 0;
};

void Reader::parse() {
  std::error_code ec;
  if (!fs::is_regular_file(m_path, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", m_name);
  const auto size = fs::file_size(m_path, ec);
  if (ec) fail(ErrorKind::Input, "cannot read '{}': {}", m_name, ec.message());
  if (size > kMaxReferencedBytes) fail(ErrorKind::Input, "cannot read '{}': larger than glint reads ({} GiB)", m_name, kMaxReferencedBytes >> 30);
  std::ifstream in(m_path, std::ios::binary);
  m_file.resize(std::size_t(size));
  in.read(reinterpret_cast<char*>(m_file.data()), std::streamsize(m_file.size()));
  if (!in || std::size_t(in.gcount()) != m_file.size()) fail(ErrorKind::Input, "cannot read '{}': {}", m_name, std::strerror(errno));
  std::string_view text(reinterpret_cast<const char*>(m_file.data()), m_file.size());
  // A .glb: a 12-byte header, then chunks (length, type, data), the JSON chunk first.
  if (m_file.size() >= 4 && std::memcmp(m_file.data(), "glTF", 4) == 0) {
    static_assert(std::endian::native == std::endian::little, "GLB is read little-endian");
    m_glb = true;
    std::uint32_t header[3];
    if (m_file.size() < 20) bad("", "a .glb shorter than its header");
    std::memcpy(header, m_file.data(), 12);
    if (header[1] != 2) bad("", fmt::format("a .glb of version {} (glint reads glTF 2.0)", header[1]));
    if (header[2] > m_file.size()) bad("", fmt::format("the .glb header says {} bytes, the file has {}", header[2], m_file.size()));
    std::uint64_t at = 12;
    std::optional<std::string_view> jsonChunk;
    for (int chunk = 0; at + 8 <= header[2]; ++chunk) {
      std::uint32_t c[2];
      std::memcpy(c, m_file.data() + at, 8);
      at += 8;
      if (c[0] > header[2] - at) bad("", fmt::format("chunk {} of the .glb reaches past its end", chunk));
      if (chunk == 0 && c[1] != 0x4E4F534Au) bad("", "the .glb's first chunk is not its JSON");
      if (chunk == 0) jsonChunk = std::string_view(reinterpret_cast<const char*>(m_file.data() + at), c[0]);
      if (chunk == 1 && c[1] == 0x004E4942u) m_bin.assign(m_file.begin() + std::ptrdiff_t(at), m_file.begin() + std::ptrdiff_t(at + c[0]));
      at += c[0];
    }
    if (!jsonChunk) bad("", "the .glb has no JSON chunk");
    text = *jsonChunk;
  }
  // Nesting is checked before the JSON is parsed: a parser, or anything that walks the
  // result recursively, would run out of stack on [[[[... 100,000 deep.
  if (jsonDepth(text) > kMaxJsonDepth)
    bad("", fmt::format("its JSON nests deeper than {} levels (glTF needs about 10)", kMaxJsonDepth));
  m_json = json::parse(text, nullptr, false);
  if (m_json.is_discarded()) bad("", m_glb ? "the .glb's JSON chunk does not parse" : "not a glTF file (its JSON does not parse)");
  if (!m_json.is_object()) bad("", "its JSON is not an object");
  const json* asset = member(m_json, "asset", "");
  if (!asset) bad("", "no \"asset\" (not a glTF 2.0 file)");
  const std::string version = string(*asset, "version", "asset");
  if (version.empty() || version[0] != '2') bad("asset.version", fmt::format("is '{}' (glint reads glTF 2.0)", printable(version)));
  // Extensions a reader must understand to show the file right.
  for (const json& e : array(m_json, "extensionsRequired")) {
    const std::string name = e.is_string() ? e.get<std::string>() : "";
    if (name != "KHR_materials_unlit" && name != "KHR_texture_transform" && name != "KHR_mesh_quantization" &&
        name != "KHR_materials_emissive_strength" && name != "KHR_lights_punctual")
      bad("extensionsRequired", fmt::format("'{}' is not read by glint", printable(e.is_string() ? name : e.dump())));
  }
}

void Reader::readBuffers() {
  const json& buffers = array(m_json, "buffers");
  m_buffers.resize(buffers.size());
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    const std::string where = at("buffers", i);
    const std::uint64_t length = required(buffers[i], "byteLength", where);
    const std::string uri = string(buffers[i], "uri", where);
    std::vector<unsigned char>& data = m_buffers[i];
    if (uri.empty()) {
      if (!m_glb || i != 0) bad(where, "has no uri (only a .glb's first buffer is its BIN chunk)");
      data = m_bin;
    } else if (isDataUri(uri)) {
      std::string media;
      try {
        data = decodeDataUri(uri, media);
      } catch (const Error& e) {
        bad(where, e.what());
      }
    } else {
      data = m_fence.read(m_fence.resolve(uri, where), where);
    }
    // glTF: a buffer holds at least byteLength bytes (a BIN chunk is padded to 4).
    if (data.size() < length) bad(where, fmt::format("byteLength is {}, but its data has {} bytes", length, data.size()));
    data.resize(std::size_t(length));
  }
}

void Reader::checkViews() {
  const json& views = array(m_json, "bufferViews");
  m_views.resize(views.size());
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::string where = at("bufferViews", i);
    View& v = m_views[i];
    const auto buffer = index(views[i], "buffer", where, m_buffers.size(), "buffers");
    if (!buffer) bad(where, "has no \"buffer\"");
    v.buffer = *buffer;
    v.offset = integerOr(views[i], "byteOffset", where, 0);
    v.length = required(views[i], "byteLength", where);
    v.stride = integerOr(views[i], "byteStride", where, 0);
    const std::uint64_t size = m_buffers[v.buffer].size();
    // offset + length ≤ size, without the sum wrapping past 2^64.
    if (v.offset > size || v.length > size - v.offset)
      bad(where, fmt::format("bytes {}..{} lie outside buffer {} of {} bytes", v.offset, double(v.offset) + double(v.length), v.buffer, size));
    if (v.stride != 0 && (v.stride < 4 || v.stride > 252)) bad(field(where, "byteStride"), fmt::format("is {} (glTF: 4 to 252)", v.stride));
  }
}

Reader::AccessorInfo Reader::accessorInfo(std::size_t accessor) const {
  const json& a = array(m_json, "accessors")[accessor];
  const std::string where = at("accessors", accessor);
  AccessorInfo info;
  const auto type = integer(a, "componentType", where);
  if (!type || !(*type == 5120 || *type == 5121 || *type == 5122 || *type == 5123 || *type == 5125 || *type == 5126))
    bad(field(where, "componentType"), "is not a glTF component type");
  info.componentType = int(*type);
  const std::string t = string(a, "type", where);
  static const std::array<std::pair<const char*, int>, 7> kTypes{
      {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}}};
  for (const auto& [name, n] : kTypes)
    if (t == name) info.components = n;
  if (info.components == 0) bad(field(where, "type"), fmt::format("is '{}', not a glTF accessor type", printable(t)));
  if (t.starts_with("MAT")) bad(field(where, "type"), "a matrix accessor where glint reads vertex data");
  const json* normalized = member(a, "normalized", where);
  if (normalized && !normalized->is_boolean()) bad(field(where, "normalized"), "is not true or false");
  info.normalized = normalized && normalized->get<bool>();
  info.count = required(a, "count", where);
  if (info.count == 0) bad(field(where, "count"), "is 0 (glTF: at least 1)");
  return info;
}

namespace {
std::uint64_t componentSize(int type) { return type == kByte || type == kUnsignedByte ? 1 : type == kShort || type == kUnsignedShort ? 2 : 4; }

double component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case kByte: { const auto v = std::int8_t(*p); return normalized ? std::max(double(v) / 127.0, -1.0) : double(v); }
    case kUnsignedByte: return normalized ? double(*p) / 255.0 : double(*p);
    case kShort: { std::int16_t v; std::memcpy(&v, p, 2); return normalized ? std::max(double(v) / 32767.0, -1.0) : double(v); }
    case kUnsignedShort: { std::uint16_t v; std::memcpy(&v, p, 2); return normalized ? double(v) / 65535.0 : double(v); }
    case 5125: { std::uint32_t v; std::memcpy(&v, p, 4); return double(v); }
    default: { float v; std::memcpy(&v, p, 4); return double(v); }
  }
}
}  // namespace

void Reader::readElements(std::size_t accessor, const AccessorInfo& info, std::vector<double>& out) const {
  const json& a = array(m_json, "accessors")[accessor];
  const std::string where = at("accessors", accessor);
  const std::uint64_t size = componentSize(info.componentType), element = size * std::uint64_t(info.components);
  // Every element must lie inside the view: offset + stride·(count − 1) + element ≤ length,
  // checked by division so that no product or sum wraps.
  const auto checkRange = [&](std::size_t view, std::uint64_t offset, std::uint64_t count, std::uint64_t stride, const std::string& w) {
    const View& v = m_views[view];
    if (count == 0) return;
    if (offset > v.length || element > v.length - offset || (count - 1) > (v.length - offset - element) / stride)
      bad(w, fmt::format("{} elements of {} bytes from byte {} reach past bufferView {} ({} bytes)", count, element, offset, view, v.length));
  };
  if (info.count > m_file.size() + std::accumulate(m_buffers.begin(), m_buffers.end(), std::uint64_t(0),
                                                    [](std::uint64_t s, const auto& b) { return s + b.size(); }))
    bad(field(where, "count"), fmt::format("is {}, more elements than the file's data can hold", info.count));
  out.assign(std::size_t(info.count) * std::size_t(info.components), 0.0);
  if (const auto view = index(a, "bufferView", where, m_views.size(), "bufferViews")) {
    const View& v = m_views[*view];
    const std::uint64_t stride = v.stride ? v.stride : element;
    if (stride < element) bad(at("bufferViews", *view), fmt::format("byteStride {} is smaller than an element ({} bytes)", stride, element));
    const std::uint64_t offset = integerOr(a, "byteOffset", where, 0);
    checkRange(*view, offset, info.count, stride, where);
    const unsigned char* base = bufferOf(*view).data() + v.offset + offset;
    for (std::uint64_t i = 0; i < info.count; ++i)
      for (int c = 0; c < info.components; ++c)
        out[std::size_t(i) * std::size_t(info.components) + std::size_t(c)] =
            component(base + i * stride + std::uint64_t(c) * size, info.componentType, info.normalized);
  } else if (integer(a, "byteOffset", where)) {
    bad(where, "has a byteOffset but no bufferView");
  }
  // Sparse: `count` elements replaced, at indices read from their own view.
  if (const json* sparse = member(a, "sparse", where)) {
    const std::string w = field(where, "sparse");
    const std::uint64_t count = required(*sparse, "count", w);
    if (count == 0 || count > info.count) bad(field(w, "count"), fmt::format("is {} for an accessor of {} elements", count, info.count));
    const json* idx = member(*sparse, "indices", w);
    const json* val = member(*sparse, "values", w);
    if (!idx || !val) bad(w, "needs indices and values");
    const std::string wi = field(w, "indices"), wv = field(w, "values");
    const auto iv = index(*idx, "bufferView", wi, m_views.size(), "bufferViews");
    const auto vv = index(*val, "bufferView", wv, m_views.size(), "bufferViews");
    if (!iv || !vv) bad(w, "indices and values each need a bufferView");
    const std::uint64_t it = integerOr(*idx, "componentType", wi, 0);
    if (it != kUnsignedByte && it != kUnsignedShort && it != 5125) bad(field(wi, "componentType"), "is not an unsigned integer type");
    const std::uint64_t isize = componentSize(int(it)), ioff = integerOr(*idx, "byteOffset", wi, 0), voff = integerOr(*val, "byteOffset", wv, 0);
    {
      const View& v = m_views[*iv];
      if (ioff > v.length || (v.length - ioff) / isize < count) bad(wi, fmt::format("{} indices reach past bufferView {}", count, *iv));
      const View& w2 = m_views[*vv];
      if (voff > w2.length || (w2.length - voff) / element < count) bad(wv, fmt::format("{} values reach past bufferView {}", count, *vv));
    }
    const unsigned char* ib = bufferOf(*iv).data() + m_views[*iv].offset + ioff;
    const unsigned char* vb = bufferOf(*vv).data() + m_views[*vv].offset + voff;
    for (std::uint64_t k = 0; k < count; ++k) {
      const auto target = std::uint64_t(component(ib + k * isize, int(it), false));
      if (target >= info.count) bad(wi, fmt::format("index {} is {}, past the accessor's {} elements", k, target, info.count));
      for (int c = 0; c < info.components; ++c)
        out[std::size_t(target) * std::size_t(info.components) + std::size_t(c)] =
            component(vb + k * element + std::uint64_t(c) * size, info.componentType, info.normalized);
    }
  }
}

std::vector<float> Reader::floats(std::size_t accessor, std::initializer_list<int> accepted, const std::string& what, int& components) const {
  const AccessorInfo info = accessorInfo(accessor);
  if (std::find(accepted.begin(), accepted.end(), info.components) == accepted.end())
    bad(what, fmt::format("accessor {} has {} component{} per element, which this attribute does not take", accessor, info.components,
                          info.components == 1 ? "" : "s"));
  if (info.componentType == 5125) bad(what, fmt::format("accessor {} is of unsigned int, which glTF does not allow for vertex data", accessor));
  components = info.components;
  std::vector<double> values;
  readElements(accessor, info, values);
  std::vector<float> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]) || std::fabs(values[i]) > double(std::numeric_limits<float>::max()))
      bad(what, fmt::format("accessor {} element {} is not a finite number", accessor, i / std::size_t(components)));
    out[i] = float(values[i]);
  }
  return out;
}

std::vector<std::uint32_t> Reader::indices(std::size_t accessor, std::uint64_t vertexCount, const std::string& where) const {
  const AccessorInfo info = accessorInfo(accessor);
  if (info.components != 1 || (info.componentType != kUnsignedByte && info.componentType != kUnsignedShort && info.componentType != 5125))
    bad(where, fmt::format("accessor {} is not a list of unsigned integers", accessor));
  std::vector<double> values;
  readElements(accessor, info, values);
  std::vector<std::uint32_t> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] >= double(vertexCount)) bad(where, fmt::format("index {} is {}, but the primitive has {} vertices", i, values[i], vertexCount));
    out[i] = std::uint32_t(values[i]);
  }
  return out;
}

int Reader::imageOfTexture(const json& textureInfo, const std::string& where) {
  const json& textures = array(m_json, "textures");
  const auto texture = index(textureInfo, "index", where, textures.size(), "textures");
  if (!texture) bad(where, "has no \"index\"");
  const std::string tw = at("textures", *texture);
  const auto source = index(textures[*texture], "source", tw, array(m_json, "images").size(), "images");
  if (!source) return -1;  // a texture of an extension's image (KTX2, WebP): not read
  m_imageUse[*source] = 1;
  return int(*source);
}

void Reader::readMaterials(Model& model) {
  const json& materials = array(m_json, "materials");
  m_imageUse.assign(array(m_json, "images").size(), 0);
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const std::string where = at("materials", i);
    const json& g = materials[i];
    Material& m = model.materials.emplace_back();
    m.name = string(g, "name", where);
    const auto texture = [&](const json& object, const char* key, const std::string& w) -> int {
      const json* t = member(object, key, w);
      return t ? imageOfTexture(*t, field(w, key)) : -1;
    };
    if (const json* pbr = member(g, "pbrMetallicRoughness", where)) {
      const std::string w = field(where, "pbrMetallicRoughness");
      if (const auto c = numbers(*pbr, "baseColorFactor", w, 4); !c.empty()) m.baseColor = vec4(c[0], c[1], c[2], c[3]);
      m.metallic = float(number(*pbr, "metallicFactor", w, 1.0));
      m.roughness = float(number(*pbr, "roughnessFactor", w, 1.0));
      m.baseColorImage = texture(*pbr, "baseColorTexture", w);
      if (member(*pbr, "metallicRoughnessTexture", w)) model.dropped.push_back(field(where, "metallicRoughnessTexture"));
    }
    m.normalImage = texture(g, "normalTexture", where);
    m.occlusionImage = texture(g, "occlusionTexture", where);
    if (member(g, "emissiveTexture", where)) model.dropped.push_back(field(where, "emissiveTexture"));
    if (const json* ext = member(g, "extensions", where); ext && ext->is_object() && !ext->empty())
      model.dropped.push_back(field(where, "extensions"));
    // A bake's maps (glint bake --asset): extras.glint_maps = {name: {texture, order}}.
    const json* extras = member(g, "extras", where);
    const json* maps = extras && extras->is_object() ? member(*extras, "glint_maps", where) : nullptr;
    if (maps && maps->is_object()) {
      const std::string w = field(where, "extras.glint_maps");
      std::vector<std::pair<std::uint64_t, std::string>> order;
      for (const auto& [name, entry] : maps->items()) order.emplace_back(integerOr(entry, "order", field(w, name.c_str()), 0), name);
      std::sort(order.begin(), order.end());
      for (const auto& [_, name] : order) {
        const json& entry = (*maps)[name];
        const std::string e = field(w, name.c_str());
        const auto t = index(entry, "texture", e, array(m_json, "textures").size(), "textures");
        if (!t) bad(e, "has no \"texture\"");
        m.maps.emplace_back(name, imageOfTexture(json{{"index", *t}}, e));
      }
    }
  }
}

/// A primitive's triangles from its corners in glTF mode 4 (triangles), 5 (strip) or 6 (fan).
std::vector<std::uint32_t> triangulateCorners(std::uint64_t mode, std::vector<std::uint32_t> corners) {
  std::vector<std::uint32_t> out;
  if (mode == 4) {
    corners.resize(corners.size() / 3 * 3);
    out = std::move(corners);
  } else {  // 5 strip, 6 fan: as triangles, every other strip triangle turned to keep the winding
    for (std::size_t i = 2; i < corners.size(); ++i) {
      if (mode == 5) {
        const bool odd = i % 2 == 1;
        out.insert(out.end(), {corners[i - 2], corners[odd ? i : i - 1], corners[odd ? i - 1 : i]});
      } else {
        out.insert(out.end(), {corners[0], corners[i - 1], corners[i]});
      }
    }
  }
  return out;
}

void Reader::readPrimitive(Model& model, std::size_t meshIndex, std::size_t p, const mat4& world, const std::string& nodeName) {
  const json& mesh = array(m_json, "meshes")[meshIndex];
  const std::string mw = at("meshes", meshIndex);
  const json* prims = member(mesh, "primitives", mw);
  if (!prims || !prims->is_array()) bad(mw, "has no primitives array");
  const json& g = (*prims)[p];
  const std::string where = at(field(mw, "primitives"), p);
  const std::uint64_t mode = integerOr(g, "mode", where, 4);
  if (mode > 6) bad(field(where, "mode"), fmt::format("is {}, not a glTF primitive mode", mode));
  if (mode < 4) return;  // points and lines: nothing a triangle renderer draws
  const json* attributes = member(g, "attributes", where);
  if (!attributes || !attributes->is_object()) bad(where, "has no attributes");
  const std::string aw = field(where, "attributes");
  const std::size_t accessors = array(m_json, "accessors").size();
  const auto position = index(*attributes, "POSITION", aw, accessors, "accessors");
  if (!position) bad(where, "has no POSITION");
  Primitive out;
  out.world = world;
  out.node = nodeName;
  out.mesh = string(mesh, "name", mw);
  if (const auto material = index(g, "material", where, model.materials.size(), "materials")) out.material = int(*material);
  int n = 0;
  const std::vector<float> pos = floats(*position, {3}, field(aw, "POSITION"), n);
  const std::size_t vertices = pos.size() / 3;
  m_instancedVertices += vertices;
  if (m_instancedVertices > kMaxVertices)
    bad(where, fmt::format("the scene's instances make over {} vertices, more than glint reads", kMaxVertices));
  out.positions.resize(vertices);
  if (!pos.empty()) std::memcpy(out.positions.data(), pos.data(), pos.size() * sizeof(float));
  readAttributes(out, *attributes, aw, accessors, vertices);
  out.indices = triangulateCorners(mode, primitiveCorners(g, where, accessors, vertices));
  if (out.indices.empty()) return;
  model.primitives.push_back(std::move(out));
}

void Reader::readAttributes(Primitive& out, const json& attributes, const std::string& aw, std::size_t accessors,
                            std::size_t vertices) const {
  int n = 0;
  const auto same = [&](const std::vector<float>& v, int components, const char* name) {
    if (v.size() / std::size_t(components) != vertices)
      bad(field(aw, name), fmt::format("has {} elements for {} positions", v.size() / std::size_t(components), vertices));
  };
  if (const auto a = index(attributes, "NORMAL", aw, accessors, "accessors")) {
    const std::vector<float> v = floats(*a, {3}, field(aw, "NORMAL"), n);
    same(v, 3, "NORMAL");
    out.normals.resize(vertices);
    if (!v.empty()) std::memcpy(out.normals.data(), v.data(), v.size() * sizeof(float));
  }
  if (const auto a = index(attributes, "TEXCOORD_0", aw, accessors, "accessors")) {
    const std::vector<float> v = floats(*a, {2}, field(aw, "TEXCOORD_0"), n);
    same(v, 2, "TEXCOORD_0");
    out.uvs.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i) out.uvs[i] = vec2(v[2 * i], 1.0f - v[2 * i + 1]);  // glTF's t down → v up
  }
  if (const auto a = index(attributes, "TANGENT", aw, accessors, "accessors")) {
    const std::vector<float> v = floats(*a, {4}, field(aw, "TANGENT"), n);
    same(v, 4, "TANGENT");
    out.tangents.resize(vertices);
    if (!v.empty()) std::memcpy(out.tangents.data(), v.data(), v.size() * sizeof(float));
  }
  if (const auto a = index(attributes, "COLOR_0", aw, accessors, "accessors")) {
    int c = 0;
    const std::vector<float> v = floats(*a, {3, 4}, field(aw, "COLOR_0"), c);
    same(v, c, "COLOR_0");
    out.colors.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i)
      out.colors[i] = vec4(v[i * std::size_t(c)], v[i * std::size_t(c) + 1], v[i * std::size_t(c) + 2], c == 4 ? v[i * 4 + 3] : 1.0f);
  }
}

std::vector<std::uint32_t> Reader::primitiveCorners(const json& g, const std::string& where, std::size_t accessors,
                                                    std::size_t vertices) const {
  std::vector<std::uint32_t> corners;
  if (const auto a = index(g, "indices", where, accessors, "accessors")) {
    corners = indices(*a, vertices, field(where, "indices"));
  } else {
    if (vertices > std::numeric_limits<std::uint32_t>::max()) bad(where, "more vertices than 32-bit indices reach");
    corners.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i) corners[i] = std::uint32_t(i);
  }
  return corners;
}

mat4 localMatrix(const std::vector<double>& matrix, const std::vector<double>& t, const std::vector<double>& r, const std::vector<double>& s) {
  if (!matrix.empty()) {
    mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(matrix[std::size_t(i)]);
    return m;
  }
  mat4 m(1.0f);
  if (!t.empty()) m = glm::translate(m, vec3(t[0], t[1], t[2]));
  if (!r.empty()) m *= glm::mat4_cast(glm::quat(float(r[3]), float(r[0]), float(r[1]), float(r[2])));
  if (!s.empty()) m = glm::scale(m, vec3(s[0], s[1], s[2]));
  return m;
}

void Reader::linkNodes(const json& nodes, std::vector<std::vector<std::size_t>>& children,
                       std::vector<std::size_t>& parent) const {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string where = at("nodes", i);
    const json* c = member(nodes[i], "children", where);
    if (!c) continue;
    if (!c->is_array()) bad(field(where, "children"), "is not an array");
    for (std::size_t k = 0; k < c->size(); ++k) {
      const std::string cw = at(field(where, "children"), k);
      if (!(*c)[k].is_number_unsigned() || (*c)[k].get<std::uint64_t>() >= nodes.size())
        bad(cw, fmt::format("is {}, not one of the file's {} nodes", printable((*c)[k].dump()), nodes.size()));
      const auto child = std::size_t((*c)[k].get<std::uint64_t>());
      if (child == i) bad(cw, "is the node itself");
      if (parent[child] != SIZE_MAX) bad(cw, fmt::format("node {} has two parents (glTF nodes form trees)", child));
      parent[child] = i;
      children[i].push_back(child);
    }
  }
}

void Reader::checkAcyclic(const std::vector<std::size_t>& parent) const {
  // A cycle: walking up from any node never reaches a root. Marked nodes are known to
  // reach one, so each node is walked once.
  std::vector<char> state(parent.size(), 0);  // 0 unknown, 1 on the current walk, 2 reaches a root
  for (std::size_t i = 0; i < parent.size(); ++i) {
    std::size_t n = i;
    std::vector<std::size_t> walk;
    while (n != SIZE_MAX && state[n] == 0) {
      state[n] = 1;
      walk.push_back(n);
      n = parent[n];
    }
    if (n != SIZE_MAX && state[n] == 1) bad(at("nodes", n), "is its own ancestor (a cycle in the node tree)");
    for (std::size_t w : walk) state[w] = 2;
  }
}

std::vector<std::size_t> Reader::rootNodes(std::size_t nodeCount, const std::vector<std::size_t>& parent) const {
  // The roots: the default scene's (or the first scene's), else every parentless node.
  std::vector<std::size_t> roots;
  const json& scenes = array(m_json, "scenes");
  if (!scenes.empty()) {
    const std::size_t scene = index(m_json, "scene", "", scenes.size(), "scenes").value_or(0);
    const std::string sw = at("scenes", scene);
    const json* list = member(scenes[scene], "nodes", sw);
    if (list && !list->is_array()) bad(field(sw, "nodes"), "is not an array");
    std::set<std::size_t> seen;
    for (std::size_t k = 0; list && k < list->size(); ++k) {
      const json& r = (*list)[k];
      if (!r.is_number_unsigned() || r.get<std::uint64_t>() >= nodeCount)
        bad(at(field(sw, "nodes"), k),
            fmt::format("is {}, not one of the file's {} nodes", printable(r.dump()), nodeCount));
      const auto root = std::size_t(r.get<std::uint64_t>());
      if (parent[root] != SIZE_MAX) bad(at(field(sw, "nodes"), k), fmt::format("node {} is a child, not a root", root));
      if (!seen.insert(root).second) bad(at(field(sw, "nodes"), k), fmt::format("node {} is listed twice", root));
      roots.push_back(root);
    }
  } else {
    for (std::size_t i = 0; i < nodeCount; ++i)
      if (parent[i] == SIZE_MAX) roots.push_back(i);
  }
  return roots;
}

std::vector<std::pair<std::string, bool>> Reader::lightDefinitions() const {
  // The lights nodes may carry (KHR_lights_punctual).
  std::vector<std::pair<std::string, bool>> lightDefs;  // name, directional
  if (const json* ext = member(m_json, "extensions", ""); ext && ext->is_object())
    if (const json* lp = member(*ext, "KHR_lights_punctual", "extensions"); lp && lp->is_object())
      if (const json* lights = member(*lp, "lights", "extensions.KHR_lights_punctual"); lights && lights->is_array())
        for (std::size_t i = 0; i < lights->size(); ++i) {
          const std::string w = at("extensions.KHR_lights_punctual.lights", i);
          lightDefs.emplace_back(string((*lights)[i], "name", w), string((*lights)[i], "type", w) == "directional");
        }
  return lightDefs;
}

void Reader::readNodes(Model& model) {
  const json& nodes = array(m_json, "nodes");
  const std::size_t meshes = array(m_json, "meshes").size();
  // The node graph, checked as glTF requires before anything walks it: every child index
  // in range, no node with two parents, no cycle (a node its own ancestor).
  std::vector<std::vector<std::size_t>> children(nodes.size());
  std::vector<std::size_t> parent(nodes.size(), SIZE_MAX);
  linkNodes(nodes, children, parent);
  checkAcyclic(parent);
  const std::vector<std::size_t> roots = rootNodes(nodes.size(), parent);
  const std::vector<std::pair<std::string, bool>> lightDefs = lightDefinitions();
  // Depth first, pre-order, children in order: the order Assimp walks a scene in. An
  // explicit stack: a chain of 100,000 nodes is a file, not a crash.
  std::vector<std::pair<std::size_t, mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, mat4(1.0f));
  while (!stack.empty()) {
    const auto [i, parentWorld] = stack.back();
    stack.pop_back();
    const json& node = nodes[i];
    const std::string where = at("nodes", i);
    const auto matrix = numbers(node, "matrix", where, 16);
    const mat4 world = parentWorld * localMatrix(matrix, numbers(node, "translation", where, 3), numbers(node, "rotation", where, 4),
                                                 numbers(node, "scale", where, 3));
    for (int k = 0; k < 16; ++k)
      if (!std::isfinite(glm::value_ptr(world)[k])) bad(where, "its transform is not finite");
    const std::string name = string(node, "name", where);
    if (const auto mesh = index(node, "mesh", where, meshes, "meshes")) {
      const json* prims = member(array(m_json, "meshes")[*mesh], "primitives", at("meshes", *mesh));
      if (!prims || !prims->is_array()) bad(at("meshes", *mesh), "has no primitives array");
      for (std::size_t p = 0; p < prims->size(); ++p) readPrimitive(model, *mesh, p, world, name);
    }
    if (const json* ext = member(node, "extensions", where); ext && ext->is_object())
      if (const json* lp = member(*ext, "KHR_lights_punctual", field(where, "extensions")))
        if (const auto light = index(*lp, "light", field(where, "extensions.KHR_lights_punctual"), lightDefs.size(), "lights");
            light && !lightDefs[*light].second)
          model.lights.push_back({vec3(world[3]), lightDefs[*light].first});
    for (auto it = children[i].rbegin(); it != children[i].rend(); ++it) stack.emplace_back(*it, world);
  }
}

void Reader::readImages(Model& model) {
  const json& images = array(m_json, "images");
  model.images.resize(images.size());
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::string where = at("images", i);
    ImageBytes& out = model.images[i];
    out.name = string(images[i], "name", where);
    out.mimeType = string(images[i], "mimeType", where);
    const std::string uri = string(images[i], "uri", where);
    const auto view = index(images[i], "bufferView", where, m_views.size(), "bufferViews");
    if (!m_options.images || !m_imageUse[i]) continue;
    if (view) {
      const View& v = m_views[*view];
      const auto& data = bufferOf(*view);
      out.bytes.assign(data.begin() + std::ptrdiff_t(v.offset), data.begin() + std::ptrdiff_t(v.offset + v.length));
    } else if (isDataUri(uri)) {
      try {
        out.bytes = decodeDataUri(uri, out.mimeType);
      } catch (const Error& e) {
        bad(where, e.what());
      }
    } else {
      // A texture is not worth refusing the model for: outside the fence, it is left out.
      try {
        out.bytes = m_fence.read(m_fence.resolve(uri, where), where);
      } catch (const Error& e) {
        log::warn("{} (the texture is left out)", e.what());
        model.dropped.push_back(fmt::format("{} ('{}')", where, printable(uri)));
      }
    }
  }
}

Model Reader::read() {
  parse();
  readBuffers();
  checkViews();
  Model model;
  readMaterials(model);
  readNodes(model);
  readImages(model);
  if (const json* extras = member(m_json, "extras", "")) model.extras = *extras;
  return model;
}

}  // namespace

bool isGltf(const fs::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".gltf" || ext == ".glb";
}

Model read(const fs::path& path, const ReadOptions& options) {
  try {
    return Reader(path, options).read();
  } catch (const nlohmann::json::exception& e) {  // a guard: every access above checks its type first
    fail(ErrorKind::Input, "cannot read '{}': malformed glTF ({})", printable(path.string()), printable(e.what()));
  }
}

}  // namespace glint::gltf
