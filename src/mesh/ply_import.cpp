// The fast PLY path: Draco's PLY reader (draco::PlyReader: ASCII and binary little endian),
// its vertex and face properties mapped the way Assimp's PLY reader maps them. Big-endian
// files, triangle strips, per-face texture coordinates and points/lines go to Assimp.
#include "import_steps.h"

#include "glint/core/error.h"
#include "glint/core/text.h"

#include <draco/core/decoder_buffer.h>
#include <draco/io/ply_reader.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>

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

}  // namespace

Mesh loadPlyFast(const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string name = path.string();
  const MappedFile file(path);
  if (file.size() == 0) fail(ErrorKind::Input, "cannot read mesh '{}': the file is empty", name);
  // Draco reads little endian and ASCII only.
  const std::string_view head(file.data(), std::min<std::size_t>(file.size(), 4096));
  const std::size_t format = head.find("format ");
  // Not passed on to Assimp: its PLY reader (5.2.5) loops forever on some broken headers
  // (found by fuzz/mesh.cpp; upstream's PLY issues: assimp/assimp#6163).
  if (!head.starts_with("ply\n") && !head.starts_with("ply\r\n")) {
    fail(ErrorKind::Input, "cannot read mesh '{}': not a PLY file (it does not start with a 'ply' line)", name);
  }
  if (format == std::string_view::npos || head.find("end_header") == std::string_view::npos) {
    fail(ErrorKind::Input, "cannot read mesh '{}': its PLY header has no format line or no end_header", name);
  }
  // The header's frame exactly as the PLY format has it: Assimp's reader (the fallback for
  // what Draco's cannot read) hangs or reads out of bounds when the format line is damaged
  // or end_header is not followed by a line break (found by fuzz/mesh.cpp).
  const std::string_view formatLine = head.substr(format, head.find_first_of("\r\n", format) - format);
  if (formatLine != "format ascii 1.0" && formatLine != "format binary_little_endian 1.0" &&
      formatLine != "format binary_big_endian 1.0") {
    fail(ErrorKind::Input, "cannot read mesh '{}': unknown PLY format line '{}'", name, printable(formatLine));
  }
  // Element counts the file cannot hold (every element takes at least a byte) are refused
  // before Draco reserves memory for them (a 4 GB allocation; found by fuzz/mesh.cpp).
  for (std::size_t at = head.find("\nelement "); at != std::string_view::npos && at < head.find("end_header");
       at = head.find("\nelement ", at + 1)) {
    const std::string_view line = head.substr(at + 9, head.find_first_of("\r\n", at + 9) - (at + 9));
    const std::size_t blank = line.rfind(' ');
    std::size_t count = 0;
    const std::string_view digits = blank == std::string_view::npos ? std::string_view() : line.substr(blank + 1);
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), count);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || count > file.size()) {
      fail(ErrorKind::Input, "cannot read mesh '{}': PLY element line 'element {}' has a count the file cannot hold", name,
           printable(line));
    }
  }
  // List properties only where glint reads them (a face's vertex indices): Draco's reader
  // trusts a list's length and reads past the mapped file for one in a vertex element
  // (SIGBUS; found by fuzz/mesh.cpp).
  {
    std::string_view element;
    const std::string_view header = head.substr(0, head.find("end_header"));
    for (std::size_t at = 0; at < header.size();) {
      const std::size_t eol = std::min(header.find('\n', at), header.size());
      const std::string_view line = header.substr(at, eol - at);
      if (line.starts_with("element ")) element = line.substr(8, line.find(' ', 8) - 8);
      if (line.starts_with("property list") && element != "face" && element != "tristrips") {
        fail(ErrorKind::Input, "cannot read mesh '{}': its PLY element '{}' has a list property", name, printable(element));
      }
      at = eol + 1;
    }
  }
  const std::size_t headerEnd = head.find("end_header") + 10;
  if (!head.substr(headerEnd).starts_with("\n") && !head.substr(headerEnd).starts_with("\r\n")) {
    fail(ErrorKind::Input, "cannot read mesh '{}': its PLY header's end_header is not followed by a line break", name);
  }
  if (head.substr(format, 25).starts_with("format binary_big_endian")) throw Declined("big-endian PLY");

  draco::DecoderBuffer buffer;
  buffer.Init(file.data(), file.size());
  draco::PlyReader reader;
  if (const draco::Status status = reader.Read(&buffer); !status.ok()) {
    fail(ErrorKind::Input, "cannot read mesh '{}': {}", name, status.error_msg_string());
  }
  const draco::PlyElement* vertex = reader.GetElementByName("vertex");
  const draco::PlyElement* face = reader.GetElementByName("face");
  if (reader.GetElementByName("tristrips")) throw Declined("triangle strips");
  // A PLY without triangles to make is an error here, not handed to Assimp: it could only
  // fail too, and Assimp 5.2.5's binary PLY reader reads out of bounds on such files (found
  // by fuzz/mesh.cpp; fixed upstream after Debian 12's version, assimp/assimp#5310).
  if (!vertex || !face) {
    fail(ErrorKind::Input, "cannot read mesh '{}': the PLY has no {} element", name, !vertex ? "vertex" : "face");
  }
  const draco::PlyProperty* x = vertex->GetPropertyByName("x");
  const draco::PlyProperty* y = vertex->GetPropertyByName("y");
  const draco::PlyProperty* z = vertex->GetPropertyByName("z");
  if (!x || !y || !z) fail(ErrorKind::Input, "cannot read mesh '{}': its PLY vertices have no x, y and z", name);
  const draco::PlyProperty* nx = vertex->GetPropertyByName("nx");
  const draco::PlyProperty* ny = vertex->GetPropertyByName("ny");
  const draco::PlyProperty* nz = vertex->GetPropertyByName("nz");
  if ((nx || ny || nz) && !(nx && ny && nz)) throw Declined("a partial normal");
  const draco::PlyProperty* u = find(*vertex, {"u", "s", "tx", "texture_u"});
  const draco::PlyProperty* v = find(*vertex, {"v", "t", "ty", "texture_v"});
  if ((u != nullptr) != (v != nullptr)) throw Declined("a partial texture coordinate");
  const draco::PlyProperty* list = face->GetPropertyByName("vertex_indices");
  if (!list) list = face->GetPropertyByName("vertex_index");
  if (!list || !list->is_list()) throw Declined("faces without vertex_indices");
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

  // Faces: the list's values, whatever their integer type.
  const int faceCount = face->num_entries();
  if (faceCount == 0) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  mesh.faceStart.resize(std::size_t(faceCount) + 1);
  std::size_t corners = 0;
  for (int f = 0; f < faceCount; ++f) {
    const std::int64_t n = list->GetListEntryNumValues(f);
    // No corners: corrupt (Assimp crashes or aborts on such files). 1–2: a point or line.
    if (n <= 0) fail(ErrorKind::Input, "cannot read mesh '{}': face {} has no corners", name, f);
    if (n < 3) throw Declined("a face with fewer than 3 corners");
    mesh.faceStart[std::size_t(f)] = std::uint32_t(corners);
    corners += std::size_t(n);
  }
  mesh.faceStart[std::size_t(faceCount)] = std::uint32_t(corners);
  mesh.corners.resize(corners);
  const auto* values = static_cast<const std::uint8_t*>(corners ? list->GetDataEntryAddress(0) : nullptr);
  const auto indexAt = [&](std::size_t i) -> std::int64_t {
    switch (list->data_type()) {
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
    const std::size_t offset = std::size_t(list->GetListEntryOffset(f));
    for (std::uint32_t k = mesh.faceStart[std::size_t(f)]; k < mesh.faceStart[std::size_t(f) + 1]; ++k) {
      const std::int64_t index = indexAt(offset + (k - mesh.faceStart[std::size_t(f)]));
      if (index < 0 || index >= vertexCount) {
        fail(ErrorKind::Input, "cannot read mesh '{}': face {} refers to vertex {} of {}", name, f, index, vertexCount);
      }
      mesh.corners[k] = std::uint32_t(index);
    }
  }

  // Before any step computes with them (the normal generator's grid, joining).
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      fail(ErrorKind::Input, "cannot read mesh '{}': vertex {} is not finite ({}, {}, {})", name, i, p.x, p.y, p.z);
    }
  }
  bool generated = false;
  Mesh result = finishPart(std::move(mesh), options.joinVertices, generated);
  warnMissingNormals(name, generated ? 1u : 0u, 1u);
  return result;
}

}  // namespace glint::detail
