#pragma once
// Private to glint_mesh: the fast OBJ/PLY importers and the post-processing they share.
//
// The fast paths must give the Mesh that the Assimp path gives (tests/mesh/import_oracle_test
// compares them), so they reproduce Assimp 5.2's steps in its order, on the same kind of
// intermediate mesh ("part" = one aiMesh: one OBJ object/group/material run, or a whole PLY):
//   triangulate (Assimp's rule: quads fan from their concave corner, n-gons by ear cutting)
//   → smooth normals where the part has none (Assimp's GenSmoothNormals on one vertex per
//     polygon corner) → join identical vertices (first occurrence keeps its place) → Mesh.
#include "glint/mesh/mesh.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint::detail {

/// A read-only memory mapping of a whole file.
class MappedFile {
public:
  /// Error(Input) naming the file when it cannot be opened or mapped.
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const char* data() const { return m_data; }
  std::size_t size() const { return m_size; }

private:
  const char* m_data = nullptr;
  std::size_t m_size = 0;
};

/// Sizes a mesh's positions to n with room for one more vertex: a ray tracer can then read
/// them in place (raytrace::SceneOptions::shareMeshes; Embree loads 16 bytes per vertex).
inline void resizePositions(std::vector<vec3>& positions, std::size_t n) {
  positions.reserve(n + 1);
  positions.resize(n);
}

/// Thrown by a fast path for a file it does not reproduce Assimp's reading of (PLY big
/// endian, OBJ vertex attributes present on some corners only, ...). loadMesh then reads
/// the file with Assimp; the reason is logged at debug level.
struct Declined : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// One Assimp-like mesh before post-processing: vertex attributes (normals and uvs empty
/// or one per vertex) and polygons as runs of vertex indices.
struct PolyMesh {
  std::vector<vec3> positions;
  std::vector<vec3> normals;
  std::vector<vec2> uvs;
  std::vector<std::uint32_t> corners;    ///< vertex index of every polygon corner
  std::vector<std::uint32_t> faceStart;  ///< face f is corners[faceStart[f] .. faceStart[f + 1]); size faces + 1
  /// True when every corner has its own vertex (OBJ): smooth normals need no expansion.
  bool perCorner = false;
};

/// Triangulates faces [first, last) of `mesh` the way Assimp's Triangulate step does,
/// appending corner positions (indices into mesh.corners, not vertices) to `out`, and
/// each face's triangle count to `perFace` when given.
void triangulate(const PolyMesh& mesh, std::size_t first, std::size_t last, std::vector<std::uint32_t>& out,
                 std::vector<std::uint32_t>* perFace = nullptr);

/// Assimp's NGON encoding (Triangulate, in a mesh with polygons): in face order, a triangle
/// whose first vertex is the previous triangle's first vertex is rotated; a quad's two
/// triangles are rotated together. `triangles` are vertex indices.
void encodeNgons(std::vector<std::uint32_t>& triangles, const std::vector<std::uint32_t>& perFace,
                 const std::vector<std::uint32_t>& faceSize);

/// Gives every polygon corner its own vertex (positions and uvs copied), so smooth
/// normals can be generated the way Assimp does on OBJ files. Returns the new corner →
/// vertex map's identity: after it, corners[i] == i.
void expandPerCorner(PolyMesh& mesh);

/// Assimp's GenSmoothNormals (no angle limit) on a mesh with one vertex per corner:
/// each vertex takes the unit normal of the last triangle using it; vertices closer than
/// 1e-4 of the bounding-box diagonal share the normalized sum. `triangles` are vertex indices.
std::vector<vec3> smoothNormals(const std::vector<vec3>& positions, const std::vector<std::uint32_t>& triangles);

/// Assimp's JoinIdenticalVertices: vertices at exactly the same position whose normals and
/// uvs differ by at most 1e-5 become one; representatives keep vertex order, unreferenced
/// vertices are dropped.
void joinVertices(Mesh& mesh);

/// The post-processing chain on one part, into a Mesh (normals unit length, as loadMesh's
/// identity node transform leaves them). A part without normals gets smooth ones when
/// `generateNormals` (and `generatedNormals` is set), or stays without.
Mesh finishPart(PolyMesh&& part, bool join, bool generateNormals, bool& generatedNormals);

/// Fast paths: the Mesh, with one warning for missing normals like the Assimp path; throws
/// Error(Input) for a corrupt file and Declined for one Assimp should read.
/// `fastLane` false leaves every line to tinyobjloader: the reading the lane is checked
/// against (tests/mesh/import_oracle_test.cpp, ImportOracle.ObjFastLane*; fuzz/mesh.cpp).
Mesh loadObjFast(const std::filesystem::path& path, const MeshLoadOptions& options, bool fastLane = true);
Mesh loadPlyFast(const std::filesystem::path& path, const MeshLoadOptions& options);
/// The fast PLY path's check of a file's whole layout (header grammar, the elements glint
/// reads, the body against the header), in linear time: what every PLY passes before
/// Assimp reads it. Error(Input), one line.
void checkPly(const std::filesystem::path& path);

/// "'file': N of M meshes have no normals; generating smooth normals" — the one warning
/// both paths log.
void warnMissingNormals(const std::string& name, unsigned missing, unsigned meshes);

}  // namespace glint::detail
