// What a bake writes besides its maps (bake/job.h's --asset and --preview): the low poly as
// baked, its groups apart, with the maps, staged with them.
#include "glint/bake/asset.h"
#include "glint/bake/job.h"
#include "glint/bake/udim.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "job_internal.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace glint::bake {

using Json = nlohmann::ordered_json;

/// --asset and --preview: a glTF file name, a tangent-space bake, places that can be written.
void checkAssetOptions(const BakeJob& a) {
  if (a.asset.empty() && a.preview.empty()) return;
  if (a.space != "tangent") {
    fail(ErrorKind::Usage, "--asset and --preview hold a tangent-space normal map (glTF's normalTexture): they need "
         "--space tangent, got {}", a.space);
  }
  if (!a.asset.empty()) {
    const std::string ext = lowerExtension(a.asset);
    if (ext != ".glb" && ext != ".gltf") fail(ErrorKind::Usage, "--asset '{}': a glTF asset ends in .glb or .gltf", a.asset);
    if (hasUdimToken(a.asset)) fail(ErrorKind::Usage, "--asset '{}': one asset holds every UDIM tile; name it without <UDIM>", a.asset);
    checkWritable(a.asset);
  }
  if (!a.preview.empty()) checkPageFolder(a.preview, "--preview");
}

/// The bake's maps as an asset holds them: 8-bit as an 8-bit file would, the normal map in
/// OpenGL's +Y convention whatever --directx did to the loose file.
std::shared_ptr<const AssetMaps> assetMaps(const BakeJob& a, const BakeResult& result) {
  auto maps = std::make_shared<AssetMaps>();
  Image normal = result.normal.type() == PixelType::U8 ? result.normal : result.normal.converted(PixelType::U8);
  if (a.directX) {
    auto px = normal.pixels<std::uint8_t>();
    for (std::size_t i = 1; i < px.size(); i += std::size_t(normal.channels())) px[i] = std::uint8_t(255 - px[i]);
  }
  (*maps)[std::size_t(Map::Normal)] = std::move(normal);
  for (const MapInfo& m : mapTable())
    if (m.map != Map::Normal && !result.map(m.map).empty())  // the maps asked for, and the miss mask
      (*maps)[std::size_t(m.map)] = m.forOutput(result.map(m.map), PixelType::U8, result.stats);
  return maps;
}

/// One tile's low poly as baked (result.low: its tangents, its split vertices) into the
/// asset: one part per bake group (`groupOf`: a triangle's group, empty for none), each its
/// own material named "<tile> <group>", sharing the tile's maps.
void addToAsset(Asset& asset, const Mesh& low, std::shared_ptr<const AssetMaps> maps, const std::string& tile,
                const std::function<std::string(std::size_t)>& groupOf) {
  std::map<std::string, std::vector<std::uint32_t>> groups;  // group -> triangles
  for (std::size_t t = 0; t < low.triangleCount(); ++t) groups[groupOf ? groupOf(t) : std::string()].push_back(std::uint32_t(t));
  for (const auto& [group, triangles] : groups) {
    AssetPart part;
    part.material = int(asset.materials.size());
    std::string name = tile;
    if (!group.empty()) name = name.empty() ? group : tile + " " + group;
    asset.materials.push_back({name.empty() ? asset.name : name, maps});
    std::vector<std::uint32_t> remap(low.vertexCount(), UINT32_MAX);
    Mesh& m = part.mesh;
    for (const std::uint32_t t : triangles)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = low.indices[3 * std::size_t(t) + std::size_t(k)];
        if (remap[v] == UINT32_MAX) {
          remap[v] = std::uint32_t(m.positions.size());
          m.positions.push_back(low.positions[v]);
          m.normals.push_back(low.normals[v]);
          m.uvs.push_back(low.uvs[v]);
          m.tangents.push_back(low.tangents[v]);
        }
        m.indices.push_back(remap[v]);
      }
    asset.parts.push_back(std::move(part));
  }
}

/// --asset and --preview, staged with the maps; their part of the report.
void writeAsset(const BakeJob& a, Asset& asset, ToolRun& run) {
  ToolRun::Phase writing(run, "asset");
  Json& report = run.report();
  asset.extras = {{"low", fs::path(a.low).filename().string()}, {"high", fs::path(a.high).filename().string()},
                  {"size", a.size}, {"samples", a.samples}, {"maps", report["maps"]}};
  if (report.contains("hard_edge_vertices")) asset.extras["hard_edge_vertices"] = report["hard_edge_vertices"];
  if (!a.asset.empty()) {
    saveAsset(asset, a.asset);
    report["asset"] = a.asset;
  }
  if (!a.preview.empty()) {
    const fs::path dir = checkPageFolder(a.preview, "--preview");
    savePreview(asset, dir);
    report["preview"] = (dir / "index.html").string();
  }
  std::size_t triangles = 0;
  for (const AssetPart& p : asset.parts) triangles += p.mesh.triangleCount();
  report["asset_materials"] = asset.materials.size();
  report["asset_triangles"] = triangles;
}

}  // namespace glint::bake
