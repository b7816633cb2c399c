// Fuzz harness: loadMeshParts (mesh/parts.h), the reader `glint render`, `glint view` and a
// bake with --material-id or --vertex-color use: glTF through glint's reader, PLY after
// its layout check, OBJ and FBX through Assimp behind the model fence. The extension comes
// from the bytes (fuzz/model_kind.h), so real model files seed it as they are.
#include "model_kind.h"
#include "support.h"

#include "glint/core/log.h"
#include "glint/mesh/parts.h"

#include <cmath>
#include <cstdint>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  const auto path = fuzz::inputFile({data, size}, fuzz::modelExtension(data, size));
  fuzz::parse([&] {
    const MeshParts parts = loadMeshParts(path, {.joinVertices = size % 2 == 0});
    const Mesh& mesh = parts.mesh;
    const std::size_t triangles = mesh.triangleCount();
    fuzz::check(triangles > 0 && mesh.indices.size() % 3 == 0, "whole triangles");
    for (std::uint32_t i : mesh.indices) fuzz::check(i < mesh.vertexCount(), "indices in range");
    for (const vec3& p : mesh.positions) fuzz::check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "finite positions");
    fuzz::check(parts.trianglePart.size() == triangles, "a part per triangle");
    for (std::uint32_t p : parts.trianglePart) fuzz::check(p < parts.partNames.size(), "part in range");
    fuzz::check(parts.triangleMaterial.empty() || parts.triangleMaterial.size() == triangles, "a material per triangle");
    for (std::uint32_t m : parts.triangleMaterial)
      fuzz::check(m == MeshParts::kNoMaterial || m < parts.materialNames.size(), "material in range");
    fuzz::check(parts.colors.empty() || parts.colors.size() == mesh.vertexCount(), "a colour per vertex");
  });
  return 0;
}
