// loadMesh: every triangle mesh in a file, flattened into one Mesh via Assimp.
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/mesh/mesh.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <string>
#include <system_error>

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

}  // namespace

Mesh loadMesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", name);
  if (!std::filesystem::is_regular_file(path, ec)) fail(ErrorKind::Input, "cannot read '{}': not a regular file", name);

  Assimp::Importer importer;
  // Read with validation only, then post-process in steps:
  //  - this Assimp build keeps its internal asserts, and some loaders accept
  //    corrupt files (a truncated PLY yields a face with no indices) that then
  //    abort() inside Triangulate; faces are checked before any step runs;
  //  - normals are generated before JoinIdenticalVertices: Assimp's smooth-normal
  //    step needs one vertex per face corner (on joined vertices it would keep
  //    only the last face's normal), and we want to know whether to warn.
  const aiScene* scene = importer.ReadFile(name, aiProcess_ValidateDataStructure);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    fail(ErrorKind::Input, "cannot read mesh '{}': {}", name, firstLine(importer.GetErrorString()));
  }
  checkFaces(*scene, name);
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
  if (missingNormals > 0) {
    log::warn("'{}': {} of {} meshes have no normals; generating smooth normals", name, missingNormals,
              triangleMeshes);
  }
  // GenSmoothNormals leaves meshes that already have normals alone, and Assimp
  // runs the requested steps in its own fixed order (normals before joining).
  unsigned steps = aiProcess_GenSmoothNormals;
  if (options.joinVertices) steps |= aiProcess_JoinIdenticalVertices;
  scene = importer.ApplyPostProcessing(steps);
  if (!scene) fail(ErrorKind::Input, "cannot read mesh '{}': {}", name, firstLine(importer.GetErrorString()));

  Mesh result;
  flatten(*scene, *scene->mRootNode, mat4(1.0f), result);
  // Meshes that no node references would be lost by the walk; treat "nothing
  // drawable came out" the same as "no triangles".
  if (result.indices.empty()) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  result.validate(fmt::format("mesh '{}'", name));
  return result;
}

}  // namespace glint
