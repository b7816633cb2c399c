// The fast PLY path: Draco's PLY reader (draco::PlyReader: ASCII and binary little endian),
// its vertex and face properties mapped the way Assimp's PLY reader maps them. Big-endian
// files, triangle strips, per-face texture coordinates and points/lines go to Assimp.
#include "import_steps.h"

#include "glint/core/error.h"
#include "glint/core/text.h"

#include <draco/core/decoder_buffer.h>
#include <draco/io/ply_reader.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <unordered_set>
#include <vector>

namespace glint::detail {
namespace {

/// Reads property `p` of every entry as float, whatever its stored type.
std::vector<float> floats(const draco::PlyProperty& p, int count) {
  std::vector<float> out(static_cast<std::size_t>(count));
  const auto copy = [&](auto sample) {
    using T = decltype(sample);
    const auto* src = static_cast<const std::uint8_t*>(p.GetDataEntryAddress(0));
    for (int i = 0; i < count; ++i) {
      T value;
      std::memcpy(&value, src + std::size_t(i) * sizeof(T), sizeof(T));
      out[std::size_t(i)] = float(value);
    }
  };
  if (count == 0) return out;
  switch (p.data_type()) {
    case draco::DT_FLOAT32: std::memcpy(out.data(), p.GetDataEntryAddress(0), out.size() * 4); break;
    case draco::DT_FLOAT64: copy(double{}); break;
    case draco::DT_INT8: copy(std::int8_t{}); break;
    case draco::DT_UINT8: copy(std::uint8_t{}); break;
    case draco::DT_INT16: copy(std::int16_t{}); break;
    case draco::DT_UINT16: copy(std::uint16_t{}); break;
    case draco::DT_INT32: copy(std::int32_t{}); break;
    case draco::DT_UINT32: copy(std::uint32_t{}); break;
    default: throw Declined("a PLY property of an unusual type");
  }
  return out;
}

/// The last property of `element` with one of `names` (Assimp lets later ones win).
const draco::PlyProperty* find(const draco::PlyElement& element, std::initializer_list<const char*> names) {
  const draco::PlyProperty* found = nullptr;
  for (int i = 0; i < element.num_properties(); ++i) {
    for (const char* n : names) {
      if (element.property(i).name() == n) found = &element.property(i);
    }
  }
  return found;
}


enum class Format { Ascii, LittleEndian, BigEndian };

/// Bytes of a PLY scalar type, 0 for a name that is not one (the names Draco and Assimp read).
std::size_t typeSize(std::string_view type) {
  static constexpr std::pair<std::string_view, std::size_t> kTypes[] = {
      {"char", 1},  {"int8", 1},   {"uchar", 1}, {"uint8", 1},   {"short", 2},   {"int16", 2},
      {"ushort", 2}, {"uint16", 2}, {"int", 4},   {"int32", 4},   {"uint", 4},    {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& [n, size] : kTypes) {
    if (n == type) return size;
  }
  return 0;
}

/// Splits `line` at single spaces; empty when two spaces meet or the line starts or ends with one.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t at = 0;;) {
    const std::size_t blank = line.find(' ', at);
    out.push_back(line.substr(at, blank - at));
    if (out.back().empty()) return {};
    if (blank == std::string_view::npos) return out;
    at = blank + 1;
  }
}

/// The next word of a line, apart by blanks (empty at the line's end), removed from it.
std::string_view nextWord(std::string_view& text) {
  std::size_t b = 0;
  while (b < text.size() && (text[b] == ' ' || text[b] == '\t')) ++b;
  std::size_t e = b;
  while (e < text.size() && text[e] != ' ' && text[e] != '\t') ++e;
  const std::string_view word = text.substr(b, e - b);
  text.remove_prefix(e);
  return word;
}

/// The most properties a PLY element may declare.
constexpr std::size_t kMaxPlyProperties = 1024;

/// A property of a PLY element as the header declares it.
struct Property {
  std::size_t size = 0;       // of a value
  std::size_t countSize = 0;  // of a list's length; 0 for a scalar property
  bool signedCount = false;   // the length's type is char, short or int
  std::string_view name;
};

struct Element {
  std::string_view name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

/// A PLY header as read by readHeader: the format, the elements in order, and where the
/// body starts.
struct Layout {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t bodyOffset = 0;

  const Element* element(std::string_view n) const {
    for (const Element& e : elements) {
      if (e.name == n) return &e;
    }
    return nullptr;
  }
};

/// Reads a PLY header strictly (printable text, one space between words, known keywords
/// and types only, each element and property once, counts that fit in the file).
Layout readHeader(std::string_view file, const std::string& name) {
  const auto bad = [&](std::string_view what, std::string_view line) {
    fail(ErrorKind::Input, "cannot read mesh '{}': {} ('{}')", name, what, printable(line.substr(0, 80)));
  };
  Layout layout;
  std::size_t& at = layout.bodyOffset;
  const auto nextLine = [&]() -> std::optional<std::string_view> {
    if (at >= file.size()) return std::nullopt;
    const std::size_t eol = file.find('\n', at);
    if (eol == std::string_view::npos) return std::nullopt;  // a header line always ends
    std::string_view line = file.substr(at, eol - at);
    if (line.ends_with('\r')) line.remove_suffix(1);
    at = eol + 1;
    return line;
  };
  if (nextLine() != std::optional<std::string_view>("ply")) {
    fail(ErrorKind::Input, "cannot read mesh '{}': not a PLY file (it does not start with a 'ply' line)", name);
  }
  const std::optional<std::string_view> formatLine = nextLine();
  if (formatLine == "format ascii 1.0") layout.format = Format::Ascii;
  else if (formatLine == "format binary_little_endian 1.0") layout.format = Format::LittleEndian;
  else if (formatLine == "format binary_big_endian 1.0") layout.format = Format::BigEndian;
  else {
    fail(ErrorKind::Input, "cannot read mesh '{}': its second line is not a PLY format line ('{}')", name,
         printable(formatLine.value_or("").substr(0, 80)));
  }
  std::vector<Element>& elements = layout.elements;
  std::unordered_set<std::string_view> elementNames, propertyNames;
  for (;;) {
    const std::optional<std::string_view> line = nextLine();
    if (!line) fail(ErrorKind::Input, "cannot read mesh '{}': its PLY header has no end_header line", name);
    if (*line == "end_header") break;
    // Printable text only (a tab in a comment aside): Draco's reader also splits words at
    // vertical tabs and form feeds, and so read an element line here differently (an
    // 8e127 count; found by fuzz/mesh.cpp).
    const bool comment = line->starts_with("comment ") || *line == "comment" || line->starts_with("obj_info ");
    if (std::any_of(line->begin(), line->end(), [&](char c) { return std::uint8_t(c) < 0x20 && !(comment && c == '\t'); })) {
      bad("a control character in the PLY header", *line);
    }
    if (comment) continue;
    const std::vector<std::string_view> w = words(*line);
    if (w.size() == 3 && w[0] == "element") {
      // Each element once: the readers index elements by name, and Assimp frees what it
      // never allocated on a file with two (found by fuzz/mesh.cpp).
      if (!elementNames.insert(w[1]).second) bad("a PLY element declared twice", *line);
      propertyNames.clear();
      Element& e = elements.emplace_back();
      e.name = w[1];
      const auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (ec != std::errc() || end != w[2].data() + w[2].size() || e.count > file.size()) {
        bad("a PLY element count the file cannot hold", *line);
      }
    } else if (!w.empty() && w[0] == "property" && !elements.empty() && elements.back().properties.size() >= kMaxPlyProperties) {
      // Assimp's reader takes time quadratic in an element's properties (100,000 of them:
      // 11 s); real files have a few dozen (a Gaussian splat's vertex: 62).
      bad(fmt::format("a PLY element with more than {} properties", kMaxPlyProperties), *line);
    } else if (!w.empty() && w[0] == "property" && !elements.empty() && !propertyNames.insert(w.back()).second) {
      // Sets, not scans: a header of 100,000 properties is read in linear time.
      bad("a PLY property declared twice in one element", *line);
    } else if (w.size() == 3 && w[0] == "property" && !elements.empty() && typeSize(w[1]) != 0) {
      elements.back().properties.push_back({typeSize(w[1]), 0, false, w[2]});
    } else if (w.size() == 5 && w[0] == "property" && w[1] == "list" && !elements.empty() && typeSize(w[3]) != 0 &&
               typeSize(w[2]) != 0 && !w[2].starts_with("float") && w[2] != "double") {
      // Lists only where glint reads them (a face's vertex indices): Draco's reader reads
      // past the file for a list in a vertex element (SIGBUS; found by fuzz/mesh.cpp).
      if (elements.back().name != "face" && elements.back().name != "tristrips") {
        bad("a list property outside the face element", *line);
      }
      const bool signedCount = !w[2].starts_with('u');
      elements.back().properties.push_back({typeSize(w[3]), typeSize(w[2]), signedCount, w[4]});
    } else {
      bad("a PLY header line that is not a comment, element, property or end_header", *line);
    }
  }
  return layout;
}

/// What both readers need to make triangles: vertices with x, y and z, and faces (or
/// triangle strips) with a vertex_indices list. Anything else is refused here, not
/// handed to Assimp, whose reader misreads such files (a 32 GB allocation for a
/// big-endian file with other element names; found by fuzz/mesh.cpp).
void checkTriangleElements(const Layout& layout, const std::string& name) {
  const auto has = [](const Element* e, std::string_view n, bool list) {
    return e && std::any_of(e->properties.begin(), e->properties.end(),
                            [&](const Property& p) { return p.name == n && (p.countSize != 0) == list; });
  };
  const Element* vertex = layout.element("vertex");
  if (!has(vertex, "x", false) || !has(vertex, "y", false) || !has(vertex, "z", false)) {
    fail(ErrorKind::Input, "cannot read mesh '{}': the PLY has no vertex element with x, y and z", name);
  }
  const Element* faces = layout.element("face");
  const Element* strips = layout.element("tristrips");
  if (!has(faces, "vertex_indices", true) && !has(faces, "vertex_index", true) && !has(strips, "vertex_indices", true)) {
    fail(ErrorKind::Input, "cannot read mesh '{}': the PLY has no face element with a vertex_indices list", name);
  }
}

[[noreturn]] void failShortBody(const std::string& name, Format format, const Element& e) {
  fail(ErrorKind::Input, "cannot read mesh '{}': the file ends inside its {} element '{}' of {} entries", name,
       format == Format::Ascii ? "ASCII" : "binary", printable(e.name), e.count);
}

/// Walks an ASCII element's entries off the front of `body`: an entry per line, as the
/// format has it, of printable words apart by blanks. Draco reads words, Assimp reads
/// lines and stops a line at a NUL (an out-of-memory in Assimp on a line the two read
/// differently; found by fuzz/mesh.cpp).
void walkAsciiElement(std::string_view& body, const Element& e, const std::string& name) {
  for (std::uint64_t entry = 0; entry < e.count; ++entry) {
    if (body.empty()) failShortBody(name, Format::Ascii, e);
    const std::size_t eol = std::min(body.find('\n'), body.size());
    std::string_view line = body.substr(0, eol);
    body.remove_prefix(std::min(body.size(), eol + 1));
    if (line.ends_with('\r')) line.remove_suffix(1);
    const auto badEntry = [&](std::string_view why) {
      fail(ErrorKind::Input, "cannot read mesh '{}': entry {} of PLY element '{}' {}", name, entry, printable(e.name), why);
    };
    if (std::any_of(line.begin(), line.end(), [](char c) { return std::uint8_t(c) < 0x20 && c != '\t'; })) {
      badEntry("has a control character");
    }
    for (const Property& p : e.properties) {
      std::uint64_t values = 1;
      if (p.countSize) {
        const std::string_view word = nextWord(line);
        const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), values);
        if (ec != std::errc() || end != word.data() + word.size()) {
          badEntry(fmt::format("has a list length '{}' that is not a count", printable(word.substr(0, 40))));
        }
      }
      for (std::uint64_t v = 0; v < values; ++v) {
        if (nextWord(line).empty()) badEntry("has fewer values than its properties");
      }
    }
    if (!nextWord(line).empty()) badEntry("has more values than its properties");
  }
}

/// Walks a binary element's entries off the front of `body`, reading every list length.
void walkBinaryElement(std::string_view& body, Format format, const Element& e, const std::string& name) {
  const bool lists = std::any_of(e.properties.begin(), e.properties.end(), [](const Property& p) { return p.countSize; });
  if (!lists) {
    std::size_t stride = 0;
    for (const Property& p : e.properties) stride += p.size;
    if (e.count > body.size() / stride) failShortBody(name, format, e);
    body.remove_prefix(std::size_t(e.count) * stride);
    return;
  }
  for (std::uint64_t entry = 0; entry < e.count; ++entry) {
    for (const Property& p : e.properties) {
      std::uint64_t values = 1;
      if (p.countSize) {  // the length in the file's byte order
        if (body.size() < p.countSize) failShortBody(name, format, e);
        values = 0;
        for (std::size_t b = 0; b < p.countSize; ++b) {
          const std::size_t byte = format == Format::LittleEndian ? p.countSize - 1 - b : b;
          values = values << 8 | std::uint8_t(body[byte]);
        }
        // Draco reads a length unsigned, Assimp as its type says: a negative one is
        // refused, so that both read the same (Assimp reserved 32 GB for a char -1;
        // found by fuzz/mesh.cpp).
        if (p.signedCount && (values >> (8 * p.countSize - 1)) != 0) {
          fail(ErrorKind::Input, "cannot read mesh '{}': entry {} of PLY element '{}' has a negative list length", name,
               entry, printable(e.name));
        }
        body.remove_prefix(p.countSize);
      }
      if (values > body.size() / p.size) failShortBody(name, format, e);
      body.remove_prefix(std::size_t(values * p.size));
    }
  }
}

/// Checks a PLY file's header against the format's grammar (readHeader), that it has the
/// elements glint reads (checkTriangleElements), and its body against the header: the
/// body is walked (every list length read) and must hold every element. Whatever passes,
/// Draco's and Assimp's readers see the same elements glint saw and stay inside the
/// file. Fails with a one-line error.
Format checkLayout(std::string_view file, const std::string& name) {
  const Layout layout = readHeader(file, name);
  checkTriangleElements(layout, name);
  std::string_view body = file.substr(layout.bodyOffset);
  for (const Element& e : layout.elements) {
    if (e.count > 0 && e.properties.empty()) {
      fail(ErrorKind::Input, "cannot read mesh '{}': PLY element '{}' has {} entries but no properties", name,
           printable(e.name), e.count);
    }
    if (e.count == 0) continue;
    if (layout.format == Format::Ascii) {
      walkAsciiElement(body, e, name);
    } else {
      walkBinaryElement(body, layout.format, e, name);
    }
  }
  return layout.format;
}

/// The faces' corners from the vertex_indices list, whatever its integer type, into
/// mesh.faceStart and mesh.corners; every index checked against the vertex count.
void readFaces(const draco::PlyElement& face, const draco::PlyProperty& list, int vertexCount, const std::string& name,
               PolyMesh& mesh) {
  const int faceCount = face.num_entries();
  if (faceCount == 0) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  mesh.faceStart.resize(std::size_t(faceCount) + 1);
  std::size_t corners = 0;
  for (int f = 0; f < faceCount; ++f) {
    const std::int64_t n = list.GetListEntryNumValues(f);
    // No corners: corrupt (Assimp crashes or aborts on such files). 1–2: a point or line.
    if (n <= 0) fail(ErrorKind::Input, "cannot read mesh '{}': face {} has no corners", name, f);
    if (n < 3) throw Declined("a face with fewer than 3 corners");
    mesh.faceStart[std::size_t(f)] = std::uint32_t(corners);
    corners += std::size_t(n);
  }
  mesh.faceStart[std::size_t(faceCount)] = std::uint32_t(corners);
  mesh.corners.resize(corners);
  const auto* values = static_cast<const std::uint8_t*>(corners ? list.GetDataEntryAddress(0) : nullptr);
  const auto indexAt = [&](std::size_t i) -> std::int64_t {
    switch (list.data_type()) {
      case draco::DT_INT8: return std::int8_t(values[i]);
      case draco::DT_UINT8: return values[i];
      case draco::DT_INT16: { std::int16_t t; std::memcpy(&t, values + 2 * i, 2); return t; }
      case draco::DT_UINT16: { std::uint16_t t; std::memcpy(&t, values + 2 * i, 2); return t; }
      case draco::DT_INT32: { std::int32_t t; std::memcpy(&t, values + 4 * i, 4); return t; }
      case draco::DT_UINT32: { std::uint32_t t; std::memcpy(&t, values + 4 * i, 4); return t; }
      default: throw Declined("face indices of an unusual type");
    }
  };
  for (int f = 0; f < faceCount; ++f) {
    const std::size_t offset = std::size_t(list.GetListEntryOffset(f));
    for (std::uint32_t k = mesh.faceStart[std::size_t(f)]; k < mesh.faceStart[std::size_t(f) + 1]; ++k) {
      const std::int64_t index = indexAt(offset + (k - mesh.faceStart[std::size_t(f)]));
      if (index < 0 || index >= vertexCount) {
        fail(ErrorKind::Input, "cannot read mesh '{}': face {} refers to vertex {} of {}", name, f, index, vertexCount);
      }
      mesh.corners[k] = std::uint32_t(index);
    }
  }
}
}  // namespace

void checkPly(const std::filesystem::path& path) {
  const std::string name = path.string();
  const MappedFile file(path);
  if (file.size() == 0) fail(ErrorKind::Input, "cannot read mesh '{}': the file is empty", name);
  checkLayout(std::string_view(file.data(), file.size()), name);
}

Mesh loadPlyFast(const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string name = path.string();
  const MappedFile file(path);
  if (file.size() == 0) fail(ErrorKind::Input, "cannot read mesh '{}': the file is empty", name);
  // The whole layout is checked before either reader sees the file: Draco's reader trusts
  // element counts and reads past the end for fixed-size properties, and Assimp's (the
  // fallback) hangs or reads out of bounds on damaged headers (both found by fuzz/mesh.cpp).
  if (checkLayout(std::string_view(file.data(), file.size()), name) == Format::BigEndian) {
    throw Declined("big-endian PLY");  // Draco reads little endian and ASCII only
  }

  draco::DecoderBuffer buffer;
  buffer.Init(file.data(), file.size());
  draco::PlyReader reader;
  draco::Status status;
  try {
    status = reader.Read(&buffer);
  } catch (const std::exception& e) {  // std::length_error, std::bad_alloc: contained, not passed on
    fail(ErrorKind::Input, "cannot read mesh '{}': Draco's PLY reader failed ({})", name, e.what());
  }
  if (!status.ok()) fail(ErrorKind::Input, "cannot read mesh '{}': {}", name, status.error_msg_string());
  const draco::PlyElement* vertex = reader.GetElementByName("vertex");
  const draco::PlyElement* face = reader.GetElementByName("face");
  if (reader.GetElementByName("tristrips")) throw Declined("triangle strips");
  // checkLayout required vertices with x, y, z and (strips aside) faces.
  const draco::PlyProperty* x = vertex ? vertex->GetPropertyByName("x") : nullptr;
  const draco::PlyProperty* y = vertex ? vertex->GetPropertyByName("y") : nullptr;
  const draco::PlyProperty* z = vertex ? vertex->GetPropertyByName("z") : nullptr;
  if (!face || !x || !y || !z) fail(ErrorKind::Internal, "'{}': Draco's reading disagrees with the PLY layout check", name);
  const draco::PlyProperty* nx = vertex->GetPropertyByName("nx");
  const draco::PlyProperty* ny = vertex->GetPropertyByName("ny");
  const draco::PlyProperty* nz = vertex->GetPropertyByName("nz");
  if ((nx || ny || nz) && !(nx && ny && nz)) throw Declined("a partial normal");
  const draco::PlyProperty* u = find(*vertex, {"u", "s", "tx", "texture_u"});
  const draco::PlyProperty* v = find(*vertex, {"v", "t", "ty", "texture_v"});
  if ((u != nullptr) != (v != nullptr)) throw Declined("a partial texture coordinate");
  const draco::PlyProperty* list = face->GetPropertyByName("vertex_indices");
  if (!list) list = face->GetPropertyByName("vertex_index");
  // Not handed to Assimp either: it has no other name for them, and its reader
  // misreads such faces' other lists (found by fuzz/mesh.cpp).
  if (!list || !list->is_list()) fail(ErrorKind::Input, "cannot read mesh '{}': its PLY faces have no vertex_indices list", name);
  if (face->GetPropertyByName("texcoord")) throw Declined("per-face texture coordinates");

  const int vertexCount = vertex->num_entries();
  PolyMesh mesh;
  {
    const std::vector<float> px = floats(*x, vertexCount), py = floats(*y, vertexCount), pz = floats(*z, vertexCount);
    resizePositions(mesh.positions, std::size_t(vertexCount));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) mesh.positions[i] = vec3(px[i], py[i], pz[i]);
  }
  if (nx) {
    const std::vector<float> a = floats(*nx, vertexCount), b = floats(*ny, vertexCount), c = floats(*nz, vertexCount);
    mesh.normals.resize(std::size_t(vertexCount));
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) mesh.normals[i] = vec3(a[i], b[i], c[i]);
  }
  if (u) {
    const std::vector<float> a = floats(*u, vertexCount), b = floats(*v, vertexCount);
    mesh.uvs.resize(std::size_t(vertexCount));
    for (std::size_t i = 0; i < mesh.uvs.size(); ++i) mesh.uvs[i] = vec2(a[i], b[i]);
  }

  readFaces(*face, *list, vertexCount, name, mesh);

  // Before any step computes with them (the normal generator's grid, joining).
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      fail(ErrorKind::Input, "cannot read mesh '{}': vertex {} is not finite ({}, {}, {})", name, i, p.x, p.y, p.z);
    }
  }
  bool generated = false;
  Mesh result = finishPart(std::move(mesh), options.joinVertices, options.generateNormals, generated);
  warnMissingNormals(name, generated ? 1u : 0u, 1u);
  return result;
}

}  // namespace glint::detail
