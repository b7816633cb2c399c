// Model files from strangers (issue 44): every file in fuzz/regressions/models/ (one per way
// a file once broke glint; fuzz/make-model-regressions.py) and the ones too big or too odd
// for git (made here) through every command that opens a model — mesh-info, render, bake
// (as the low poly, and as the high poly with --material-id: the parts reader), view
// --export-web — as a user runs them. Each run ends within its time limit with a
// documented exit status, and when it fails, with one line. Nothing outside a model's
// folder is read: the secret beside the folder is a named pipe, so opening it would hang
// the run past its limit.
#include "glint/core/text.h"

#include "support/cli.h"
#include "support/obj.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using namespace glint::testing;

namespace {

std::string q(const fs::path& p) { return shellQuote(p); }

const fs::path kRegressions = fs::path(GLINT_SOURCE_DIR) / "fuzz/regressions/models";

/// What `glint mesh-info` answers for each regression file: 0 (a usable mesh: what the file
/// does wrong is left out, with a warning) or 3 (refused: one line naming the file and the rule).
const std::map<std::string, int> kMeshInfo = {
    {"accessor-byte-offset-wraps.glb", 3},
    {"accessor-count-zero.gltf", 3},
    {"buffer-view-offset-past-2-63.glb", 3},
    {"color-of-type-mat4.glb", 3},
    {"color-of-type-scalar.glb", 3},
    {"color-of-type-vec2.glb", 3},
    {"coordinate-1e38.obj", 0},  // a mesh; the ray tracer refuses it (bake)
    {"coordinate-inf.obj", 3},
    {"export-http-emissive-texture.glb", 0},
    {"extras-glint-bake-wrong-types.glb", 0},
    {"extras-glint-maps-wrong-types.glb", 3},
    {"extras-nested-30-levels.gltf", 0},
    {"glb-json-chunk-length-past-end.glb", 3},
    {"image-buffer-view-offset-past-2-31.glb", 3},
    {"index-count-past-file.glb", 3},
    {"json-array-not-object.gltf", 3},
    {"material-index-past-materials.glb", 3},
    {"node-cycle-of-two.glb", 3},
    {"node-its-own-child.glb", 3},
    {"node-with-two-parents.glb", 3},
    {"ply-bit-flipped-corner-count.ply", 3},
    {"ply-header-only.ply", 3},
    {"ply-truncated-body.ply", 3},
    {"sparse-accessor-without-buffer-view.glb", 0},
    {"sparse-indices-without-buffer-view.glb", 3},
    {"uri-absolute-image.gltf", 0},
    {"uri-file-scheme-image.gltf", 0},
    {"uri-http-buffer.gltf", 3},
    {"uri-parent-buffer.gltf", 3},
    {"uri-parent-image.gltf", 0},
    {"uri-percent-encoded-parent-buffer.gltf", 3},
    {"uri-percent-encoded-parent-image.gltf", 0},
};

/// A run's verdict: a documented status within the limit, and on failure one line.
void expectClean(const CliRun& r, const std::string& what) {
  static const std::set<int> kDocumented = {0, 2, 3, 4, 6};
  EXPECT_TRUE(kDocumented.count(r.status)) << what << ": exit " << r.status << (r.status == 124 ? " (over its time limit)" : "")
                                           << "\n" << r.output;
  std::size_t errors = 0;
  for (std::size_t at = 0; at < r.output.size();) {
    const std::size_t end = std::min(r.output.find('\n', at), r.output.size());
    const std::string line = r.output.substr(at, end - at);
    at = end + 1;
    if (line.starts_with("glint: ")) ++errors;
    else EXPECT_TRUE(line.starts_with("warning: ")) << what << ": a line that is neither an error nor a warning: " << line;
  }
  EXPECT_EQ(errors, r.status == 0 ? 0u : 1u) << what << ": " << r.output;
}

/// A glTF of one triangle whose buffer and (when given) image are the uris given.
std::string gltfWith(const std::string& bufferUri, const std::string& imageUri) {
  std::string doc = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":48,"uri":")" + bufferUri + R"("}],)"
                    R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12}],)"
                    R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
                    R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}],)"
                    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1)";
  if (!imageUri.empty()) doc += R"(,"material":0)";
  doc += R"(}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0)";
  if (!imageUri.empty())
    doc += R"(,"images":[{"uri":")" + imageUri + R"("}],"textures":[{"source":0}],)"
           R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}])";
  return doc + "}";
}

void writeBuffer(const fs::path& path) {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint32_t indices[3] = {0, 1, 2};
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(positions), sizeof positions);
  out.write(reinterpret_cast<const char*>(indices), sizeof indices);
}

/// The files git cannot hold or that are too big to keep: made in `dir`.
std::vector<fs::path> madeHere(const fs::path& dir) {
  std::vector<fs::path> files;
  {  // JSON nested 100,000 deep (parsers and recursive walks run out of stack)
    const fs::path f = dir / "json-nested-100000-deep.gltf";
    std::ofstream(f) << R"({"asset":{"version":"2.0"},"extras":)" << std::string(100000, '[') << std::string(100000, ']') << "}";
    files.push_back(f);
  }
  {  // a chain of 100,000 nodes, the last with the triangle (a recursive walk overflows)
    const fs::path f = dir / "node-chain-100000.gltf";
    std::string nodes;
    for (int i = 0; i < 100000; ++i) nodes += fmt::format("{}{{\"children\":[{}]}}", i ? "," : "", i + 1);
    std::string doc = gltfWith("tri.bin", "");
    doc.replace(doc.find(R"("nodes":[{"mesh":0}])"), 20, R"("nodes":[)" + nodes + R"(,{"mesh":0}])");
    std::ofstream(f) << doc;
    files.push_back(f);
  }
  {  // a PLY element of 100,000 properties (quadratic in Assimp: 11 s)
    const fs::path f = dir / "ply-100000-properties.ply";
    std::ofstream out(f, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    for (int i = 0; i < 100000; ++i) out << "property float p" << i << "\n";
    out << "element face 1\nproperty list uchar int vertex_indices\nend_header\n" << std::string(3 * 4 * 100003, '\0');
    const unsigned char face[13] = {3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0};
    out.write(reinterpret_cast<const char*>(face), sizeof face);
    files.push_back(f);
  }
  // A file name that is not UTF-8, and one with a line break.
  for (const char* name : {"caf\xe9.gltf", "line\nbreak.gltf"}) {
    std::ofstream(dir / name) << gltfWith("tri.bin", "");
    files.push_back(dir / name);
  }
  // Symbolic links inside the folder that point out of it, at a buffer and an image.
  fs::create_symlink("../outside/secret.bin", dir / "linked.bin");
  fs::create_symlink("../outside/secret.png", dir / "linked.png");
  std::ofstream(dir / "symlink-out-buffer.gltf") << gltfWith("linked.bin", "");
  std::ofstream(dir / "symlink-out-image.gltf") << gltfWith("tri.bin", "linked.png");
  files.push_back(dir / "symlink-out-buffer.gltf");
  files.push_back(dir / "symlink-out-image.gltf");
  // And uris that reach the secrets directly, percent-encoded or not.
  std::ofstream(dir / "parent-buffer.gltf") << gltfWith("../outside/secret.bin", "");
  std::ofstream(dir / "encoded-parent-image.gltf") << gltfWith("tri.bin", "%2e%2e%2Foutside%2Fsecret.png");
  files.push_back(dir / "parent-buffer.gltf");
  files.push_back(dir / "encoded-parent-image.gltf");
  return files;
}

}  // namespace

TEST(HostileModels, EveryCommandEndsEveryFileCleanlyAndReadsNothingOutsideItsFolder) {
  const fs::path root = freshDir("hostile", "models");
  const fs::path dir = root / "models", outside = root / "outside", out = root / "out";
  fs::create_directories(dir);
  fs::create_directories(outside);
  fs::create_directories(out);
  // The secrets are named pipes: opening one for reading blocks until a writer comes, which
  // none does, so a read would end in `timeout`'s status 124.
  ASSERT_EQ(::mkfifo((outside / "secret.bin").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((outside / "secret.png").c_str(), 0600), 0);
  writeBuffer(dir / "tri.bin");
  writeObj(makeUvSphere(1.0f, 8, 4), out / "good.obj");

  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kRegressions)) {
    EXPECT_TRUE(kMeshInfo.count(e.path().filename().string())) << e.path().filename() << ": add it to kMeshInfo";
    fs::copy_file(e.path(), dir / e.path().filename());
    files.push_back(dir / e.path().filename());
  }
  std::sort(files.begin(), files.end());
  const std::vector<fs::path> made = madeHere(dir);
  files.insert(files.end(), made.begin(), made.end());
  ASSERT_GE(files.size(), kMeshInfo.size() + 9);

  const std::string limit = "timeout -k 5 60 ";
  for (const fs::path& file : files) {
    const std::string name = escapedLine(file.filename().string());
    SCOPED_TRACE(name);
    const CliRun info = runShell("(" + limit + GLINT_EXE " mesh-info " + q(file) + " > /dev/null)");  // its messages only
    expectClean(info, "mesh-info " + name);
    if (const auto it = kMeshInfo.find(file.filename().string()); it != kMeshInfo.end()) {
      EXPECT_EQ(info.status, it->second) << "mesh-info " << name << ": " << info.output;
    }
    const bool refused = info.status != 0;
    const std::vector<std::pair<std::string, std::string>> runs = {
        {"render", "render " + q(file) + " -o " + q(out / "r.png") + " --size 24x24 -q"},
        {"bake (low)", "bake " + q(file) + " " + q(out / "good.obj") + " -o " + q(out / "n.png") + " --size 16x16 -q"},
        {"bake (high)", "bake " + q(out / "good.obj") + " " + q(file) + " -o " + q(out / "n.png") +
                            " --size 16x16 --material-id " + q(out / "m.png") + " -q"},
        {"view --export-web", "view " + q(file) + " --export-web " + q(out / "web") + " -q"},
    };
    for (const auto& [what, args] : runs) {
      const CliRun r = runShell(limit + GLINT_EXE " " + args);
      expectClean(r, what + " " + name);
      if (refused) {
        EXPECT_EQ(r.status, 3) << what << " " << name << " reads what mesh-info refuses: " << r.output;
      }
    }
  }
  // The line break and the Latin-1 byte were quoted on one line, escaped.
  const CliRun missing = runShell(GLINT_EXE " mesh-info " + q(dir / "no\nsuch\xff.glb"));
  EXPECT_EQ(missing.status, 3);
  EXPECT_TRUE(glint::testing::oneLine(missing.output)) << missing.output;
  EXPECT_NE(missing.output.find("no\\nsuch\\xff.glb"), std::string::npos) << missing.output;
}

// Names the filesystem takes are names glint takes (issue 44): an output name of 250 bytes
// (its temporary must fit the 255-byte limit too), and names that are not UTF-8 in the
// reports every tool writes (JSON is UTF-8: each stray byte is written \xNN).
TEST(HostileNames, LongNamesAndNamesThatAreNotUtf8AreWrittenAndReported) {
  const fs::path d = freshDir("hostile", "names");
  writeObj(makeUvSphere(1.0f, 8, 4), d / "low.obj");
  const std::string stem(246, 'n');  // + ".png" = 250 bytes
  const CliRun longName = runGlint("bake " + q(d / "low.obj") + " " + q(d / "low.obj") + " -o " + q(d / (stem + ".png")) +
                                   " --size 16x16 -q --json " + q(d / (stem.substr(0, 245) + ".json")));
  ASSERT_EQ(longName.status, 0) << longName.output;
  EXPECT_TRUE(fs::exists(d / (stem + ".png")));

  const std::string latin = "caf\xe9";  // Latin-1 é: not UTF-8
  fs::copy_file(d / "low.obj", d / (latin + ".obj"));
  const CliRun bake = runGlint("bake " + q(d / (latin + ".obj")) + " " + q(d / "low.obj") + " -o " + q(d / (latin + ".png")) +
                               " --size 16x16 -q --json " + q(d / "bake.json"));
  ASSERT_EQ(bake.status, 0) << bake.output;
  const CliRun cut = runGlint("cut " + q(d / (latin + ".obj")) + " -o " + q(d / (latin + ".glb")) + " --light 0,3,0," + q(latin) +
                              " -q --json " + q(d / "cut.json"));
  ASSERT_EQ(cut.status, 0) << cut.output;
  const CliRun post = runGlint("post " + q(d / (latin + ".png")) + " -o " + q(d / (latin + "-sepia.png")) + " -e sepia -q --json " +
                               q(d / "post.json"));
  ASSERT_EQ(post.status, 0) << post.output;
  for (const char* report : {"bake.json", "cut.json", "post.json"}) {
    const std::string text = readBytes(d / report);
    EXPECT_TRUE(isUtf8(text)) << report;
    EXPECT_NE(text.find("caf\\\\xe9"), std::string::npos) << report << " names the file, its stray byte escaped:\n" << text;
  }
  // The cut's glTF names its light the same way, and glint reads it back.
  const CliRun info = runGlint("mesh-info " + q(d / (latin + ".glb")));
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_NE(readBytes(d / (latin + ".glb")).find("caf\\\\xe9"), std::string::npos);
}
