#pragma once
// glint/mesh/mesh.h — an indexed triangle mesh, its generators and its importer.
//
// Contents
//   Mesh             positions, normals, UVs, tangents, triangle indices (no GL inside)
//   make*            procedural generators (plane, grid, cube, UV sphere, icosphere, torus)
//   loadMesh         any format Assimp reads (OBJ, PLY, glTF/GLB, FBX, STL, ...); OBJ and PLY
//                    through faster parsers that give the same Mesh
//   computeNormals   area-weighted smooth vertex normals
//
// Conventions: right-handed, counter-clockwise front faces (OpenGL's default),
// UV origin at the lower left (OpenGL texture convention, v up). Optional
// attributes are either empty or exactly one per vertex.

#include "glint/core/math.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

struct Bounds {
  vec3 min{0.0f};
  vec3 max{0.0f};
  vec3 center() const { return 0.5f * (min + max); }
  vec3 extent() const { return max - min; }
  /// Length of the diagonal; 0 for an empty mesh.
  float diagonal() const { return glm::length(max - min); }
};

struct Mesh {
  std::vector<vec3> positions;
  std::vector<vec3> normals;        ///< empty, or one unit normal per vertex
  std::vector<vec2> uvs;            ///< empty, or one per vertex
  std::vector<vec4> tangents;       ///< empty, or xyz tangent + w = ±1 bitangent sign
  std::vector<std::uint32_t> indices;  ///< 3 per triangle, counter-clockwise front faces

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return indices.size() / 3; }
  bool hasNormals() const { return !normals.empty(); }
  bool hasUvs() const { return !uvs.empty(); }
  bool hasTangents() const { return !tangents.empty(); }

  Bounds bounds() const;
  /// Throws Error(Input) naming the problem: no triangles, index count not a multiple of 3,
  /// index out of range, attribute arrays of the wrong length, NaN/inf positions.
  void validate(const std::string& what = "mesh") const;
  /// Appends another mesh (indices rebased). Attributes are kept only if both have them.
  void append(const Mesh& other);
  /// Applies a transform: positions by `m`, normals by its inverse transpose, tangents by `m`
  /// itself (tangents lie in the surface); a mirroring `m` also flips winding and tangent w.
  void transform(const mat4& m);
};

/// Recomputes smooth normals: area-weighted average of incident face normals.
void computeNormals(Mesh& mesh);

/// Recomputes the normals loadMesh generates for a file without them: at each position, the
/// normalized sum of the unit normals of the faces there (positions closer than 1e-4 of the
/// bounding box's diagonal are one; Assimp's GenSmoothNormals). A mesh made from arrays and
/// the same mesh read from an OBJ, PLY or glTF file get the same normals, whatever their
/// vertices' sharing: what `glint bake` and glint.bake give a high or low poly without normals.
void generateSmoothNormals(Mesh& mesh);

/// Square in the XZ plane centred at the origin, normal +Y, UVs 0..uvScale.
Mesh makePlane(float size = 2.0f, float uvScale = 1.0f);
/// Like makePlane with (cellsX × cellsZ) quads; useful for displacement and tessellated grounds.
Mesh makeGrid(int cellsX, int cellsZ, float size = 2.0f, float uvScale = 1.0f);
/// Axis-aligned cube centred at the origin, 24 vertices (flat normals), each face UV 0..1.
Mesh makeCube(float size = 2.0f);
/// Latitude/longitude sphere; UV u along longitude, v from south (0) to north (1) pole.
Mesh makeUvSphere(float radius = 1.0f, int segments = 48, int rings = 24);
/// Subdivided icosahedron, vertices exactly on the sphere; no UVs.
Mesh makeIcosphere(float radius = 1.0f, int subdivisions = 3);
/// Torus around +Y: major radius R (centre to tube centre), minor radius r; UVs wrap once.
Mesh makeTorus(float majorRadius = 1.0f, float minorRadius = 0.35f, int segments = 64, int sides = 32);

/// Which parser reads a file.
enum class MeshParser {
  Auto,    ///< OBJ and PLY through the fast paths, anything else (and any file they decline) through Assimp
  Assimp,  ///< always Assimp: the reference the fast paths are tested and benchmarked against
  Fast,    ///< only the fast paths: Error(Input) for other formats and for files they decline
};

struct MeshLoadOptions {
  /// Join identical vertices into one indexed vertex (what a renderer wants). Files such
  /// as OBJ come in as one vertex per face corner; joining them costs about as much as
  /// parsing. A ray tracer does not need shared vertices: `glint bake` loads its high
  /// poly without.
  bool joinVertices = true;
  /// Generate smooth normals for meshes the file gives none (and log one warning saying so).
  /// Tools that use positions only (`glint cut`) turn this off: such meshes then come
  /// without normals (Mesh::normals empty), silently. Normals the file has are kept either way.
  bool generateNormals = true;
  /// The fast paths: OBJ on all cores (the file cut into chunks at line starts, parsed in
  /// parallel; the usual `v`/`vn`/`vt`/`f` lines by a std::from_chars lane, every other
  /// line by tinyobjloader), PLY through Draco's PLY reader (ASCII, binary little endian)
  /// after a strict check of the file's layout. They give the Mesh Assimp gives (tests/mesh/import_oracle_test.cpp)
  /// and hand files they do not reproduce Assimp's reading of to Assimp: big-endian PLY,
  /// OBJ faces with uvs or normals on some corners only, points and lines, ...
  MeshParser parser = MeshParser::Auto;
};

/// Loads every mesh in a file into one Mesh (node transforms applied, triangulated,
/// identical vertices joined unless asked not to). Error(Input) when the file is missing,
/// corrupt or has no triangles. Missing normals are generated as smooth normals, the
/// normalized sum of the unit normals of the faces at each position (a warning is logged),
/// unless options.generateNormals is off.
///
/// ```cpp
/// const glint::Mesh high = glint::loadMesh("statue.obj", {.joinVertices = false});  // for a ray tracer
/// const glint::Mesh reference = glint::loadMesh("statue.obj", {.parser = glint::MeshParser::Assimp});
/// const glint::Mesh shape = glint::loadMesh("statue.obj", {.generateNormals = false});  // positions are all it needs
/// ```
Mesh loadMesh(const std::filesystem::path& path, const MeshLoadOptions& options = {});

}  // namespace glint
