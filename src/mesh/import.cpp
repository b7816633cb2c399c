// loadMesh: every triangle mesh in a file, flattened into one Mesh: OBJ and PLY through the
// fast paths (obj_import.cpp, ply_import.cpp), everything else through Assimp.
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/text.h"
#include "glint/mesh/fence.h"
#include "glint/mesh/gltf.h"
#include "glint/mesh/mesh.h"
#include "glint/mesh/parts.h"

#include "import_steps.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

namespace glint {
namespace {

/// Assimp's matrices are row-major (a1..a4 is the first row); GLM is column-major.
mat4 toGlm(const aiMatrix4x4& m) {
  return glm::transpose(glm::make_mat4(&m.a1));
}

/// Assimp error strings can span lines; glint errors are one line.
std::string firstLine(const char* text) {
  std::string s = text ? text : "";
  if (const auto end = s.find_first_of("\r\n"); end != std::string::npos) s.resize(end);
  return s.empty() ? "unknown error" : s;
}

/// Copies the triangles of one aiMesh. After SortByPType a mesh holds one
/// primitive type; non-triangle meshes (points, lines) are skipped because a
/// triangle renderer cannot draw them, and returned empty.
Mesh convert(const aiMesh& in) {
  Mesh out;
  if (!(in.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return out;
  out.positions.reserve(in.mNumVertices);
  for (unsigned i = 0; i < in.mNumVertices; ++i) {
    out.positions.emplace_back(in.mVertices[i].x, in.mVertices[i].y, in.mVertices[i].z);
  }
  if (in.HasNormals()) {
    for (unsigned i = 0; i < in.mNumVertices; ++i) {
      out.normals.emplace_back(in.mNormals[i].x, in.mNormals[i].y, in.mNormals[i].z);
    }
  }
  // Only the first UV set: glint materials sample one. Assimp already delivers
  // v up (no aiProcess_FlipUVs), matching the OpenGL convention glint uses.
  if (in.HasTextureCoords(0)) {
    for (unsigned i = 0; i < in.mNumVertices; ++i) {
      out.uvs.emplace_back(in.mTextureCoords[0][i].x, in.mTextureCoords[0][i].y);
    }
  }
  out.indices.reserve(std::size_t(in.mNumFaces) * 3);
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    if (face.mNumIndices != 3) continue;  // defensive: Triangulate should leave none
    out.indices.insert(out.indices.end(), face.mIndices, face.mIndices + 3);
  }
  return out;
}

/// Rejects faces that would trip Assimp's internal asserts in later steps.
void checkFaces(const aiScene& scene, const std::string& name) {
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& m = *scene.mMeshes[i];
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      bool ok = face.mNumIndices > 0 && face.mIndices != nullptr;
      for (unsigned k = 0; ok && k < face.mNumIndices; ++k) ok = face.mIndices[k] < m.mNumVertices;
      if (!ok) fail(ErrorKind::Input, "cannot read mesh '{}': face {} of mesh {} is malformed", name, f, i);
    }
  }
}

/// Gives every face corner of a mesh without normals its own vertex. Assimp's smooth
/// normals take, per vertex, the normal of the last face using it and then average over
/// vertices at the same position: right for OBJ (one vertex per corner), but on shared
/// vertices (PLY, glTF) every vertex would get one face's normal. JoinIdenticalVertices
/// shares them again afterwards.
void expandForNormals(aiMesh& m) {
  if (m.HasNormals() || m.mNumBones > 0 || m.mNumAnimMeshes > 0 || m.HasTangentsAndBitangents()) return;
  std::vector<char> used(m.mNumVertices, 0);
  bool shared = false;
  unsigned corners = 0;
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    for (unsigned k = 0; k < m.mFaces[f].mNumIndices; ++k) {
      char& u = used[m.mFaces[f].mIndices[k]];
      shared = shared || u;
      u = 1;
    }
    corners += m.mFaces[f].mNumIndices;
  }
  if (!shared && corners == m.mNumVertices) return;
  const auto remap = [&](auto*& array) {
    if (!array) return;
    using T = std::remove_pointer_t<std::remove_reference_t<decltype(array)>>;
    T* out = new T[corners];
    unsigned c = 0;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      for (unsigned k = 0; k < m.mFaces[f].mNumIndices; ++k) out[c++] = array[m.mFaces[f].mIndices[k]];
    }
    delete[] array;
    array = out;
  };
  remap(m.mVertices);
  for (auto& channel : m.mTextureCoords) remap(channel);
  for (auto& channel : m.mColors) remap(channel);
  unsigned c = 0;
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    for (unsigned k = 0; k < m.mFaces[f].mNumIndices; ++k) m.mFaces[f].mIndices[k] = c++;
  }
  m.mNumVertices = corners;
}

/// Appends every mesh instance under `node`, baked with its accumulated transform.
/// This is what aiProcess_PreTransformVertices does, done here so that instanced
/// meshes are copied per node and mirrored nodes keep counter-clockwise winding
/// (Mesh::transform handles both normals and winding).
void flatten(const aiScene& scene, const aiNode& node, const mat4& parent, Mesh& result) {
  const mat4 world = parent * toGlm(node.mTransformation);
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    Mesh part = convert(*scene.mMeshes[node.mMeshes[i]]);
    if (part.indices.empty()) continue;
    part.transform(world);
    result.append(part);
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i) flatten(scene, *node.mChildren[i], world, result);
}


/// Assimp's file system, fenced: the model and the files inside its folder open, nothing
/// else (an OBJ's `mtllib ../../x`, an FBX's or a COLLADA's side files). A refused file is
/// one Assimp cannot open: it warns and goes on without it, as for a missing one.
class FencedIOSystem : public Assimp::DefaultIOSystem {
public:
  explicit FencedIOSystem(const std::filesystem::path& model) : m_fence(model) {}
  bool Exists(const char* file) const override { return m_fence.allows(file) && DefaultIOSystem::Exists(file); }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!m_fence.allows(file)) {
      log::warn("'{}': not reading '{}': a model may only reference files in its own folder", printable(m_fence.model().string()),
                printable(file));
      return nullptr;
    }
    return DefaultIOSystem::Open(file, mode);
  }

private:
  ModelFence m_fence;
};

/// One glTF primitive as the fast paths make a part (Assimp's steps: smooth normals where
/// it has none, vertices joined), placed by its node. A primitive with vertex colours keeps
/// its vertices (the colours stay one per vertex) and, without normals, gets Assimp's smooth
/// normals on one vertex per corner.
Mesh gltfPart(gltf::Primitive&& p, const MeshLoadOptions& options, bool& generated, std::vector<vec4>* colors) {
  Mesh mesh;
  if (p.colors.empty() || !colors) {
    detail::PolyMesh poly;
    poly.positions = std::move(p.positions);
    poly.normals = std::move(p.normals);
    poly.uvs = std::move(p.uvs);
    poly.faceStart.resize(p.indices.size() / 3 + 1);
    for (std::size_t f = 0; f < poly.faceStart.size(); ++f) poly.faceStart[f] = std::uint32_t(3 * f);
    poly.corners = std::move(p.indices);
    mesh = detail::finishPart(std::move(poly), options.joinVertices, options.generateNormals, generated);
    if (colors) colors->clear();
  } else {
    generated = options.generateNormals && p.normals.empty();
    if (generated) {
      const std::size_t n = p.indices.size();
      mesh.positions.resize(n);
      mesh.uvs.resize(p.uvs.empty() ? 0 : n);
      colors->resize(n);
      mesh.indices.resize(n);
      for (std::size_t c = 0; c < n; ++c) {
        const std::uint32_t v = p.indices[c];
        mesh.positions[c] = p.positions[v];
        if (!p.uvs.empty()) mesh.uvs[c] = p.uvs[v];
        (*colors)[c] = p.colors[v];
        mesh.indices[c] = std::uint32_t(c);
      }
      mesh.normals = detail::smoothNormals(mesh.positions, mesh.indices);
      for (vec3& n : mesh.normals) n = glm::length(n) > 0.0f ? glm::normalize(n) : n;
    } else {
      mesh.positions = std::move(p.positions);
      mesh.normals = std::move(p.normals);
      mesh.uvs = std::move(p.uvs);
      mesh.indices = std::move(p.indices);
      *colors = std::move(p.colors);
    }
  }
  mesh.transform(p.world);
  return mesh;
}

/// A glTF file through glint's reader (mesh/gltf.h) as parts: each primitive a part named
/// by its node (else its mesh), its material by name ("material N" when unnamed).
MeshParts loadGltfParts(const std::filesystem::path& path, const MeshLoadOptions& options, bool keepParts) {
  const std::string name = printable(path.string());
  gltf::Model model = gltf::read(path, {.images = false});
  MeshParts result;
  std::vector<char> hasColors;
  unsigned missingNormals = 0;
  const auto primitives = unsigned(model.primitives.size());
  for (gltf::Primitive& p : model.primitives) {
    std::string partName = !p.node.empty() ? p.node : p.mesh;
    std::uint32_t material = MeshParts::kNoMaterial;
    if (p.material >= 0) {
      const std::string& m = model.materials[std::size_t(p.material)].name;
      const std::string materialName = m.empty() ? fmt::format("material {}", p.material) : m;
      const auto found = std::find(result.materialNames.begin(), result.materialNames.end(), materialName);
      material = std::uint32_t(found - result.materialNames.begin());
      if (found == result.materialNames.end()) result.materialNames.push_back(materialName);
    }
    bool generated = false;
    std::vector<vec4> colors;
    const Mesh part = gltfPart(std::move(p), options, generated, keepParts ? &colors : nullptr);
    missingNormals += generated ? 1 : 0;
    if (!keepParts) {
      result.mesh.append(part);
      continue;
    }
    const auto it = std::find(result.partNames.begin(), result.partNames.end(), partName);
    const auto partIndex = std::uint32_t(it - result.partNames.begin());
    if (it == result.partNames.end()) result.partNames.push_back(partName);
    result.mesh.append(part);
    result.trianglePart.insert(result.trianglePart.end(), part.triangleCount(), partIndex);
    result.triangleMaterial.insert(result.triangleMaterial.end(), part.triangleCount(), material);
    result.colors.resize(result.mesh.vertexCount(), vec4(1.0f));
    hasColors.resize(result.mesh.vertexCount(), 0);
    std::copy(colors.begin(), colors.end(), result.colors.end() - std::ptrdiff_t(colors.size()));
    std::fill(hasColors.end() - std::ptrdiff_t(colors.size()), hasColors.end(), char(!colors.empty()));
  }
  if (options.generateNormals) detail::warnMissingNormals(name, missingNormals, primitives);
  if (result.mesh.indices.empty()) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  if (std::find(hasColors.begin(), hasColors.end(), 1) == hasColors.end()) result.colors.clear();
  if (std::all_of(result.triangleMaterial.begin(), result.triangleMaterial.end(),
                  [](std::uint32_t m) { return m == MeshParts::kNoMaterial; }))
    result.triangleMaterial.clear();
  return result;
}

/// The scene of a file after glint's post-processing (triangulated, normals generated,
/// vertices joined as the options say); Error(Input) when it has no triangles.
const aiScene& readScene(Assimp::Importer& importer, const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string name = path.string();
  // Read with validation only, then post-process in steps:
  //  - this Assimp build keeps its internal asserts, and some loaders accept
  //    corrupt files (a truncated PLY yields a face with no indices) that then
  //    abort() inside Triangulate; faces are checked before any step runs;
  //  - normals are generated before JoinIdenticalVertices: Assimp's smooth-normal
  //    step needs one vertex per face corner (on joined vertices it would keep
  //    only the last face's normal), and we want to know whether to warn.
  if (gltf::isGltf(path))
    fail(ErrorKind::Usage, "'{}': glTF is read by glint's own reader (mesh/gltf.h), not by Assimp", printable(name));
  // A PLY reaches Assimp only after the fast path's check of its whole layout, on every
  // path (MeshParser::Assimp too): Assimp 5.2's PLY reader hangs and crashes on damaged files.
  if (lowerExtension(path) == ".ply") detail::checkPly(path);
  importer.SetIOHandler(new FencedIOSystem(path));  // the importer owns it
  const aiScene* scene = importer.ReadFile(name, aiProcess_ValidateDataStructure);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    fail(ErrorKind::Input, "cannot read mesh '{}': {}", name, firstLine(importer.GetErrorString()));
  }
  checkFaces(*scene, name);
  if (options.generateNormals)
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) expandForNormals(*scene->mMeshes[i]);
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene) fail(ErrorKind::Input, "cannot read mesh '{}': {}", name, firstLine(importer.GetErrorString()));

  unsigned missingNormals = 0, triangleMeshes = 0;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh& m = *scene->mMeshes[i];
    if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    ++triangleMeshes;
    if (!m.HasNormals()) ++missingNormals;
  }
  if (triangleMeshes == 0) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  // GenSmoothNormals leaves meshes that already have normals alone, and Assimp
  // runs the requested steps in its own fixed order (normals before joining).
  unsigned steps = 0;
  if (options.generateNormals) {
    detail::warnMissingNormals(name, missingNormals, triangleMeshes);
    steps |= aiProcess_GenSmoothNormals;
  }
  if (options.joinVertices) steps |= aiProcess_JoinIdenticalVertices;
  scene = importer.ApplyPostProcessing(steps);
  if (!scene) fail(ErrorKind::Input, "cannot read mesh '{}': {}", name, firstLine(importer.GetErrorString()));
  return *scene;
}

Mesh loadWithAssimp(const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string name = path.string();
  Assimp::Importer importer;
  const aiScene* scene = &readScene(importer, path, options);
  Mesh result;
  flatten(*scene, *scene->mRootNode, mat4(1.0f), result);
  // Meshes that no node references would be lost by the walk; treat "nothing
  // drawable came out" the same as "no triangles".
  if (result.indices.empty()) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  return result;
}

/// flatten(), keeping each instance's part name, material and colours.
void flattenParts(const aiScene& scene, const aiNode& node, const mat4& parent, MeshParts& result,
                  std::vector<char>& hasColors) {
  const mat4 world = parent * toGlm(node.mTransformation);
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& in = *scene.mMeshes[node.mMeshes[i]];
    Mesh part = convert(in);
    if (part.indices.empty()) continue;
    part.transform(world);
    // The node's name is the object's (OBJ `o`/`g`, glTF/FBX nodes); Assimp names nodes it
    // makes up after the file or leaves them empty, so a named mesh is the fallback.
    std::string name = node.mName.C_Str();
    if ((name.empty() || &node == scene.mRootNode) && in.mName.length > 0) name = in.mName.C_Str();
    const auto it = std::find(result.partNames.begin(), result.partNames.end(), name);
    const auto partIndex = std::uint32_t(it - result.partNames.begin());
    if (it == result.partNames.end()) result.partNames.push_back(name);
    std::uint32_t material = MeshParts::kNoMaterial;
    if (in.mMaterialIndex < scene.mNumMaterials) {
      const aiString materialName = scene.mMaterials[in.mMaterialIndex]->GetName();
      const std::string m = materialName.C_Str();
      if (!m.empty() && m != AI_DEFAULT_MATERIAL_NAME) {
        const auto found = std::find(result.materialNames.begin(), result.materialNames.end(), m);
        material = std::uint32_t(found - result.materialNames.begin());
        if (found == result.materialNames.end()) result.materialNames.push_back(m);
      }
    }
    const std::size_t firstVertex = result.mesh.vertexCount();
    result.mesh.append(part);
    result.trianglePart.insert(result.trianglePart.end(), part.triangleCount(), partIndex);
    result.triangleMaterial.insert(result.triangleMaterial.end(), part.triangleCount(), material);
    result.colors.resize(result.mesh.vertexCount(), vec4(1.0f));
    hasColors.resize(result.mesh.vertexCount(), 0);
    if (in.HasVertexColors(0) && in.mNumVertices == part.vertexCount()) {
      for (unsigned v = 0; v < in.mNumVertices; ++v) {
        const aiColor4D& c = in.mColors[0][v];
        result.colors[firstVertex + v] = vec4(c.r, c.g, c.b, c.a);
        hasColors[firstVertex + v] = 1;
      }
    }
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i) flattenParts(scene, *node.mChildren[i], world, result, hasColors);
}

}  // namespace

MeshParts loadMeshParts(const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", name);
  if (!std::filesystem::is_regular_file(path, ec)) fail(ErrorKind::Input, "cannot read '{}': not a regular file", name);
  if (gltf::isGltf(path)) {
    MeshParts result = loadGltfParts(path, options, true);
    result.mesh.validate(fmt::format("mesh '{}'", name));
    return result;
  }
  Assimp::Importer importer;
  const aiScene& scene = readScene(importer, path, options);
  MeshParts result;
  std::vector<char> hasColors;
  flattenParts(scene, *scene.mRootNode, mat4(1.0f), result, hasColors);
  if (result.mesh.indices.empty()) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  result.mesh.validate(fmt::format("mesh '{}'", name));
  if (std::find(hasColors.begin(), hasColors.end(), 1) == hasColors.end()) result.colors.clear();
  if (std::all_of(result.triangleMaterial.begin(), result.triangleMaterial.end(),
                  [](std::uint32_t m) { return m == MeshParts::kNoMaterial; }))
    result.triangleMaterial.clear();
  return result;
}

Mesh loadMesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", name);
  if (!std::filesystem::is_regular_file(path, ec)) fail(ErrorKind::Input, "cannot read '{}': not a regular file", name);

  Mesh result;
  bool done = false;
  if (options.parser != MeshParser::Assimp) {
    const std::string ext = lowerExtension(path);
    try {
      if (ext == ".obj") {
        result = detail::loadObjFast(path, options);
        done = true;
      } else if (ext == ".ply") {
        result = detail::loadPlyFast(path, options);
        done = true;
      } else if (ext == ".gltf" || ext == ".glb") {
        result = loadGltfParts(path, options, false).mesh;
        done = true;
      } else if (options.parser == MeshParser::Fast) {
        fail(ErrorKind::Input, "cannot read mesh '{}': no fast parser for '{}' files", name, ext);
      }
    } catch (const detail::Declined& declined) {
      if (options.parser == MeshParser::Fast) {
        fail(ErrorKind::Input, "cannot read mesh '{}' with the fast parser: {}", name, declined.what());
      }
      log::debug("'{}': read with Assimp ({})", name, declined.what());
    }
  }
  if (!done) result = loadWithAssimp(path, options);
  if (result.indices.empty()) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  result.validate(fmt::format("mesh '{}'", name));
  return result;
}

}  // namespace glint
