// `glint bake --asset` and `--preview` as a user runs them (issue 35): the glTF asset passes
// the Khronos glTF-Validator (npm gltf-validator: 0 errors, 0 warnings), holds the baker's
// own MikkTSpace tangents and the maps as the loose files hold them (the normal map in
// OpenGL's convention whatever --directx did), one material per UDIM tile and per bake
// group; and the web page renders the bake in headless Chromium (WebGL through SwiftShader)
// with no console error, the model where the camera frames it, and the normal map changing
// the shading where the high poly has detail.
#include "glint/bake/asset.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"
#include "glint/mesh/tangents.h"

#include "support/cli.h"
#include "support/gltf.h"
#include "support/obj.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using namespace glint::testing;

namespace {

constexpr auto q = shellQuote;

fs::path dir(const char* name) { return freshDir("bake-asset", name); }

}  // namespace

TEST(BakeAsset, TheGlbPassesTheValidatorAndHoldsTheBakersTangentsAndMaps) {
  const auto d = dir("sphere");
  writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  writeObj(bumpySphere(), d / "high.obj");
  for (const bool directX : {false, true}) {
    const std::string x = directX ? "dx" : "gl";
    const auto bake = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / (x + "-n.png")) +
                               " --ao " + q(d / (x + "-ao.png")) + " --curvature " + q(d / (x + "-curv.png")) +
                               " --size 64x64 --samples 4 -q --asset " + q(d / (x + ".glb")) + " --json " +
                               q(d / (x + ".json")) + (directX ? " --directx" : ""));
    ASSERT_EQ(bake.status, 0) << bake.output;
    const nlohmann::json verdict = validateGltf(d / (x + ".glb"));
    EXPECT_EQ(verdict.value("errors", -1), 0) << verdict.dump(1);
    EXPECT_EQ(verdict.value("warnings", -1), 0) << verdict.dump(1);
    const auto report = nlohmann::json::parse(readBytes(d / (x + ".json")));
    EXPECT_EQ(report["asset"], (d / (x + ".glb")).string());
    EXPECT_EQ(report["asset_materials"], 1);

    const Glb glb(d / (x + ".glb"));
    ASSERT_EQ(glb.json["meshes"].size(), 1u);
    ASSERT_EQ(glb.json["meshes"][0]["primitives"].size(), 1u);
    const auto& prim = glb.json["meshes"][0]["primitives"][0];
    const auto& attributes = prim["attributes"];
    for (const char* a : {"POSITION", "NORMAL", "TANGENT", "TEXCOORD_0"}) ASSERT_TRUE(attributes.contains(a)) << a;
    const auto positions = glb.read<float>(attributes["POSITION"]), normals = glb.read<float>(attributes["NORMAL"]);
    const auto tangents = glb.read<float>(attributes["TANGENT"]), uvs = glb.read<float>(attributes["TEXCOORD_0"]);
    const auto indices = glb.read<std::uint32_t>(prim["indices"]);

    // Corner by corner, the frame the baker encoded against: frameLowPoly of the low poly
    // as glint reads it (the baker's own function), exactly; UVs as glTF's (u, 1 - v).
    const Mesh framed = bake::frameLowPoly(loadMesh(d / "low.obj"));
    ASSERT_EQ(indices.size(), framed.indices.size());
    int different = 0;
    for (std::size_t c = 0; c < indices.size(); ++c) {
      const std::size_t g = indices[c], f = framed.indices[c];
      for (int k = 0; k < 3; ++k) {
        different += positions[3 * g + std::size_t(k)] != framed.positions[f][k];
        different += normals[3 * g + std::size_t(k)] != framed.normals[f][k];
      }
      for (int k = 0; k < 4; ++k) different += tangents[4 * g + std::size_t(k)] != framed.tangents[f][k];
      different += uvs[2 * g] != framed.uvs[f].x || uvs[2 * g + 1] != 1.0f - framed.uvs[f].y;
    }
    EXPECT_EQ(different, 0) << "values that differ from the baker's frame";

    // The material: the normal map (OpenGL +Y), AO as occlusion, the rest named in extras.
    const auto& material = glb.json["materials"][prim["material"].get<int>()];
    const auto& maps = material["extras"]["glint_maps"];
    ASSERT_TRUE(maps.contains("normal") && maps.contains("ao") && maps.contains("curvature")) << material.dump(1);
    EXPECT_EQ(material["normalTexture"]["index"], maps["normal"]["texture"]);
    EXPECT_EQ(material["occlusionTexture"]["index"], maps["ao"]["texture"]);
    EXPECT_EQ(maps["curvature"]["color_space"], "linear");
    const Image normal = glb.image(maps["normal"]["texture"], d / "scratch.png");
    const Image loose = loadImage(d / (x + "-n.png"));
    ASSERT_EQ(normal.width(), 64);
    ASSERT_EQ(loose.channels(), 3);
    int wrong = 0;
    for (int y = 0; y < 64; ++y)
      for (int px = 0; px < 64; ++px)
        for (int c = 0; c < 3; ++c) {
          const float expected = directX && c == 1 ? 1.0f - loose.at(px, y, c) : loose.at(px, y, c);
          wrong += std::fabs(normal.at(px, y, c) - expected) > 0.5f / 255.0f;
        }
    EXPECT_EQ(wrong, 0) << x << ": the asset's normal map is the loose file's, in OpenGL's convention";
    EXPECT_TRUE(glb.image(maps["ao"]["texture"], d / "scratch.png") == loadImage(d / (x + "-ao.png")));
  }

  // A .gltf holds the same document with its buffer inside; the validator passes it too.
  const auto gltf = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "t.png") +
                             " --size 32x32 -q --asset " + q(d / "t.gltf"));
  ASSERT_EQ(gltf.status, 0) << gltf.output;
  const nlohmann::json verdict = validateGltf(d / "t.gltf");
  EXPECT_EQ(verdict.value("errors", -1), 0) << verdict.dump(1);
  EXPECT_EQ(verdict.value("warnings", -1), 0) << verdict.dump(1);
}

TEST(BakeAsset, OneMaterialPerUdimTileAndPerBakeGroupAndBatchFilesTakeIt) {
  const auto d = dir("tiles-groups");
  // Two spheres apart: a in tile 1001, b in 1002.
  Mesh a = makeUvSphere(1.0f, 16, 8), b = a;
  b.transform(glm::translate(mat4(1.0f), vec3(3.0f, 0.0f, 0.0f)));
  for (vec2& uv : b.uvs) uv.x += 1.0f;
  Mesh low = a;
  low.append(b);
  writeObj(low, d / "low.obj");
  Mesh high = bumpySphere(), highB = bumpySphere();
  highB.transform(glm::translate(mat4(1.0f), vec3(3.0f, 0.0f, 0.0f)));
  high.append(highB);
  writeObj(high, d / "high.obj");
  const auto udim = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n.<UDIM>.png") +
                             " --size 32x32 -q --asset " + q(d / "udim.glb"));
  ASSERT_EQ(udim.status, 0) << udim.output;
  nlohmann::json verdict = validateGltf(d / "udim.glb");
  EXPECT_EQ(verdict.value("errors", -1), 0) << verdict.dump(1);
  EXPECT_EQ(verdict.value("warnings", -1), 0) << verdict.dump(1);
  const Glb tiles(d / "udim.glb");
  ASSERT_EQ(tiles.json["materials"].size(), 2u);
  EXPECT_EQ(tiles.json["materials"][0]["name"], "1001");
  EXPECT_EQ(tiles.json["materials"][1]["name"], "1002");
  EXPECT_EQ(tiles.json["meshes"][0]["primitives"].size(), 2u);
  for (int t = 0; t < 2; ++t) {  // each tile's normal map is its file; its UVs are in 0..1
    const auto& material = tiles.json["materials"][t];
    EXPECT_TRUE(tiles.image(material["normalTexture"]["index"], d / "scratch.png") ==
                loadImage(d / (t == 0 ? "n.1001.png" : "n.1002.png")));
    const auto uv = tiles.read<float>(tiles.json["meshes"][0]["primitives"][t]["attributes"]["TEXCOORD_0"]);
    EXPECT_LE(*std::max_element(uv.begin(), uv.end()), 1.0f);
    EXPECT_GE(*std::min_element(uv.begin(), uv.end()), 0.0f);
  }

  // Bake groups: parts a_low and b_low (one map), a material each.
  {
    std::ofstream out(d / "parts.obj");
    Mesh a1 = a, b1 = b;  // a's island in the left half of the map, b's in the right
    for (vec2& uv : a1.uvs) uv *= 0.5f;
    for (vec2& uv : b1.uvs) uv = vec2(uv.x - 1.0f, uv.y) * 0.5f + vec2(0.5f, 0.0f);
    out << "o a_low\n";
    writeObjLines(out, a1);
    out << "o b_low\n";
    writeObjLines(out, b1, a1.positions.size());
  }
  {
    std::ofstream out(d / "parts_high.obj");
    out << "o a_high\n";
    writeObjLines(out, bumpySphere());
    out << "o b_high\n";
    writeObjLines(out, highB, bumpySphere().positions.size());
  }
  const auto groups = runGlint("bake " + q(d / "parts.obj") + " " + q(d / "parts_high.obj") + " -o " + q(d / "g.png") +
                               " --size 32x32 -q --asset " + q(d / "groups.glb"));
  ASSERT_EQ(groups.status, 0) << groups.output;
  verdict = validateGltf(d / "groups.glb");
  EXPECT_EQ(verdict.value("errors", -1), 0) << verdict.dump(1);
  EXPECT_EQ(verdict.value("warnings", -1), 0) << verdict.dump(1);
  const Glb grouped(d / "groups.glb");
  ASSERT_EQ(grouped.json["materials"].size(), 2u);
  EXPECT_EQ(grouped.json["materials"][0]["name"], "a");
  EXPECT_EQ(grouped.json["materials"][1]["name"], "b");
  EXPECT_EQ(grouped.json["images"].size(), 2u) << "the groups share one normal map and one miss mask";

  // A batch file's job takes the asset as a key; --list shows it as the option.
  std::ofstream(d / "jobs.json") << R"({"bakes": [{"low": "low.obj", "high": "high.obj", "output": "b.<UDIM>.png",
                                                   "size": "16x16", "asset": "batch.glb"}]})";
  const auto batch = runGlint("bake -q --batch " + q(d / "jobs.json"));
  ASSERT_EQ(batch.status, 0) << batch.output;
  EXPECT_TRUE(fs::exists(d / "batch.glb"));
  const auto list = runGlint("bake --batch " + q(d / "jobs.json") + " --list");
  EXPECT_NE(list.output.find("--asset"), std::string::npos) << list.output;
  const auto farm = runGlint("farm bake " + q(d / "jobs.json") + " --dry-run --work-dir " + q(d / "farm"));
  EXPECT_EQ(farm.status, 0) << farm.output;
}

TEST(BakeAsset, BadAssetOptionsAreOneLineAndWriteNothing) {
  const auto d = dir("bad");
  writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  writeObj(bumpySphere(), d / "high.obj");
  const std::string bake = "bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n.png") + " --size 16x16 ";
  struct Case {
    std::string options, says;
    int status;
  };
  std::ofstream(d / "file") << "x";
  for (const Case& c : {Case{"--asset " + q(d / "a.obj"), ".glb or .gltf", 2},
                        Case{"--asset " + q(d / "a.glb") + " --space object", "--space tangent", 2},
                        Case{"--asset " + q(d / "low.obj"), "", 2},
                        Case{"--asset " + q(d / "n.png"), "", 2},
                        Case{"--asset " + q(d / "missing/a.glb"), "missing", 4},
                        Case{"--preview " + q(d / "file"), "is a file", 4}}) {
    const auto r = runGlint(bake + c.options);
    EXPECT_EQ(r.status, c.status) << c.options << ": " << r.output;
    EXPECT_TRUE(glint::testing::oneLine(r.output)) << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(d / "n.png")) << c.options;
  }
}

// The page in headless Chromium (Debian's chromium; WebGL 2 through SwiftShader): a bumpy
// sphere's bake on its 16×8 low poly, drawn with and without the normal map.
TEST(BakePreview, ThePageRendersTheBakeInChromiumAndTheNormalMapShowsTheDetail) {
  const auto d = dir("preview");
  writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  writeObj(bumpySphere(), d / "high.obj");
  const auto bake = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n.png") +
                             " --ao " + q(d / "ao.png") + " --size 256x128 --samples 4 -q --preview " + q(d / "web"));
  ASSERT_EQ(bake.status, 0) << bake.output;
  for (const std::string& f : bake::previewFiles()) EXPECT_TRUE(fs::exists(d / "web" / f)) << f;
  // Offline: everything the page loads is a file beside it (no address with a scheme).
  const std::string html = readBytes(d / "web/index.html");
  int loads = 0;
  for (const std::string attribute : {"src=\"", "href=\""})
    for (auto at = html.find(attribute); at != std::string::npos; at = html.find(attribute, at + 1)) {
      const auto from = at + attribute.size();
      const std::string target = html.substr(from, html.find('"', from) - from);
      EXPECT_EQ(target.find(':'), std::string::npos) << target;
      EXPECT_TRUE(fs::exists(d / "web" / target)) << target;
      ++loads;
    }
  EXPECT_EQ(loads, 4) << "three.js's three scripts and the model";

  // A fresh Chromium: its own profile; no sandbox (the tests may run as root).
  const auto chromium = [&](const std::string& what, const std::string& hash, const std::string& name) {
    return runShell(fmt::format(
        "HOME={0} XDG_CONFIG_HOME={0}/config XDG_CACHE_HOME={0}/cache timeout 120 chromium --headless --no-sandbox "
        "--use-angle=swiftshader --enable-unsafe-swiftshader --window-size=320,240 --hide-scrollbars "
        "--virtual-time-budget=20000 --enable-logging=stderr {1} {2} > {3} 2> {4}",
        q(d / "profile"), what, q("file://" + (d / "web/index.html").string() + "#" + hash), q(d / (name + ".out")),
        q(d / (name + ".log"))));
  };
  const auto dom = chromium("--dump-dom", "clean=1", "dom");
  ASSERT_EQ(dom.status, 0) << readBytes(d / "dom.log")
                           << (dom.status == 127 ? "\nchromium is missing: scripts/setup --test installs it" : "");
  std::string page = readBytes(d / "dom.out");
  const std::string open = "<div id=\"status\" hidden=\"\">";
  const auto at = page.find(open);
  ASSERT_NE(at, std::string::npos) << page.substr(0, 2000);
  std::string text = page.substr(at + open.size(), page.find("</div>", at) - at - open.size());
  for (const auto& [from, to] : std::map<std::string, std::string>{{"&quot;", "\""}, {"&lt;", "<"}, {"&gt;", ">"}})
    for (auto p = text.find(from); p != std::string::npos; p = text.find(from, p)) text.replace(p, from.size(), to);
  for (auto p = text.find("&amp;"); p != std::string::npos; p = text.find("&amp;", p + 1)) text.replace(p, 5, "&");
  ASSERT_FALSE(text.empty()) << "the page never finished loading; Chromium's log:\n" << readBytes(d / "dom.log");
  const auto status = nlohmann::json::parse(text);
  EXPECT_TRUE(status.value("ready", false)) << status.dump(1);
  EXPECT_TRUE(status["problems"].empty()) << status["problems"].dump(1);
  EXPECT_EQ(status["maps"], nlohmann::json::array({"normal", "ao", "miss_mask"})) << "the table's order (and the miss "
                                                                                    "mask every asset carries)";
  std::istringstream log(readBytes(d / "dom.log"));
  for (std::string line; std::getline(log, line);) EXPECT_EQ(line.find(":CONSOLE"), std::string::npos) << line;

  // Shaded with and without the normal map, at the same camera (straight on).
  ASSERT_EQ(chromium("--screenshot=" + q(d / "with.png"), "clean=1&yaw=0&pitch=0", "with").status, 0);
  ASSERT_EQ(chromium("--screenshot=" + q(d / "without.png"), "clean=1&yaw=0&pitch=0&normal=0", "without").status, 0);
  const Image with = loadImage(d / "with.png"), without = loadImage(d / "without.png");
  ASSERT_EQ(with.width(), 320);
  ASSERT_EQ(with.height(), 240);
  // The background is the page's (#2b2d31). The page frames the model's bounding sphere
  // (radius 1 about its centre) to 1/1.05 of the vertical field of view (35°), so the unit
  // sphere's silhouette is a disc of angular radius asin(sin(17.5°) / 1.05): in pixels,
  // 120 · tan(that) / tan(17.5°). The 16-segment low poly is inscribed in it (a regular
  // 16-gon holds 97.4 % of its circle's area): within 5 % of the disc's share of the frame.
  const double half = 17.5 * 3.14159265358979 / 180.0;
  const double radius = 120.0 * std::tan(std::asin(std::sin(half) / 1.05)) / std::tan(half);
  const double expected = 3.14159265358979 * radius * radius / (320.0 * 240.0);
  const auto background = [](const Image& im, int x, int y) {
    return std::fabs(im.at(x, y, 0) - 0x2b / 255.0f) < 0.02f && std::fabs(im.at(x, y, 1) - 0x2d / 255.0f) < 0.02f &&
           std::fabs(im.at(x, y, 2) - 0x31 / 255.0f) < 0.02f;
  };
  int model = 0, changed = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const bool inside = !background(with, x, y);
      model += inside;
      if (!inside) continue;
      double diff = 0.0;
      for (int c = 0; c < 3; ++c) diff += std::fabs(with.at(x, y, c) - without.at(x, y, c));
      changed += diff > 6.0 / 255.0;
    }
  const double share = double(model) / (320.0 * 240.0);
  EXPECT_NEAR(share / expected, 1.0, 0.05) << "the model covers " << share << " of the frame, the disc " << expected;
  // The bumps (4 % of the radius, 9 waves) bend the shading over much of the sphere; the
  // low poly's own smooth shading is all there is without the map.
  EXPECT_GT(double(changed) / model, 0.25) << changed << " of " << model << " model pixels changed by the normal map";
}

// glint cut's glTF goes through the same writer (mesh/gltf.h): the validator passes both forms.
TEST(GltfFiles, GlintCutsGlbAndGltfPassTheValidatorToo) {
  const auto d = dir("cut");
  writeObj(bumpySphere(), d / "ball.obj");
  for (const char* file : {"cut.glb", "cut.gltf"}) {
    const auto r = runGlint("-q cut " + q(d / "ball.obj") + " -o " + q(d / file) + " --light 0,3,2,key");
    ASSERT_EQ(r.status, 0) << r.output;
    const nlohmann::json verdict = validateGltf(d / file);
    EXPECT_EQ(verdict.value("errors", -1), 0) << verdict.dump(1);
    EXPECT_EQ(verdict.value("warnings", -1), 0) << verdict.dump(1);
    EXPECT_EQ(verdict.value("infos", -1), 0) << verdict.dump(1);
  }
}

// A file name is text on the page: markup, quotes and $(...) in the low poly's name stay
// characters of its title (escaped), and a line break in it bakes as any name does.
TEST(BakePreview, AFileNameWithMarkupQuotesAndALineBreakStaysTextInThePage) {
  const auto d = dir("preview-name");
  const std::string name = "a<b onload=x>&\"q'$(touch PWNED)\nz";
  writeObj(makeUvSphere(1.0f, 16, 8), d / (name + ".obj"));
  writeObj(bumpySphere(), d / "high.obj");
  const auto bake = runGlint("bake " + q(d / (name + ".obj")) + " " + q(d / "high.obj") + " -o " + q(d / "n.png") +
                             " --size 16x16 -q --preview " + q(d / "web"));
  ASSERT_EQ(bake.status, 0) << bake.output;
  const std::string page = readBytes(d / "web/index.html");
  EXPECT_EQ(page.find("<b onload"), std::string::npos);
  EXPECT_NE(page.find("a&lt;b onload=x&gt;&amp;&quot;q&#39;$(touch PWNED)\nz"), std::string::npos);
  EXPECT_FALSE(fs::exists(d / "PWNED"));
  EXPECT_FALSE(fs::exists("PWNED"));
}

namespace {
/// base64 text's bytes (the alphabet only; anything else ends the text).
std::string fromBase64(std::string_view text) {
  std::string out;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    const char* at = std::strchr("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/", c);
    if (!at || c == '\0') break;
    bits = bits << 6 | std::uint32_t(at - "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/");
    if (++count == 4) {
      out += char(bits >> 16), out += char(bits >> 8), out += char(bits);
      bits = 0, count = 0;
    }
  }
  return out;
}

/// A .glb's JSON chunk.
std::string glbJson(const std::string& glb) {
  if (glb.size() < 20) return {};
  std::uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return glb.substr(20, length);
}
}  // namespace

// An exported page holds only what glint wrote (issue 44): the model file carries a texture
// glint does not read, an emissive map at an http: address, which a browser would fetch
// from the network if the file's own bytes were copied. The page leaves it out and says so;
// nothing glint writes names an address with a scheme or a path out of the folder; and
// Chromium, with every host unresolvable, loads only files in the folder and starts no
// request of the page's own (its NetLog: every request's initiator; Chromium's own
// background requests have none).
TEST(BakePreview, AnExportedPageHoldsOnlyWhatGlintWroteAndFetchesNothingOutsideItsFolder) {
  const auto d = dir("export-self-contained");
  const fs::path model = d / "lamp.glb";
  fs::copy_file(fs::path(GLINT_SOURCE_DIR) / "fuzz/regressions/models/export-http-emissive-texture.glb", model);
  ASSERT_NE(readBytes(model).find("http://example.com/emissive.png"), std::string::npos) << "the model references the network";
  const auto web = runGlint("view " + q(model) + " --export-web " + q(d / "web"));
  ASSERT_EQ(web.status, 0) << web.output;
  EXPECT_NE(web.output.find("warning: --export-web: materials[0].emissiveTexture is left out of the page"), std::string::npos)
      << web.output;

  // What glint wrote: the page, its script (the model as base64: decoded), the model's JSON.
  const std::string script = readBytes(d / "web/model.js");
  const auto quote = script.find('"');
  ASSERT_NE(quote, std::string::npos);
  const std::string embedded = fromBase64(std::string_view(script).substr(quote + 1));
  EXPECT_EQ(embedded, readBytes(d / "web/model.glb")) << "model.js holds model.glb";
  const std::map<std::string, std::string> written = {{"index.html", readBytes(d / "web/index.html")},
                                                      {"model.js", script},
                                                      {"model.glb's JSON", glbJson(embedded)}};
  for (const auto& [name, text] : written) {
    ASSERT_FALSE(text.empty()) << name;
    for (const char* reference : {"http:", "https:", "file:", "../", "\"uri\""})
      EXPECT_EQ(text.find(reference), std::string::npos) << name << " holds " << reference;
  }
  const auto json = nlohmann::json::parse(glbJson(embedded));
  ASSERT_FALSE(json["images"].empty()) << "the base colour texture";
  for (const auto& image : json["images"]) EXPECT_TRUE(image.contains("bufferView")) << image << ": embedded";
  EXPECT_EQ(json["materials"][0].count("emissiveTexture"), 0u);

  const auto chromium = runShell(fmt::format(
      "HOME={0} XDG_CONFIG_HOME={0}/config XDG_CACHE_HOME={0}/cache timeout 120 chromium --headless --no-sandbox "
      "--use-angle=swiftshader --enable-unsafe-swiftshader --window-size=320,240 --virtual-time-budget=20000 "
      "--no-first-run --disable-background-networking --disable-component-update --disable-sync "
      "--host-resolver-rules='MAP * ~NOTFOUND' --log-net-log={1} --net-log-capture-mode=Default --dump-dom {2} > {3} 2> {4}",
      q(d / "profile"), q(d / "net.json"), q("file://" + (d / "web/index.html").string() + "#clean=1"), q(d / "dom.out"),
      q(d / "dom.log")));
  ASSERT_EQ(chromium.status, 0) << readBytes(d / "dom.log");
  const std::string page = readBytes(d / "dom.out");
  const std::string open = "<div id=\"status\" hidden=\"\">";
  const auto at = page.find(open);
  ASSERT_NE(at, std::string::npos) << page.substr(0, 2000);
  std::string text = page.substr(at + open.size(), page.find("</div>", at) - at - open.size());
  for (auto p = text.find("&quot;"); p != std::string::npos; p = text.find("&quot;", p)) text.replace(p, 6, "\"");
  for (auto p = text.find("&amp;"); p != std::string::npos; p = text.find("&amp;", p + 1)) text.replace(p, 5, "&");
  const auto status = nlohmann::json::parse(text);
  ASSERT_TRUE(status.value("ready", false)) << text;
  const std::string folder = "file://" + (d / "web").string() + "/";
  ASSERT_GE(status["resources"].size(), 5u) << status.dump(1) << ": three.js's three scripts, model.js and the texture";
  for (const auto& url : status["resources"]) {
    const std::string u = url.get<std::string>();
    EXPECT_TRUE(u.starts_with(folder) || u.starts_with("blob:")) << u << " is neither a file of the page's folder nor in memory";
  }

  // The NetLog: no request started by the page (an initiator other than Chromium's own).
  const auto net = nlohmann::json::parse(readBytes(d / "net.json"), nullptr, false);
  ASSERT_FALSE(net.is_discarded()) << "Chromium's NetLog did not parse";
  const int startJob = net["constants"]["logEventTypes"].value("URL_REQUEST_START_JOB", -1);
  ASSERT_GE(startJob, 0);
  int browserRequests = 0;
  for (const auto& event : net["events"]) {
    if (event.value("type", -1) != startJob || !event.contains("params") || !event["params"].contains("url")) continue;
    const auto& params = event["params"];  // the job's start (its end has no address)
    if (params.value("initiator", "") == "not an origin") {
      ++browserRequests;  // Chromium's own (time, updates): refused by the resolver rules
      continue;
    }
    ADD_FAILURE() << "the page requested " << params.value("url", "?") << " (initiator " << params.value("initiator", "?") << ")";
  }
  RecordProperty("chromium_background_requests", browserRequests);
}
