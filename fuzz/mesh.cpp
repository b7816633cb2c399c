// Fuzz harness: mesh import (mesh/mesh.h loadMesh), built three ways (fuzz/CMakeLists.txt):
//   fuzz_mesh_obj     the fast OBJ path (tinyobjloader on several threads, Assimp's rules),
//                     its fast lane checked against tinyobjloader alone on every input
//   fuzz_mesh_ply     the fast PLY path (Draco's reader)
//   fuzz_mesh_assimp  Assimp for every format it reads but glTF, chosen by the first byte
// The first byte also chooses whether vertices are joined. Whatever loads must be a mesh
// the rest of glint can trust: indices in range, finite positions, whole triangles.
#include "support.h"

#include "glint/core/log.h"
#include "glint/mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <optional>

#if !defined(GLINT_FUZZ_ASSIMP) && !defined(GLINT_FUZZ_PLY)
#include "import_steps.h"  // detail::loadObjFast with and without its fast lane
#endif

namespace {

#if defined(GLINT_FUZZ_ASSIMP)
// Not glTF: glint reads it itself (mesh/gltf.h; fuzz/gltf.cpp), and Assimp refuses it.
constexpr const char* kExtensions[] = {"obj", "ply", "stl", "off", "fbx", "dae", "3ds", "x"};
constexpr glint::MeshParser kParser = glint::MeshParser::Assimp;
#elif defined(GLINT_FUZZ_PLY)
constexpr const char* kExtensions[] = {"ply"};
constexpr glint::MeshParser kParser = glint::MeshParser::Auto;
#else
constexpr const char* kExtensions[] = {"obj"};
constexpr glint::MeshParser kParser = glint::MeshParser::Auto;
#endif

#if !defined(GLINT_FUZZ_ASSIMP) && !defined(GLINT_FUZZ_PLY)
/// The OBJ path's reading with its fast lane or with tinyobjloader alone: a Mesh, or the
/// outcome without one ("error", "declined").
struct Reading {
  std::optional<glint::Mesh> mesh;
  const char* outcome = "mesh";
};

Reading readObj(const std::filesystem::path& path, bool fastLane) {
  Reading r;
  try {
    r.mesh = glint::detail::loadObjFast(path, {.joinVertices = false}, fastLane);
  } catch (const glint::Error&) {
    r.outcome = "error";
  } catch (const glint::detail::Declined&) {
    r.outcome = "declined";
  }
  return r;
}

bool near(float a, float b) { return std::fabs(a - b) <= 2.4e-7f * std::max({1.0f, std::fabs(a), std::fabs(b)}); }

/// The fast lane reads what tinyobjloader reads: the same outcome, the same triangles,
/// positions and uvs within 2 ulps (the two round some decimal numbers differently).
void checkFastLane(const std::filesystem::path& path) {
  using glint::fuzz::check;
  const Reading lane = readObj(path, true), tiny = readObj(path, false);
  check(std::string_view(lane.outcome) == tiny.outcome, "the fast lane and tinyobjloader: the same outcome");
  if (!lane.mesh) return;
  const glint::Mesh &a = *lane.mesh, &b = *tiny.mesh;
  check(a.indices == b.indices && a.vertexCount() == b.vertexCount(), "the fast lane and tinyobjloader: the same triangles");
  check(a.hasUvs() == b.hasUvs() && a.hasNormals() == b.hasNormals(), "the fast lane and tinyobjloader: the same attributes");
  for (std::size_t i = 0; i < a.vertexCount(); ++i) {
    for (int k = 0; k < 3; ++k) check(near(a.positions[i][k], b.positions[i][k]), "the fast lane and tinyobjloader: positions");
    for (int k = 0; a.hasUvs() && k < 2; ++k) check(near(a.uvs[i][k], b.uvs[i][k]), "the fast lane and tinyobjloader: uvs");
  }
}
#endif

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);  // warnings about odd files are expected here
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  const auto input = fuzz::inputFile(data, size, kExtensions, /*selectorShift=*/1);  // bit 0: joinVertices
  if (!input) return 0;
  const std::filesystem::path& path = *input;
  const std::uint8_t selector = data[0];
  fuzz::parse([&] {
    const Mesh mesh = loadMesh(path, {.joinVertices = (selector & 1) != 0, .parser = kParser});
    fuzz::check(mesh.indices.size() % 3 == 0, "whole triangles");
    fuzz::check(!mesh.indices.empty(), "a loaded mesh has triangles");
    for (std::uint32_t i : mesh.indices) fuzz::check(i < mesh.vertexCount(), "indices in range");
    for (const vec3& p : mesh.positions) fuzz::check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "finite positions");
    fuzz::check(mesh.normals.empty() || mesh.normals.size() == mesh.vertexCount(), "one normal per vertex");
    fuzz::check(mesh.uvs.empty() || mesh.uvs.size() == mesh.vertexCount(), "one uv per vertex");
  });
#if !defined(GLINT_FUZZ_ASSIMP) && !defined(GLINT_FUZZ_PLY)
  checkFastLane(path);
#endif
  return 0;
}
