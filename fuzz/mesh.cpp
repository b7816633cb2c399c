// Fuzz harness: mesh import (mesh/mesh.h loadMesh), built three ways (fuzz/CMakeLists.txt):
//   fuzz_mesh_obj     the fast OBJ path (tinyobjloader on several threads, Assimp's rules)
//   fuzz_mesh_ply     the fast PLY path (Draco's reader)
//   fuzz_mesh_assimp  Assimp for every format it reads, chosen by the first byte
// The first byte also chooses whether vertices are joined. Whatever loads must be a mesh
// the rest of glint can trust: indices in range, finite positions, whole triangles.
#include "support.h"

#include "glint/core/log.h"
#include "glint/mesh/mesh.h"

#include <cmath>

namespace {

#if defined(GLINT_FUZZ_ASSIMP)
constexpr const char* kExtensions[] = {"obj", "ply", "gltf", "glb", "stl", "off", "fbx", "dae", "3ds", "x"};
constexpr glint::MeshParser kParser = glint::MeshParser::Assimp;
#elif defined(GLINT_FUZZ_PLY)
constexpr const char* kExtensions[] = {"ply"};
constexpr glint::MeshParser kParser = glint::MeshParser::Auto;
#else
constexpr const char* kExtensions[] = {"obj"};
constexpr glint::MeshParser kParser = glint::MeshParser::Auto;
#endif
constexpr std::size_t kExtensionCount = sizeof kExtensions / sizeof kExtensions[0];

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);  // warnings about odd files are expected here
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  if (size < 1) return 0;
  const std::uint8_t selector = data[0];
  const auto path = fuzz::inputFile({data + 1, size - 1}, kExtensions[(selector >> 1) % kExtensionCount]);
  fuzz::parse([&] {
    const Mesh mesh = loadMesh(path, {.joinVertices = (selector & 1) != 0, .parser = kParser});
    fuzz::check(mesh.indices.size() % 3 == 0, "whole triangles");
    fuzz::check(!mesh.indices.empty(), "a loaded mesh has triangles");
    for (std::uint32_t i : mesh.indices) fuzz::check(i < mesh.vertexCount(), "indices in range");
    for (const vec3& p : mesh.positions) fuzz::check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "finite positions");
    fuzz::check(mesh.normals.empty() || mesh.normals.size() == mesh.vertexCount(), "one normal per vertex");
    fuzz::check(mesh.uvs.empty() || mesh.uvs.size() == mesh.vertexCount(), "one uv per vertex");
  });
  return 0;
}
