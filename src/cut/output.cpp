#include "glint/cut/output.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/text.h"
#include "glint/mesh/gltf.h"

#include "lights.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <string_view>

namespace glint::cut {

namespace {

/// Polygon corner to start from: one whose neighbours both turn (see triangulate()).
std::size_t apex(const CutMesh& m, std::size_t p) {
  const std::size_t s = m.polygonStart[p], n = m.cornerCount(p);
  for (std::size_t i = 0; i < n; ++i)
    if (!m.straight[s + i] && !m.straight[s + (i + 1) % n] && !m.straight[s + (i + n - 1) % n]) return i;
  return 0;
}

void append(std::vector<unsigned char>& data, const void* p, std::size_t n) {
  const auto* b = static_cast<const unsigned char*>(p);
  data.insert(data.end(), b, b + n);
}

int addView(tinygltf::Model& model, std::size_t offset, std::size_t length, int target) {
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = offset;
  v.byteLength = length;
  v.target = target;
  model.bufferViews.push_back(v);
  return int(model.bufferViews.size() - 1);
}

/// One primitive of the glTF mesh: the triangles of one light mask, with their own
/// vertices (positions, grey COLOR_0) appended to `buffer`, and the mask in its extras.
tinygltf::Primitive addPrimitive(tinygltf::Model& model, tinygltf::Buffer& buffer, const Triangles& tris,
                                 const std::vector<std::uint32_t>& triangles, LightMask mask,
                                 const std::vector<Light>& lights) {
  std::vector<std::uint32_t> remap(tris.mesh.positions.size(), 0xFFFFFFFFu);
  std::vector<vec3> positions;
  std::vector<std::uint32_t> indices;
  for (std::uint32_t t : triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = tris.mesh.indices[3 * std::size_t(t) + std::size_t(k)];
      if (remap[v] == 0xFFFFFFFFu) {
        remap[v] = std::uint32_t(positions.size());
        positions.push_back(tris.mesh.positions[v]);
      }
      indices.push_back(remap[v]);
    }
  const vec3 colour = maskColor(mask, int(lights.size()));
  std::vector<vec3> colours(positions.size(), colour);
  vec3 lo(std::numeric_limits<float>::infinity()), hi(-lo);
  for (const vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const std::size_t posOffset = buffer.data.size();
  append(buffer.data, positions.data(), positions.size() * sizeof(vec3));
  const std::size_t colOffset = buffer.data.size();
  append(buffer.data, colours.data(), colours.size() * sizeof(vec3));
  const std::size_t idxOffset = buffer.data.size();
  append(buffer.data, indices.data(), indices.size() * 4);

  tinygltf::Accessor pos;
  pos.bufferView = addView(model, posOffset, positions.size() * sizeof(vec3), TINYGLTF_TARGET_ARRAY_BUFFER);
  pos.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pos.count = positions.size();
  pos.type = TINYGLTF_TYPE_VEC3;
  pos.minValues = {lo.x, lo.y, lo.z};
  pos.maxValues = {hi.x, hi.y, hi.z};
  model.accessors.push_back(pos);
  tinygltf::Accessor col = pos;
  col.bufferView = addView(model, colOffset, colours.size() * sizeof(vec3), TINYGLTF_TARGET_ARRAY_BUFFER);
  col.minValues.clear();
  col.maxValues.clear();
  model.accessors.push_back(col);
  tinygltf::Accessor idx;
  idx.bufferView = addView(model, idxOffset, indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  idx.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  idx.count = indices.size();
  idx.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(idx);

  tinygltf::Primitive prim;
  const int base = int(model.accessors.size()) - 3;
  prim.attributes["POSITION"] = base;
  prim.attributes["COLOR_0"] = base + 1;
  prim.indices = base + 2;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  return prim;  // extras: withExtras
}

/// A primitive's extras: {"light_mask": m (an unsigned integer), "lit_by": [names] (empty
/// when no light reaches the faces)}.
nlohmann::json primitiveExtras(LightMask mask, const std::vector<Light>& lights) {
  nlohmann::json litBy = nlohmann::json::array();
  for (std::size_t l = 0; l < lights.size(); ++l)
    if (mask & (LightMask(1) << l)) litBy.push_back(utf8Escaped(lightName(lights[l], l)));  // JSON text is UTF-8
  return {{"light_mask", mask}, {"lit_by", litBy}};
}

/// A node's KHR_lights_punctual reference, as the tinygltf at hand writes it: 2.9 (Debian
/// 13) keeps it in Node::light and writes the extension from that field alone (dropping one
/// set by hand while the field is -1); 2.7 (Debian 12) has no field and writes the
/// extension as given.
template <class Node>
void setLight(Node& node, int light) {
  if constexpr (requires { node.light; }) node.light = light;
  tinygltf::Value::Object ext;
  ext["light"] = tinygltf::Value(light);
  node.extensions["KHR_lights_punctual"] = tinygltf::Value(ext);
}

/// The lights as KHR_lights_punctual point lights, each on a node of `scene`.
void addLights(tinygltf::Model& model, tinygltf::Scene& scene, const std::vector<Light>& lights) {
  for (std::size_t l = 0; l < lights.size(); ++l) {
    tinygltf::Light light;
    light.name = utf8Escaped(lightName(lights[l], l));  // JSON text is UTF-8
    light.type = "point";
    light.color = {1.0, 1.0, 1.0};
    model.lights.push_back(light);
    tinygltf::Node ln;
    ln.name = light.name;
    ln.translation = {lights[l].position.x, lights[l].position.y, lights[l].position.z};
    setLight(ln, int(l));
    model.nodes.push_back(ln);
    scene.nodes.push_back(int(model.nodes.size() - 1));
  }
}

void saveGltf(const CutMesh& mesh, const std::vector<Light>& lights, const std::filesystem::path& path, bool binary) {
  const Triangles tris = triangulate(mesh);
  // Triangles grouped by mask, in mask order; each group its own vertices.
  std::map<LightMask, std::vector<std::uint32_t>> groups;
  for (std::uint32_t t = 0; t < tris.trianglePolygon.size(); ++t)
    groups[mesh.polygonMask[tris.trianglePolygon[t]]].push_back(t);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "glint cut";
  tinygltf::Buffer buffer;
  tinygltf::Mesh gm;
  gm.name = "cut";
  std::vector<nlohmann::json> extras;
  for (const auto& [mask, triangles] : groups) {
    gm.primitives.push_back(addPrimitive(model, buffer, tris, triangles, mask, lights));
    extras.push_back(primitiveExtras(mask, lights));
  }
  // tinygltf writes the JSON; glint puts in the extras and the buffer and writes the file.
  // tinygltf's extras (tinygltf::Value) would write every number as a double
  // ("light_mask": 1.0) and an empty list as null, and it would copy the buffer once more
  // (.glb) or hold it as base64 text twice (.gltf).
  const std::vector<unsigned char> bin = std::move(buffer.data);
  buffer.data.clear();
  model.buffers.push_back(std::move(buffer));
  model.meshes.push_back(std::move(gm));
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "cut";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  addLights(model, scene, lights);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  std::ostringstream written;
  if (!tinygltf::TinyGLTF().WriteGltfSceneToStream(&model, written, false, false))
    fail(ErrorKind::Output, "cannot write '{}'", path.string());
  nlohmann::json gltf = nlohmann::json::parse(written.str(), nullptr, false);
  if (gltf.is_discarded() || gltf["meshes"][0]["primitives"].size() != extras.size())
    fail(ErrorKind::Output, "cannot write '{}': tinygltf's JSON is not the model's", path.string());
  for (std::size_t i = 0; i < extras.size(); ++i) gltf["meshes"][0]["primitives"][i]["extras"] = extras[i];
  gltf::saveFile(path, std::move(gltf), bin, binary);  // one file either way: the write stays atomic
}

void savePly(const CutMesh& mesh, const std::vector<Light>& lights, const std::filesystem::path& path) {
  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\ncomment glint cut: light_mask bit l set = light l reaches the face\n";
  for (std::size_t l = 0; l < lights.size(); ++l)
    header << fmt::format("comment light {} {} {} {} {}\n", l, lightName(lights[l], l), lights[l].position.x,
                          lights[l].position.y, lights[l].position.z);
  header << "element vertex " << mesh.positions.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
         << "element face " << mesh.polygonCount() << "\nproperty list uchar uint vertex_indices\n"
         << "property uint light_mask\nproperty uint source\nproperty uchar red\nproperty uchar green\n"
         << "property uchar blue\nend_header\n";
  std::string data = header.str();
  static_assert(std::endian::native == std::endian::little, "PLY is written little-endian");
  data.append(reinterpret_cast<const char*>(mesh.positions.data()), mesh.positions.size() * sizeof(vec3));
  for (std::size_t p = 0; p < mesh.polygonCount(); ++p) {
    const std::size_t n = mesh.cornerCount(p);
    if (n > 255) fail(ErrorKind::Output, "'{}': a polygon with {} corners does not fit PLY's uchar count", path.string(), n);
    data.push_back(char(n));
    const std::size_t first = apex(mesh, p);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t v = mesh.corners[mesh.polygonStart[p] + (first + i) % n];
      data.append(reinterpret_cast<const char*>(&v), 4);
    }
    const std::uint32_t mask = mesh.polygonMask[p], source = mesh.polygonSource[p];
    data.append(reinterpret_cast<const char*>(&mask), 4);
    data.append(reinterpret_cast<const char*>(&source), 4);
    const vec3 c = maskColor(mask, int(lights.size()));
    for (float x : {c.r, c.g, c.b}) data.push_back(char(std::uint8_t(std::lround(x * 255.0f))));
  }
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(data.data(), std::streamsize(data.size()));
    if (!out) fail(ErrorKind::Output, "cannot write '{}'", path.string());
  });
}

}  // namespace

void checkOutputFormat(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".glb" && ext != ".gltf" && ext != ".ply")
    fail(ErrorKind::Usage, "cannot write '{}': the cut mesh is written as .glb, .gltf or .ply", path.string());
}

void saveCutMesh(const CutMesh& mesh, const std::vector<Light>& lights, const std::filesystem::path& path) {
  checkOutputFormat(path);
  const std::string ext = lowerExtension(path);
  if (ext == ".ply") savePly(mesh, lights, path);
  else saveGltf(mesh, lights, path, ext == ".glb");
}

vec3 maskColor(LightMask mask, int lightCount) {
  const int lit = std::popcount(mask & (lightCount >= 32 ? ~LightMask(0) : (LightMask(1) << lightCount) - 1));
  const float grey = 0.2f + 0.8f * float(lit) / float(std::max(1, lightCount));
  return vec3(grey);
}

Mesh loadScene(const std::vector<std::filesystem::path>& paths, std::vector<Light>* gltfLights) {
  Mesh scene;
  for (const auto& path : paths) {
    // Positions are all a cut needs: no normals generated (nor warned about).
    const Mesh part = loadMesh(path, {.generateNormals = false});
    if (scene.positions.empty()) scene = part;
    else scene.append(part);
    if (gltfLights)
      for (Light& l : loadGltfLights(path)) gltfLights->push_back(std::move(l));
  }
  return scene;
}

std::vector<Light> loadGltfLights(const std::filesystem::path& path) {
  if (!gltf::isGltf(path)) return {};
  // glint's one glTF reader (mesh/gltf.h): the nodes' KHR_lights_punctual point and spot
  // lights at their world positions, every index and transform checked.
  std::vector<Light> out;
  for (gltf::Light& l : gltf::read(path, {.images = false}).lights) out.push_back({l.position, std::move(l.name)});
  return out;
}

std::vector<LightMask> loadPlyMasks(const std::filesystem::path& path) {
  const std::string text = readTextFile(path);
  const std::size_t end = text.find("end_header\n");
  if (text.rfind("ply\n", 0) != 0 || end == std::string::npos || text.find("property uint light_mask") > end)
    fail(ErrorKind::Input, "'{}' is not a PLY written by glint cut", path.string());
  std::size_t vertices = 0, faces = 0;
  std::istringstream h(text.substr(0, end));
  std::string line;
  // A count that is not a number, or more elements than the file has bytes: not glint's PLY.
  const auto count = [&](std::string_view digits) {
    std::size_t n = 0;
    const auto [last, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (ec != std::errc() || last != digits.data() + digits.size() || n > text.size())
      fail(ErrorKind::Input, "'{}' is not a PLY written by glint cut (element count '{}')", path.string(), printable(digits));
    return n;
  };
  while (std::getline(h, line)) {
    if (line.rfind("element vertex ", 0) == 0) vertices = count(std::string_view(line).substr(15));
    if (line.rfind("element face ", 0) == 0) faces = count(std::string_view(line).substr(13));
  }
  std::size_t pos = end + 11 + vertices * 12;
  std::vector<LightMask> masks;
  for (std::size_t f = 0; f < faces; ++f) {
    if (pos >= text.size()) fail(ErrorKind::Input, "'{}' is truncated", path.string());
    const std::size_t n = std::uint8_t(text[pos]);
    pos += 1 + 4 * n;
    if (pos + 11 > text.size()) fail(ErrorKind::Input, "'{}' is truncated", path.string());
    LightMask m;
    std::memcpy(&m, text.data() + pos, 4);
    masks.push_back(m);
    pos += 11;
  }
  return masks;
}

}  // namespace glint::cut
