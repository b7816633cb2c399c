// Model files as the viewer reads them (scenes/model.h): glTF through TinyGLTF, the other
// formats through mesh/parts.h.
#include "glint/core/error.h"
#include "glint/mesh/gltf.h"
#include "glint/mesh/parts.h"
#include "glint/mesh/tangents.h"
#include "glint/scenes/model.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>

namespace glint::scenes {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

/// An accessor's elements as floats (`components` each): float, or normalized unsigned
/// bytes and shorts (colours). Error(Input) for anything else.
std::vector<float> readFloats(const tinygltf::Model& m, int index, int components, const std::string& file) {
  const tinygltf::Accessor& a = m.accessors.at(std::size_t(index));
  if (tinygltf::GetNumComponentsInType(std::uint32_t(a.type)) != components)
    fail(ErrorKind::Input, "'{}': an accessor has {} components, {} expected", file,
         tinygltf::GetNumComponentsInType(std::uint32_t(a.type)), components);
  if (a.bufferView < 0) fail(ErrorKind::Input, "'{}': an accessor without a buffer view (sparse) is not read", file);
  const tinygltf::BufferView& v = m.bufferViews.at(std::size_t(a.bufferView));
  const auto& data = m.buffers.at(std::size_t(v.buffer)).data;
  const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
  if (size <= 0) fail(ErrorKind::Input, "'{}': an accessor of component type {} is not read", file, a.componentType);
  const std::size_t stride = v.byteStride ? v.byteStride : std::size_t(size * components);
  const std::size_t start = v.byteOffset + a.byteOffset;
  // Checked before anything is allocated: a count a corrupt file claims is not trusted.
  if (a.count > 0 && (a.count > data.size() || start + (a.count - 1) * stride + std::size_t(size * components) > data.size()))
    fail(ErrorKind::Input, "'{}': an accessor reaches past its buffer", file);
  std::vector<float> out(a.count * std::size_t(components), 0.0f);
  for (std::size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < components; ++c) {
      const unsigned char* p = data.data() + start + i * stride + std::size_t(c * size);
      float value = 0.0f;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&value, p, 4); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: value = float(*p) / 255.0f; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t s;
          std::memcpy(&s, p, 2);
          value = float(s) / 65535.0f;
          break;
        }
        default: fail(ErrorKind::Input, "'{}': an attribute of component type {} is not read", file, a.componentType);
      }
      out[i * std::size_t(components) + std::size_t(c)] = value;
    }
  return out;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& m, int index, const std::string& file) {
  const tinygltf::Accessor& a = m.accessors.at(std::size_t(index));
  if (a.bufferView < 0) fail(ErrorKind::Input, "'{}': indices without a buffer view", file);
  const tinygltf::BufferView& v = m.bufferViews.at(std::size_t(a.bufferView));
  const auto& data = m.buffers.at(std::size_t(v.buffer)).data;
  const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
  if (size != 1 && size != 2 && size != 4) fail(ErrorKind::Input, "'{}': indices of component type {}", file, a.componentType);
  const std::size_t stride = v.byteStride ? v.byteStride : std::size_t(size), start = v.byteOffset + a.byteOffset;
  if (a.count > 0 && (a.count > data.size() || start + (a.count - 1) * stride + std::size_t(size) > data.size()))
    fail(ErrorKind::Input, "'{}': the indices reach past their buffer", file);
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = data.data() + start + i * stride;
    std::uint32_t value = 0;
    std::memcpy(&value, p, std::size_t(size));  // little-endian: the low bytes
    out[i] = value;
  }
  return out;
}

/// A TinyGLTF value as JSON (extras).
nlohmann::json toJson(const tinygltf::Value& v) {
  if (v.IsBool()) return v.Get<bool>();
  if (v.IsInt()) return v.Get<int>();
  if (v.IsNumber()) return v.GetNumberAsDouble();
  if (v.IsString()) return v.Get<std::string>();
  if (v.IsArray()) {
    nlohmann::json a = nlohmann::json::array();
    for (std::size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(toJson(v.Get(int(i))));
    return a;
  }
  if (v.IsObject()) {
    nlohmann::json o = nlohmann::json::object();
    for (const std::string& k : v.Keys()) o[k] = toJson(v.Get(k));
    return o;
  }
  return nullptr;
}

Image textureImage(const tinygltf::Model& m, int texture, const std::string& file) {
  if (texture < 0 || std::size_t(texture) >= m.textures.size()) return {};
  const int source = m.textures[std::size_t(texture)].source;
  if (source < 0 || std::size_t(source) >= m.images.size()) return {};
  const tinygltf::Image& im = m.images[std::size_t(source)];
  if (im.width <= 0 || im.height <= 0 || im.component < 1 || im.component > 4 || im.image.empty())
    fail(ErrorKind::Input, "'{}': image {} could not be decoded", file, source);
  Image out(im.width, im.height, im.component, im.bits == 16 ? PixelType::U16 : PixelType::U8);
  if (out.bytes().size() != im.image.size()) fail(ErrorKind::Input, "'{}': image {} has the wrong size", file, source);
  std::memcpy(out.bytes().data(), im.image.data(), im.image.size());
  return out;
}

ModelMaterial readMaterial(const tinygltf::Model& m, const tinygltf::Material& g, const std::string& file) {
  ModelMaterial mat;
  mat.name = g.name;
  const auto& pbr = g.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() == 4)
    mat.baseColor = vec4(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]), float(pbr.baseColorFactor[2]),
                         float(pbr.baseColorFactor[3]));
  mat.roughness = float(pbr.roughnessFactor);
  mat.baseColorMap = textureImage(m, pbr.baseColorTexture.index, file);
  mat.normalMap = textureImage(m, g.normalTexture.index, file);
  mat.occlusionMap = textureImage(m, g.occlusionTexture.index, file);
  // A bake's maps, in the table's order; else the material's own textures.
  const tinygltf::Value& maps = g.extras.Get("glint_maps");
  if (maps.IsObject()) {
    std::vector<std::pair<int, std::string>> order;
    for (const std::string& k : maps.Keys()) order.emplace_back(maps.Get(k).Get("order").GetNumberAsInt(), k);
    std::sort(order.begin(), order.end());
    for (const auto& [_, k] : order) mat.maps.emplace_back(k, textureImage(m, maps.Get(k).Get("texture").GetNumberAsInt(), file));
  } else {
    for (const auto& [name, image] : {std::pair{"base_color", &mat.baseColorMap}, std::pair{"normal", &mat.normalMap},
                                      std::pair{"ao", &mat.occlusionMap}})
      if (!image->empty()) mat.maps.emplace_back(name, *image);
  }
  return mat;
}

mat4 nodeMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(n.matrix[std::size_t(i)]);
    return m;
  }
  mat4 m(1.0f);
  if (n.translation.size() == 3) m = glm::translate(m, vec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4)
    m *= glm::mat4_cast(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2])));
  if (n.scale.size() == 3) m = glm::scale(m, vec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

ModelPart readPrimitive(const tinygltf::Model& m, const tinygltf::Primitive& p, const mat4& world, const std::string& file) {
  ModelPart part;
  part.material = p.material;
  Mesh& mesh = part.mesh;
  const auto attribute = [&](const char* name) { const auto it = p.attributes.find(name); return it == p.attributes.end() ? -1 : it->second; };
  const int position = attribute("POSITION");
  if (position < 0) fail(ErrorKind::Input, "'{}': a primitive has no POSITION", file);
  const std::vector<float> pos = readFloats(m, position, 3, file);
  for (std::size_t i = 0; i < pos.size(); i += 3) mesh.positions.emplace_back(pos[i], pos[i + 1], pos[i + 2]);
  if (const int a = attribute("NORMAL"); a >= 0) {
    const std::vector<float> n = readFloats(m, a, 3, file);
    for (std::size_t i = 0; i < n.size(); i += 3) mesh.normals.emplace_back(n[i], n[i + 1], n[i + 2]);
  }
  if (const int a = attribute("TEXCOORD_0"); a >= 0) {
    const std::vector<float> t = readFloats(m, a, 2, file);
    for (std::size_t i = 0; i < t.size(); i += 2) mesh.uvs.emplace_back(t[i], 1.0f - t[i + 1]);  // glTF's t down → v up
  }
  if (const int a = attribute("TANGENT"); a >= 0) {
    const std::vector<float> t = readFloats(m, a, 4, file);
    for (std::size_t i = 0; i < t.size(); i += 4) mesh.tangents.emplace_back(t[i], t[i + 1], t[i + 2], t[i + 3]);
  }
  if (const int a = attribute("COLOR_0"); a >= 0) {
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(m.accessors.at(std::size_t(a)).type));
    const std::vector<float> c = readFloats(m, a, components, file);
    for (std::size_t i = 0; i + std::size_t(components) <= c.size(); i += std::size_t(components))
      part.colors.emplace_back(c[i], c[i + 1], c[i + 2], components == 4 ? c[i + 3] : 1.0f);
  }
  if (p.indices >= 0) {
    mesh.indices = readIndices(m, p.indices, file);
  } else {
    for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
  }
  mesh.indices.resize(mesh.indices.size() / 3 * 3);
  mesh.validate("'" + file + "'");
  if (!mesh.hasNormals()) computeNormals(mesh);
  mesh.transform(world);
  return part;
}

ModelFile loadGltf(const fs::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string error, warning;
  const std::string file = path.string();
  const bool ok = lowerExtension(path) == ".glb" ? loader.LoadBinaryFromFile(&m, &error, &warning, file)
                                                 : loader.LoadASCIIFromFile(&m, &error, &warning, file);
  if (!ok) {
    std::replace(error.begin(), error.end(), '\n', ' ');
    fail(ErrorKind::Input, "cannot read '{}': {}", file, error.empty() ? "not a glTF file" : error);
  }
  ModelFile model;
  for (const tinygltf::Material& g : m.materials) model.materials.push_back(readMaterial(m, g, file));
  if (m.extras.Has("glint_bake")) model.bake = toJson(m.extras.Get("glint_bake"));
  const std::function<void(int, const mat4&)> visit = [&](int index, const mat4& parent) {
    const tinygltf::Node& node = m.nodes.at(std::size_t(index));
    const mat4 world = parent * nodeMatrix(node);
    if (node.mesh >= 0)
      for (const tinygltf::Primitive& p : m.meshes.at(std::size_t(node.mesh)).primitives)
        if (p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1) model.parts.push_back(readPrimitive(m, p, world, file));
    for (int child : node.children) visit(child, world);
  };
  const int scene = m.defaultScene >= 0 ? m.defaultScene : 0;
  if (std::size_t(scene) < m.scenes.size())
    for (int root : m.scenes[std::size_t(scene)].nodes) visit(root, mat4(1.0f));
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
    try {
      model = loadGltf(path);
    } catch (const std::out_of_range&) {  // an index into an array the file does not have
      fail(ErrorKind::Input, "cannot read '{}': an index points past the end of its array", path.string());
    }
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
