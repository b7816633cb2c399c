// The fast OBJ/PLY paths against Assimp (the oracle): the same file read both ways
// must give the same Mesh.
//
// What "the same" means, exactly: the same vertex count and the same triangle index
// list, element for element (same triangulation, same vertex order, same joining);
// positions and uvs equal within 2 ulps (relative 2.4e-7) — tinyobjloader and Assimp parse
// decimal text with different float routines, which may round the last bit differently;
// normals within 1e-5 (file normals are normalized the same way; generated normals sum
// the same face normals in a different order).
#include "glint/core/error.h"
#include "glint/mesh/gltf.h"
#include "glint/mesh/mesh.h"
#include "import_steps.h"  // detail::loadObjFast without its fast lane

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include "support/files.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;

namespace {

fs::path outDir() { return glint::testing::testOutputDir("mesh-oracle"); }

fs::path writeFile(const std::string& name, const std::string& contents) {
  return glint::testing::writeTestFile(outDir(), name, contents);
}

using glint::testing::captureError;

bool near(float a, float b, float relative) {
  return std::fabs(a - b) <= relative * std::max(1.0f, std::max(std::fabs(a), std::fabs(b)));
}

/// Compares two readings of one file as stated at the top of this file.
void expectSameMesh(const Mesh& fast, const Mesh& other, const char* otherName) {
  EXPECT_EQ(fast.vertexCount(), other.vertexCount());
  EXPECT_EQ(fast.indices, other.indices) << "same triangles, same vertex order";
  EXPECT_EQ(fast.hasNormals(), other.hasNormals());
  EXPECT_EQ(fast.hasUvs(), other.hasUvs());
  if (fast.vertexCount() != other.vertexCount()) return;
  const auto vec = [](const auto& v, int n) {
    std::string s = "(";
    for (int k = 0; k < n; ++k) s += (k ? ", " : "") + std::to_string(v[k]);
    return s + ")";
  };
  int reported = 0;
  for (std::size_t i = 0; i < fast.vertexCount() && reported < 5; ++i) {
    bool same = true;
    for (int k = 0; k < 3; ++k) same = same && near(fast.positions[i][k], other.positions[i][k], 2.4e-7f);
    if (fast.hasNormals() && other.hasNormals()) {
      for (int k = 0; k < 3; ++k) same = same && std::fabs(fast.normals[i][k] - other.normals[i][k]) <= 1e-5f;
    }
    if (fast.hasUvs() && other.hasUvs()) {
      for (int k = 0; k < 2; ++k) same = same && near(fast.uvs[i][k], other.uvs[i][k], 2.4e-7f);
    }
    if (!same) {
      ++reported;
      ADD_FAILURE() << "vertex " << i << ": fast p" << vec(fast.positions[i], 3) << " vs " << otherName << " p"
                    << vec(other.positions[i], 3)
                    << (fast.hasNormals() && other.hasNormals()
                            ? " fast n" + vec(fast.normals[i], 3) + " " + otherName + " n" + vec(other.normals[i], 3)
                            : "");
    }
  }
}

/// Loads `path` through the fast path (which must take it) and through Assimp, joined
/// and not, and compares as stated at the top of this file. Returns the fast joined Mesh.
Mesh expectSameAsAssimp(const fs::path& path) {
  Mesh fastJoined;
  for (bool join : {true, false}) {
    SCOPED_TRACE(path.filename().string() + (join ? " joined" : " not joined"));
    ::testing::internal::CaptureStderr();
    const Mesh fast = loadMesh(path, {.joinVertices = join, .parser = MeshParser::Fast});
    const std::string fastLog = ::testing::internal::GetCapturedStderr();
    ::testing::internal::CaptureStderr();
    const Mesh assimp = loadMesh(path, {.joinVertices = join, .parser = MeshParser::Assimp});
    const std::string assimpLog = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(fastLog, assimpLog) << "the same warning (or none)";
    expectSameMesh(fast, assimp, "Assimp");
    if (join) fastJoined = fast;
  }
  return fastJoined;
}

/// One-line Error(Input) from the fast path, naming the file.
void expectInputError(const fs::path& path, MeshParser parser) {
  const Error e = captureError([&] { loadMesh(path, {.parser = parser}); });
  EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
  const std::string msg = e.what();
  EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

// A torus as OBJ text, quads, with every attribute: a few thousand corners, so the fast
// path cuts it into several chunks when the chunk size is small enough (it is not here;
// the big-file test below covers chunking).
std::string torusObj(int segments, int sides, bool normals, bool uvs) {
  std::string s = "# torus\no torus\n";
  for (int i = 0; i < segments; ++i) {
    for (int j = 0; j < sides; ++j) {
      const float a = 2 * kPi * float(i) / float(segments), b = 2 * kPi * float(j) / float(sides);
      const vec3 c(std::cos(a), 0, std::sin(a));
      const vec3 n = std::cos(b) * c + vec3(0, std::sin(b), 0);
      const vec3 p = c + 0.3f * n;
      s += fmt::format("v {} {} {}\n", p.x, p.y, p.z);
      if (normals) s += fmt::format("vn {} {} {}\n", n.x, n.y, n.z);
      if (uvs) s += fmt::format("vt {} {}\n", float(i) / float(segments), float(j) / float(sides));
    }
  }
  for (int i = 0; i < segments; ++i) {
    for (int j = 0; j < sides; ++j) {
      const int q[4] = {i * sides + j, ((i + 1) % segments) * sides + j, ((i + 1) % segments) * sides + (j + 1) % sides,
                        i * sides + (j + 1) % sides};
      s += "f";
      for (int k : {q[0], q[3], q[2], q[1]}) {
        const int id = k + 1;
        if (normals && uvs) s += fmt::format(" {}/{}/{}", id, id, id);
        else if (normals) s += fmt::format(" {}//{}", id, id);
        else if (uvs) s += fmt::format(" {}/{}", id, id);
        else s += fmt::format(" {}", id);
      }
      s += "\n";
    }
  }
  return s;
}

void put(std::string& s, const void* data, std::size_t n, bool bigEndian) {
  const auto* b = static_cast<const char*>(data);
  if (!bigEndian) {
    s.append(b, n);
  } else {
    for (std::size_t i = n; i-- > 0;) s.push_back(b[i]);
  }
}

/// A PLY of the two quads of a bent strip (one quad concave) and a pentagon, in `format`.
std::string plyFile(const std::string& format, bool normals, bool uvs) {
  const std::vector<vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.8f, 0.3f, 0}, {2, 0, 0.5f}, {2, 1, 0.5f},
                               {3, 0, 1}, {4, 0.5f, 1}, {3.5f, 1.5f, 1}, {2.5f, 1.5f, 1}, {2.2f, 0.7f, 1}};
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {1, 4, 5, 2}, {6, 7, 8, 9, 10}};
  std::string s = "ply\nformat " + format + " 1.0\ncomment written by import_oracle_test\n";
  s += fmt::format("element vertex {}\nproperty float x\nproperty float y\nproperty float z\n", p.size());
  if (normals) s += "property float nx\nproperty float ny\nproperty float nz\n";
  if (uvs) s += "property float s\nproperty float t\n";
  s += fmt::format("element face {}\nproperty list uchar int vertex_indices\nend_header\n", faces.size());
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::vector<float> values = {p[i].x, p[i].y, p[i].z};
    if (normals) {
      const vec3 n = glm::normalize(vec3(0.1f * float(i), 0.2f, 1.0f));
      values.insert(values.end(), {n.x, n.y, n.z});
    }
    if (uvs) values.insert(values.end(), {p[i].x / 4, p[i].y / 2});
    if (ascii) {
      for (std::size_t k = 0; k < values.size(); ++k) s += fmt::format("{}{}", k ? " " : "", values[k]);
      s += "\n";
    } else {
      for (float v : values) put(s, &v, 4, big);
    }
  }
  for (const auto& f : faces) {
    if (ascii) {
      s += std::to_string(f.size());
      for (int i : f) s += " " + std::to_string(i);
      s += "\n";
    } else {
      const auto n = std::uint8_t(f.size());
      s.push_back(char(n));
      for (int i : f) put(s, &i, 4, big);
    }
  }
  return s;
}

}  // namespace

TEST(ImportOracle, ObjQuadsNgonsNegativeIndicesObjectsAndGroups) {
  // Three objects (one with groups and a material change), in one file:
  //  - "strip": a convex quad and a concave quad (Assimp fans from the concave corner),
  //    normals and uvs, absolute indices;
  //  - "ngons": a convex hexagon and a concave L-shaped hexagon (ear cutting), relative
  //    (negative) indices, uvs but no normals → smooth normals and a warning;
  //  - groups "a"/"b" with two materials: normals, no uvs.
  const std::string obj = R"(# oracle
mtllib missing.mtl
o strip
v 0 0 0
v 1 0 0
v 1 1 0
v 0.8 0.3 0
v 2 0 0.5
v 2 1 0.5
vt 0 0
vt 1 0
vt 1 1
vt 0.8 0.3
vt 0.5 0.5
vt 0.5 0.9
vn 0 0 1
vn 0.2 0 1
usemtl red
f 1/1/1 2/2/1 3/3/1 4/4/1
f 2/2/2 5/5/2 6/6/2 3/3/2
o ngons
v 0 0 2
v 1 0 2
v 1.5 0.8 2
v 1 1.6 2
v 0 1.6 2
v -0.5 0.8 2
vt 0 0
vt 1 0
vt 1 0.5
vt 1 1
vt 0 1
vt 0 0.5
f -6/-6 -5/-5 -4/-4 -3/-3 -2/-2 -1/-1
v 3 0 2
v 5 0 2
v 5 1 2
v 4 1 2
v 4 3 2
v 3 3 2
f -6/-6 -5/-5 -4/-4 -3/-3 -2/-2 -1/-1
g a
v 0 0 4
v 1 0 4
v 0 1 4
vn 0 0 1
f -3//-1 -2//-1 -1//-1
usemtl blue
v 1 1 4
f -3//1 -2//1 -1//1
g b
f 7//2 8//2 9//2
)";
  const fs::path path = writeFile("mixed.obj", obj);
  const Mesh m = expectSameAsAssimp(path);
  EXPECT_EQ(m.triangleCount(), 2u + 2u + 4u + 4u + 1u + 1u + 1u);
  EXPECT_FALSE(m.hasUvs()) << "uvs are dropped when a part has none (Mesh::append)";
}

TEST(ImportOracle, ObjJoiningToleratesTinyNormalAndUvDifferencesOnly) {
  // Assimp joins vertices at exactly the same position whose normals and uvs differ by at
  // most 1e-5; a position 1e-6 away is another vertex.
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0.000001 0 0\n"
                          "vt 0 0\nvt 0.000001 0\nvt 0.1 0\n"
                          "vn 0 0 1\nvn 0 0.000002 1\nvn 0 0.1 1\n"
                          "f 1/1/1 2/1/1 3/1/1\nf 1/2/2 4/1/1 3/1/1\nf 1/3/1 2/1/1 4/1/1\nf 1/1/3 4/1/1 2/1/1\n"
                          "f 5/1/1 2/1/1 4/1/1\n";
  const Mesh m = expectSameAsAssimp(writeFile("near.obj", obj));
  EXPECT_EQ(m.vertexCount(), 4u + 2u + 1u) << "corner 1 near-equal joins; uv 0.1, normal 0.1 and x 1e-6 do not";
}

TEST(ImportOracle, ObjWithoutNormalsOrUvs) {
  const fs::path path = writeFile("torus-bare.obj", torusObj(24, 12, false, false));
  const Mesh m = expectSameAsAssimp(path);
  EXPECT_EQ(m.vertexCount(), 24u * 12u);
  EXPECT_EQ(m.triangleCount(), 2u * 24u * 12u);
}

TEST(ImportOracle, ObjWithNormalsAndUvs) {
  const fs::path path = writeFile("torus-full.obj", torusObj(24, 12, true, true));
  const Mesh m = expectSameAsAssimp(path);
  // The uv seam duplicates the vertices on u = 0 and v = 0... except that this torus
  // uses one uv per vertex (wrapping), so joining gives back the grid.
  EXPECT_EQ(m.vertexCount(), 24u * 12u);
}

TEST(ImportOracle, BigObjIsCutIntoChunksAndGivesAssimpsMesh) {
  // ~6 MB: several 1 MiB chunks parsed on different threads, relative indices across
  // chunk borders, CRLF line ends.
  std::string obj;
  const std::string torus = torusObj(400, 100, true, true);
  for (char c : torus) {
    if (c == '\n') obj += '\r';
    obj += c;
  }
  // A second object with relative indices, so resolution across chunk borders is tested.
  obj += "o tail\r\n";
  for (int i = 0; i < 30000; ++i) {
    obj += fmt::format("v {} {} 5\r\nv {} {} 5\r\nv {} {} 5.5\r\nf -3 -2 -1\r\n", i, 0, i + 1, 0, i, 1);
  }
  const fs::path path = writeFile("big.obj", obj);
  ASSERT_GT(fs::file_size(path), 4u << 20);
  expectSameAsAssimp(path);
}

TEST(ImportOracle, ObjFastLaneReadsEveryLineAsTinyObjLoaderDoes) {
  // The OBJ path reads `v`/`vn`/`vt`/`f` lines of the usual shape itself and leaves every
  // other line to tinyobjloader. Lines of each kind written every way this file knows
  // (blanks, tabs, signs, exponents, comments, 4 coordinates, CR LF, lone CR, relative
  // indices) must give what tinyobjloader alone gives, the rest of the path unchanged.
  const std::string obj =
      "# a comment\nmtllib none.mtl\no first\n"
      "v 0 0 0\nv\t1 0 0\n v 0 1 0\nv +1 1 0\nv 1e-3 2.5E+2 -0.125\nv 1 1 1 # trailing comment\n"
      "v 2 2 2 1\nv 0.1 0.2 0.3\r\nv -7 1e2 3.\n"
      "vt 0 0\nvt 1 0 0\nvt 0.5 1\n vt 0.25 0.75\n"
      "vn 0 0 1\r\nvn 0 1 0 \nvn\t1 0 0\n"
      "usemtl a\nf 1/1/1 2/2/2 3/3/3\nf 1/1/1 -7/2/2 -6/3/3 4/4/1\nf\t5/1/2  6/2/2 7/3/3 \n f 8/1/3 9/2/3 1/3/3\r\n"
      "g grp\nf 5//1 6//2 7//3\nf -9//1 -8//2 -7//-1\n"
      "g plain\ns off\nf 1 2 3\r\nv 3 3 3\rv 4 4 4\rv 4 5 4\rf -1 -2 -3\nf 2 3 4\n";
  const fs::path path = writeFile("lanes.obj", obj);
  for (bool join : {true, false}) {
    SCOPED_TRACE(join ? "joined" : "not joined");
    ::testing::internal::CaptureStderr();
    const Mesh lane = detail::loadObjFast(path, {.joinVertices = join}, true);
    const Mesh tiny = detail::loadObjFast(path, {.joinVertices = join}, false);
    ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(lane.triangleCount(), 10u);
    expectSameMesh(lane, tiny, "tinyobjloader");
  }
}

TEST(ImportOracle, PlyAsciiAndBinaryWithAndWithoutAttributes) {
  for (const std::string format : {"ascii", "binary_little_endian"}) {
    for (bool normals : {false, true}) {
      for (bool uvs : {false, true}) {
        const fs::path path = writeFile(fmt::format("strip-{}-{}-{}.ply", format, normals, uvs), plyFile(format, normals, uvs));
        const Mesh m = expectSameAsAssimp(path);
        EXPECT_EQ(m.triangleCount(), 2u + 2u + 3u);
        EXPECT_EQ(m.hasUvs(), uvs);
      }
    }
  }
}

TEST(ImportOracle, BigEndianPlyGoesToAssimp) {
  const fs::path path = writeFile("strip-be.ply", plyFile("binary_big_endian", true, true));
  const Mesh automatic = loadMesh(path);
  const Mesh assimp = loadMesh(path, {.parser = MeshParser::Assimp});
  EXPECT_EQ(automatic.indices, assimp.indices);
  EXPECT_EQ(automatic.positions, assimp.positions);
  // The same file in little endian through the fast path gives the same Mesh.
  const Mesh little = loadMesh(writeFile("strip-le.ply", plyFile("binary_little_endian", true, true)),
                               {.parser = MeshParser::Fast});
  EXPECT_EQ(little.indices, assimp.indices);
  EXPECT_EQ(little.positions, assimp.positions);
  const Error e = captureError([&] { loadMesh(path, {.parser = MeshParser::Fast}); });
  EXPECT_EQ(e.kind(), ErrorKind::Input);
  EXPECT_NE(std::string(e.what()).find("big-endian"), std::string::npos) << e.what();
}

TEST(ImportOracle, PlyWithoutNormalsGetsSmoothNormalsBothWays) {
  // An octahedron with shared vertices: the smooth normal at each vertex is radial. (Before
  // the fast paths, Assimp's step gave each shared vertex the normal of its last face.)
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 8\nproperty list uchar int vertex_indices\nend_header\n"
                          "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
                          "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";
  const fs::path path = writeFile("octahedron.ply", ply);
  for (MeshParser parser : {MeshParser::Fast, MeshParser::Assimp}) {
    ::testing::internal::CaptureStderr();
    const Mesh m = loadMesh(path, {.parser = parser});
    EXPECT_NE(::testing::internal::GetCapturedStderr().find("no normals"), std::string::npos);
    ASSERT_EQ(m.vertexCount(), 6u);
    for (std::size_t i = 0; i < 6; ++i) EXPECT_GT(glm::dot(m.normals[i], m.positions[i]), 1.0f - 1e-6f) << i;
  }
  expectSameAsAssimp(path);
}

TEST(ImportOracle, FastPathErrorsAreOneLineInputErrors) {
  struct Case {
    const char* name;
    std::string contents;
  };
  const std::vector<Case> objCases = {
      {"empty.obj", ""},
      // The length from the literal itself (it has no NUL inside): a hand-counted 33 read
      // past its end (found by the ASan pass).
      {"garbage.obj", std::string("\x01\x02garbage\xff\xfe not an obj at all\n")},
      {"out-of-range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"},
      {"relative-out-of-range.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n"},
      {"zero-index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"},
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n"},
      {"truncated.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\nf 3 4 5"},
      {"no-faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"},
  };
  for (const Case& c : objCases) {
    SCOPED_TRACE(c.name);
    const fs::path path = writeFile(c.name, c.contents);
    expectInputError(path, MeshParser::Fast);
    expectInputError(path, MeshParser::Auto);
  }
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n";
  std::string full = header;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(full, &v, 4, false);
  full.push_back(3);
  for (int i : {0, 1, 5}) put(full, &i, 4, false);
  const std::vector<Case> plyCases = {
      {"empty.ply", ""},
      {"truncated-binary.ply", full.substr(0, header.size() + 20)},
      {"index-out-of-range.ply", full},
      {"header-only.ply", header},
      {"nan.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"},
      {"no-corners.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                         "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0\n"},
  };
  for (const Case& c : plyCases) {
    SCOPED_TRACE(c.name);
    const fs::path path = writeFile(c.name, c.contents);
    expectInputError(path, MeshParser::Auto);
  }
}

TEST(ImportOracle, FastParserRefusesOtherFormats) {
  const fs::path path = writeFile("tri.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                             "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
  EXPECT_EQ(loadMesh(path).triangleCount(), 1u);
  expectInputError(path, MeshParser::Fast);
}

namespace {
/// Assimp's own reading of a glTF file (the oracle glint's glTF reader is held to): its
/// importer with triangulation, smooth normals where a mesh has none and joined vertices,
/// every node's meshes placed by its world transform, depth first.
Mesh assimpReading(const fs::path& path) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_SortByPType |
                                                              aiProcess_GenSmoothNormals | aiProcess_JoinIdenticalVertices);
  if (!scene || !scene->mRootNode) return {};
  Mesh out;
  const std::function<void(const aiNode&, const mat4&)> visit = [&](const aiNode& node, const mat4& parent) {
    const mat4 world = parent * glm::transpose(glm::make_mat4(&node.mTransformation.a1));
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const aiMesh& in = *scene->mMeshes[node.mMeshes[i]];
      if (!(in.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
      Mesh part;
      for (unsigned v = 0; v < in.mNumVertices; ++v) {
        part.positions.emplace_back(in.mVertices[v].x, in.mVertices[v].y, in.mVertices[v].z);
        if (in.HasNormals()) part.normals.push_back(glm::normalize(vec3(in.mNormals[v].x, in.mNormals[v].y, in.mNormals[v].z)));
        if (in.HasTextureCoords(0)) part.uvs.emplace_back(in.mTextureCoords[0][v].x, in.mTextureCoords[0][v].y);
      }
      for (unsigned f = 0; f < in.mNumFaces; ++f) part.indices.insert(part.indices.end(), in.mFaces[f].mIndices, in.mFaces[f].mIndices + 3);
      part.transform(world);
      out.append(part);
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) visit(*node.mChildren[c], world);
  };
  visit(*scene->mRootNode, mat4(1.0f));
  return out;
}
}  // namespace

/// The same triangles, corner by corner: positions, normals and uvs of every triangle's
/// corners in order, whatever the vertices' order and sharing (Assimp 5.2 and 5.4 join
/// vertices into different orders).
void expectSameCorners(const Mesh& mine, const Mesh& other, const char* otherName) {
  ASSERT_EQ(mine.triangleCount(), other.triangleCount()) << "the same triangles";
  EXPECT_EQ(mine.hasNormals(), other.hasNormals());
  EXPECT_EQ(mine.hasUvs(), other.hasUvs());
  int reported = 0;
  for (std::size_t c = 0; c < mine.indices.size() && reported < 5; ++c) {
    const std::uint32_t a = mine.indices[c], b = other.indices[c];
    bool same = true;
    for (int k = 0; k < 3; ++k) same = same && near(mine.positions[a][k], other.positions[b][k], 2.4e-7f);
    for (int k = 0; k < 3 && mine.hasNormals() && other.hasNormals(); ++k)
      same = same && std::fabs(mine.normals[a][k] - other.normals[b][k]) <= 1e-5f;
    for (int k = 0; k < 2 && mine.hasUvs() && other.hasUvs(); ++k) same = same && near(mine.uvs[a][k], other.uvs[b][k], 2.4e-7f);
    if (!same) {
      ++reported;
      ADD_FAILURE() << "corner " << c << " (triangle " << c / 3 << ") differs from " << otherName << "'s";
    }
  }
}

// glTF is read by glint's own reader (mesh/gltf.h) on every path, never by Assimp; Assimp
// reading the same clean files is the oracle: the same triangles in the same order, corner
// for corner the same positions, normals and uvs. A Blender 3.4 export (two objects, materials, normals, uvs), a glint bake
// asset, and a node tree written here: translation, rotation, non-uniform and mirroring
// scale, a mesh used by two nodes, a primitive without normals.
TEST(ImportOracle, GlintsGltfReaderGivesAssimpsMesh) {
  const fs::path corpus = fs::path(GLINT_SOURCE_DIR) / "fuzz/corpus/mesh_parts";
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0.5f};
  const float normals[] = {0, 0, 1, 0, 0.6f, 0.8f, 0.6f, 0, 0.8f, 0, 1, 0};
  const std::uint32_t indices[] = {0, 1, 2, 2, 1, 3};
  gltf::Document doc("glint import_oracle_test");
  const int p = doc.addAccessor(positions, 4, gltf::kFloat, "VEC3", gltf::kVertices, {0, 0, 0}, {1, 1, 0.5});
  const int n = doc.addAccessor(normals, 4, gltf::kFloat, "VEC3", gltf::kVertices);
  const int ix = doc.addAccessor(indices, 6, gltf::kUnsignedInt, "SCALAR", gltf::kIndices);
  doc.json["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", p}, {"NORMAL", n}}}, {"indices", ix}}}}}};
  doc.json["nodes"] = {{{"children", {1, 2}}, {"translation", {1, 2, 3}}},
                       {{"mesh", 0}, {"rotation", {0, 0.3826834, 0, 0.9238795}}, {"scale", {2, 1, 0.5}}},
                       {{"mesh", 0}, {"scale", {-1, 1, 1}}, {"translation", {-4, 0, 0}}}};
  doc.json["scenes"] = {{{"nodes", {0}}}};
  doc.json["scene"] = 0;
  doc.save(outDir() / "tree.gltf");
  for (const fs::path& path : {corpus / "blender-export.glb", corpus / "glint-bake-asset.glb", outDir() / "tree.gltf"}) {
    SCOPED_TRACE(path.filename().string());
    const Mesh oracle = assimpReading(path);
    ASSERT_GT(oracle.triangleCount(), 0u) << "Assimp read nothing";
    expectSameCorners(loadMesh(path), oracle, "Assimp");
  }
  // Without normals, glint makes them as for every format (Assimp's GenSmoothNormals on one
  // vertex per corner, then joined): the same mesh as the same triangles in a PLY file, whose
  // reading the tests above hold to Assimp's.
  doc.json["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
  doc.json["nodes"] = {{{"mesh", 0}}};
  doc.save(outDir() / "bare.glb");
  const fs::path ply = writeFile("bare.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                             "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                                             "end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0.5\n3 0 1 2\n3 2 1 3\n");
  for (const bool join : {true, false}) {
    SCOPED_TRACE(join ? "joined" : "not joined");
    expectSameMesh(loadMesh(outDir() / "bare.glb", {.joinVertices = join}), loadMesh(ply, {.joinVertices = join}), "PLY");
  }
  // Assimp is never handed glTF by glint: asking for it is a usage error.
  const Error e = captureError([&] { loadMesh(outDir() / "tree.gltf", {.parser = MeshParser::Assimp}); });
  EXPECT_EQ(e.kind(), ErrorKind::Usage) << e.what();
}
