// A bake as a glTF 2.0 asset and a web page that shows it (bake/asset.h).
#include "glint/bake/asset.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/locations.h"
#include "glint/mesh/gltf.h"
#include "glint/mesh/tangents.h"
#include "internal.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

namespace glint::bake {

namespace fs = std::filesystem;
using AssetJson = nlohmann::json;

std::size_t frameLowPolyInPlace(Mesh& low) {
  // Unit vertex normals: the renderer normalizes them per vertex before interpolating
  // (render/bump/normal_mapping.h), so the baker's frame starts from the same vectors.
  for (vec3& n : low.normals) {
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : vec3(0.0f, 0.0f, 1.0f);
  }
  return generateTangents(low);
}

Mesh frameLowPoly(Mesh low) {
  low.tangents.clear();
  if (!low.hasNormals()) generateSmoothNormals(low);  // as the baker frames it (prepare.cpp)
  frameLowPolyInPlace(low);
  return low;
}

namespace {

/// One primitive: the part's vertices (glTF's UVs: v flipped) and triangles.
AssetJson addPrimitive(gltf::Document& doc, const AssetPart& part) {
  const Mesh& m = part.mesh;
  if (m.indices.empty() || !m.hasNormals() || !m.hasUvs() || m.tangents.size() != m.positions.size())
    fail(ErrorKind::Input, "asset: a part without triangles, normals, UVs or tangents");
  vec3 lo(std::numeric_limits<float>::infinity()), hi(-lo);
  for (const vec3& p : m.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  std::vector<vec2> uvs(m.uvs.size());
  std::transform(m.uvs.begin(), m.uvs.end(), uvs.begin(), [](vec2 uv) { return vec2(uv.x, 1.0f - uv.y); });
  const std::size_t n = m.positions.size();
  AssetJson attributes = {
      {"POSITION", doc.addAccessor(m.positions.data(), n, gltf::kFloat, "VEC3", gltf::kVertices, {lo.x, lo.y, lo.z},
                                   {hi.x, hi.y, hi.z})},
      {"NORMAL", doc.addAccessor(m.normals.data(), n, gltf::kFloat, "VEC3", gltf::kVertices)},
      {"TANGENT", doc.addAccessor(m.tangents.data(), n, gltf::kFloat, "VEC4", gltf::kVertices)},
      {"TEXCOORD_0", doc.addAccessor(uvs.data(), n, gltf::kFloat, "VEC2", gltf::kVertices)}};
  const int indices = doc.addAccessor(m.indices.data(), m.indices.size(), gltf::kUnsignedInt, "SCALAR", gltf::kIndices);
  return {{"attributes", std::move(attributes)}, {"indices", indices}, {"material", part.material}, {"mode", 4}};
}

/// Each material with its maps' textures (one image per map of each map set, however many
/// materials share the set).
AssetJson addMaterials(gltf::Document& doc, const Asset& asset) {
  std::map<std::pair<const AssetMaps*, Map>, int> textures;
  AssetJson materials = AssetJson::array();
  for (const AssetMaterial& material : asset.materials) {
    if (!material.maps || (*material.maps)[std::size_t(Map::Normal)].empty())
      fail(ErrorKind::Input, "asset: material '{}' has no normal map", material.name);
    AssetJson maps = AssetJson::object();
    for (const MapInfo& info : mapTable()) {
      const Image& image = (*material.maps)[std::size_t(info.map)];
      if (image.empty()) continue;
      auto [at, added] = textures.try_emplace({material.maps.get(), info.map}, 0);
      if (added) {
        const Image u8 = image.type() == PixelType::U8 ? image : image.converted(PixelType::U8);
        at->second = doc.addTexture(doc.addImage(encodePng(u8), fmt::format("{} {}", material.name, info.reportKey)));
      }
      maps[info.reportKey] = {{"texture", at->second},
                              {"color_space", isColourMap(info.map) ? "srgb" : "linear"},
                              {"channels", image.channels()},
                              {"order", int(info.map)},  // the table's (JSON objects keep none)
                              {"holds", info.summary}};
    }
    AssetJson m = {{"name", material.name},
              {"pbrMetallicRoughness",
               {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.55}}},
              {"normalTexture", {{"index", maps["normal"]["texture"]}}},
              {"extras", {{"glint_maps", maps}}}};
    if (maps.contains("ao")) m["occlusionTexture"] = {{"index", maps["ao"]["texture"]}};
    materials.push_back(std::move(m));
  }
  return materials;
}

gltf::Document assetDocument(const Asset& asset) {
  if (asset.parts.empty()) fail(ErrorKind::Input, "asset: no triangles to write");
  gltf::Document doc("glint bake");
  AssetJson primitives = AssetJson::array();
  for (const AssetPart& part : asset.parts) {
    if (part.material < 0 || std::size_t(part.material) >= asset.materials.size())
      fail(ErrorKind::Internal, "asset: a part's material {} does not exist", part.material);
    primitives.push_back(addPrimitive(doc, part));
  }
  doc.json["materials"] = addMaterials(doc, asset);
  doc.json["meshes"] = AssetJson::array({{{"name", asset.name}, {"primitives", std::move(primitives)}}});
  doc.json["nodes"] = AssetJson::array({{{"name", asset.name}, {"mesh", 0}}});
  doc.json["scenes"] = AssetJson::array({{{"nodes", {0}}}});
  doc.json["scene"] = 0;
  doc.json["extras"] = {{"glint_bake", asset.extras}};
  return doc;
}

}  // namespace

void saveAsset(const Asset& asset, const fs::path& path) { assetDocument(asset).save(path); }

// ---------------------------------------------------------------- the preview page

std::string_view previewPage();  // web/bake-preview.html, embedded by the build (glint_embed_text)

namespace {
/// three.js's files the page loads (classic scripts, not modules: a page opened from disk
/// may load a module from no file), where scripts/setup puts them in glint's data.
constexpr const char* kThreeFiles[] = {"three.min.js", "OrbitControls.js", "GLTFLoader.js", "LICENSE"};
}  // namespace

std::vector<std::string> previewFiles() {
  std::vector<std::string> files{"index.html", "model.glb", "model.js"};
  for (const char* f : kThreeFiles) files.push_back(std::string("three/") + f);
  files.push_back(kPageMarker);
  return files;
}

fs::path checkPageFolder(const std::string& dir, std::string_view option) {
  fs::path path = fs::path(dir).lexically_normal();
  if (!path.has_filename() && path.has_parent_path()) path = path.parent_path();  // "prev/" as shell completion types it
  if (path.empty()) fail(ErrorKind::Usage, "{} needs a folder", option);
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec))
    fail(ErrorKind::Output, "{} '{}' is a file, not a folder", option, path.string());
  if (!fs::is_directory(path, ec)) {
    checkWritable(path);  // a new folder: its parent exists and can be written
    return path;
  }
  if (fs::exists(path / kPageMarker, ec)) {
    checkWritable(path / "index.html");
    return path;
  }
  // Someone else's folder: glint does not write its page over what is there.
  std::vector<std::string> held;
  std::size_t count = 0;
  for (fs::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec), ++count)
    if (held.size() < 3) held.push_back(it->path().filename().string());
  if (count > 0) {
    std::string list;
    for (const std::string& name : held) list += (list.empty() ? "" : ", ") + name;
    fail(ErrorKind::Output, "{} '{}' holds files glint did not write ({}{}): give a new or empty folder, or one glint "
         "wrote a page into", option, path.string(), list, count > held.size() ? fmt::format(" and {} more", count - held.size()) : "");
  }
  checkWritable(path / "index.html");
  return path;
}

void savePreview(const Asset& asset, const fs::path& dir) {
  savePreviewPage(assetDocument(asset).glb(), asset.name.empty() ? std::string("bake") : asset.name, dir);
}

void savePreviewPage(const std::vector<unsigned char>& glb, const std::string& title, const fs::path& dir) {
  std::vector<fs::path> three;
  for (const char* f : kThreeFiles)
    three.push_back(findDataFile(fs::path("web/three") / f, "three.js for the preview page (scripts/setup installs it)"));
  checkPageFolder(dir.string(), "the page's folder");
  createOutputDirectories(dir / "three");  // removed again if the run fails (core/file.h)
  writeAtomically(dir / "model.glb", [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
    if (!out) fail(ErrorKind::Output, "cannot write '{}'", (dir / "model.glb").string());
  });
  // The same bytes as a script: a page opened from disk (file://) may run a script beside
  // it but not fetch a file (Chromium refuses), so the page reads the asset from here.
  writeAtomically(dir / "model.js", [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << "// glint bake --preview: model.glb as base64, for a page opened from disk.\nwindow.glintModel = \"";
    gltf::writeBase64(out, glb);
    out << "\";\n";
    if (!out) fail(ErrorKind::Output, "cannot write '{}'", (dir / "model.js").string());
  });
  std::string page(previewPage());
  // The title is a file name: escaped, so `<`, `&` and quotes in it stay text.
  std::string escaped;
  for (const char c : title) {
    switch (c) {
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '&': escaped += "&amp;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&#39;"; break;
      default: escaped += c;
    }
  }
  for (std::size_t at = page.find("{{title}}"); at != std::string::npos; at = page.find("{{title}}", at + escaped.size()))
    page.replace(at, 9, escaped);
  writeTextAtomically(dir / "index.html", page);
  for (std::size_t i = 0; i < three.size(); ++i) writeTextAtomically(dir / "three" / kThreeFiles[i], readTextFile(three[i]));
  writeTextAtomically(dir / kPageMarker, "glint wrote the web page in this folder (glint bake --preview, glint view "
                                         "--export-web), and writes it again over its own files.\n");
}

}  // namespace glint::bake
