// Model files as the viewer reads them (scenes/model.h): glTF through glint's reader
// (mesh/gltf.h), the other formats through mesh/parts.h.
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/mesh/gltf.h"
#include "glint/mesh/parts.h"
#include "glint/mesh/tangents.h"
#include "glint/scenes/model.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include "glint/core/text.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint::scenes {

namespace fs = std::filesystem;

namespace {


/// A material's image, decoded; empty for none or one left out. A texture that does not
/// decode is the file's error.
Image decodedImage(const gltf::Model& m, int index, const std::string& file) {
  if (index < 0) return {};
  const gltf::ImageBytes& im = m.images[std::size_t(index)];
  if (im.bytes.empty()) return {};
  return decodeImage(im.bytes, fmt::format("{} images[{}]", file, index));
}

ModelMaterial readMaterial(const gltf::Model& m, const gltf::Material& g, const std::string& file) {
  ModelMaterial mat;
  mat.name = g.name;
  mat.baseColor = g.baseColor;
  mat.roughness = g.roughness;
  mat.baseColorMap = decodedImage(m, g.baseColorImage, file);
  mat.normalMap = decodedImage(m, g.normalImage, file);
  mat.occlusionMap = decodedImage(m, g.occlusionImage, file);
  // A bake's maps, in the table's order; else the material's own textures.
  if (!g.maps.empty()) {
    for (const auto& [name, image] : g.maps) mat.maps.emplace_back(name, decodedImage(m, image, file));
  } else {
    for (const auto& [name, image] : {std::pair{"base_color", &mat.baseColorMap}, std::pair{"normal", &mat.normalMap},
                                      std::pair{"ao", &mat.occlusionMap}})
      if (!image->empty()) mat.maps.emplace_back(name, *image);
  }
  return mat;
}

ModelFile loadGltf(const fs::path& path) {
  const std::string file = printable(path.string());
  gltf::Model m = gltf::read(path);
  ModelFile model;
  for (const gltf::Material& g : m.materials) model.materials.push_back(readMaterial(m, g, file));
  // A bake asset's record (extras.glint_bake): kept only as the object glint writes.
  if (m.extras.is_object() && m.extras.contains("glint_bake") && m.extras["glint_bake"].is_object())
    model.bake = m.extras["glint_bake"];
  model.dropped = std::move(m.dropped);
  for (gltf::Primitive& p : m.primitives) {
    ModelPart part;
    part.material = p.material;
    part.colors = std::move(p.colors);
    Mesh& mesh = part.mesh;
    mesh.positions = std::move(p.positions);
    mesh.normals = std::move(p.normals);
    mesh.uvs = std::move(p.uvs);
    mesh.tangents = std::move(p.tangents);
    mesh.indices = std::move(p.indices);
    mesh.validate("'" + file + "'");
    if (!mesh.hasNormals()) computeNormals(mesh);
    mesh.transform(p.world);
    model.parts.push_back(std::move(part));
  }
  return model;
}

}  // namespace

bool isModelFile(std::string_view name) {
  const std::string ext = lowerExtension(fs::path(name));
  return ext == ".glb" || ext == ".gltf" || ext == ".obj" || ext == ".ply" || ext == ".fbx";
}

ModelFile loadModelFile(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", path.string());
  ModelFile model;
  const std::string ext = lowerExtension(path);
  if (ext == ".glb" || ext == ".gltf") {
    model = loadGltf(path);
  } else {
    MeshParts parts = loadMeshParts(path);
    ModelPart part;
    part.mesh = std::move(parts.mesh);
    if (!part.mesh.hasNormals()) computeNormals(part.mesh);
    model.parts.push_back(std::move(part));
  }
  model.name = path.filename().string();
  std::size_t triangles = 0;
  for (ModelPart& part : model.parts) {
    triangles += part.mesh.triangleCount();
    // A normal map needs a tangent frame: MikkTSpace where the file has none (not where
    // vertex colours would have to be split along).
    const bool mapped = part.material >= 0 && !model.materials[std::size_t(part.material)].normalMap.empty();
    if (mapped && !part.mesh.hasTangents() && part.mesh.hasUvs() && part.colors.empty()) generateTangents(part.mesh);
  }
  if (triangles == 0) fail(ErrorKind::Input, "'{}' has no triangles to show", path.string());
  return model;
}

Bounds ModelFile::bounds() const {
  Bounds b{vec3(std::numeric_limits<float>::infinity()), vec3(-std::numeric_limits<float>::infinity())};
  for (const ModelPart& p : parts)
    for (const vec3& v : p.mesh.positions) {
      b.min = glm::min(b.min, v);
      b.max = glm::max(b.max, v);
    }
  return b;
}

std::vector<unsigned char> modelGlb(const ModelFile& model) {
  gltf::Document doc("glint view");
  nlohmann::json primitives = nlohmann::json::array();
  for (const ModelPart& part : model.parts) {
    const Mesh& m = part.mesh;
    const Bounds b = [&] {
      Bounds r{vec3(std::numeric_limits<float>::infinity()), vec3(-std::numeric_limits<float>::infinity())};
      for (const vec3& p : m.positions) r.min = glm::min(r.min, p), r.max = glm::max(r.max, p);
      return r;
    }();
    const std::size_t n = m.positions.size();
    nlohmann::json attributes = {
        {"POSITION", doc.addAccessor(m.positions.data(), n, gltf::kFloat, "VEC3", gltf::kVertices,
                                     {b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z})}};
    std::vector<vec3> normals(m.normals);
    for (vec3& v : normals) v = glm::length(v) > 0.0f ? glm::normalize(v) : vec3(0.0f, 0.0f, 1.0f);
    attributes["NORMAL"] = doc.addAccessor(normals.data(), n, gltf::kFloat, "VEC3", gltf::kVertices);
    if (m.hasUvs()) {
      std::vector<vec2> uvs(m.uvs);
      for (vec2& uv : uvs) uv.y = 1.0f - uv.y;
      attributes["TEXCOORD_0"] = doc.addAccessor(uvs.data(), n, gltf::kFloat, "VEC2", gltf::kVertices);
    }
    if (m.hasTangents()) attributes["TANGENT"] = doc.addAccessor(m.tangents.data(), n, gltf::kFloat, "VEC4", gltf::kVertices);
    if (!part.colors.empty()) attributes["COLOR_0"] = doc.addAccessor(part.colors.data(), n, gltf::kFloat, "VEC4", gltf::kVertices);
    nlohmann::json primitive = {{"attributes", attributes},
                                {"indices", doc.addAccessor(m.indices.data(), m.indices.size(), gltf::kUnsignedInt,
                                                            "SCALAR", gltf::kIndices)}};
    if (part.material >= 0) primitive["material"] = part.material;
    primitives.push_back(std::move(primitive));
  }
  nlohmann::json materials = nlohmann::json::array();
  for (const ModelMaterial& mat : model.materials) {
    const auto texture = [&](const Image& image, const std::string& name) {
      return doc.addTexture(doc.addImage(encodePng(image.type() == PixelType::F32 ? image.converted(PixelType::U16) : image), name));
    };
    nlohmann::json j = {{"name", mat.name},
                        {"pbrMetallicRoughness", {{"baseColorFactor", {mat.baseColor.r, mat.baseColor.g, mat.baseColor.b,
                                                                       mat.baseColor.a}},
                                                  {"metallicFactor", 0.0}, {"roughnessFactor", mat.roughness}}}};
    if (!mat.baseColorMap.empty()) j["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", texture(mat.baseColorMap, "base_color")}};
    if (!mat.normalMap.empty()) j["normalTexture"] = {{"index", texture(mat.normalMap, "normal")}};
    if (!mat.occlusionMap.empty()) j["occlusionTexture"] = {{"index", texture(mat.occlusionMap, "ao")}};
    nlohmann::json maps = nlohmann::json::object();
    int order = 0;
    for (const auto& [name, image] : mat.maps) maps[name] = {{"texture", texture(image, name)}, {"order", order++}};
    if (!maps.empty()) j["extras"] = {{"glint_maps", maps}};
    materials.push_back(std::move(j));
  }
  if (!materials.empty()) doc.json["materials"] = std::move(materials);
  doc.json["meshes"] = nlohmann::json::array({{{"name", model.name}, {"primitives", std::move(primitives)}}});
  doc.json["nodes"] = nlohmann::json::array({{{"name", model.name}, {"mesh", 0}}});
  doc.json["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
  doc.json["scene"] = 0;
  return doc.glb();
}

std::vector<std::string> ModelFile::mapNames() const {
  std::vector<std::string> names;
  for (const ModelMaterial& m : materials)
    for (const auto& [name, _] : m.maps)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

}  // namespace glint::scenes
