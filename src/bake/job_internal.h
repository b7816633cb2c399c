#pragma once
// What bake's job (job.cpp) and its batches (batch.cpp) share: the high meshes of a batch.
#include "glint/bake/asset.h"
#include "glint/bake/baker.h"
#include "glint/bake/job.h"
#include "glint/bake/scene_cache.h"
#include "glint/mesh/mesh.h"
#include "glint/mesh/parts.h"

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace glint::bake {

/// BakeJob::gpuPossible for a job's --device with `gpu` as its backend (an EGL query: no context).
bool gpuPossible(const std::string& device, GpuBackend* gpu);

namespace fs = std::filesystem;

/// Within one `--batch` run: the high meshes read so far, by path and modification time,
/// and their BVHs, so that jobs sharing a high poly read it and build its BVH once.
class HighMeshCache {
public:
  struct Entry {
    fs::path path;
    fs::file_time_type modified;
    std::shared_ptr<const Mesh> mesh;        ///< read with loadMesh
    std::shared_ptr<const MeshParts> parts;  ///< read with loadMeshParts
  };
  std::vector<Entry> entries;
  SceneCache scenes;  // after `entries`: destroyed first (its BVHs read their meshes)
  /// Jobs still to run per high-mesh path as given: a mesh is kept only while one will use it.
  std::map<std::string, int> usesLeft;
  std::string progressLabel;  ///< "bake 2/5": the progress bar's label for the job running

  /// After a job: forget its high mesh (and BVH) when no later job reads the same path.
  void done(const std::string& path) {
    if (--usesLeft[path] > 0) return;
    std::erase_if(entries, [&](const Entry& e) {
      std::error_code ec;
      if (!fs::equivalent(e.path, path, ec)) return false;
      scenes.release(e.parts ? e.parts->mesh : *e.mesh);
      return true;
    });
  }

  Entry* find(const std::string& path, bool parts) {
    std::error_code ec;
    const fs::file_time_type modified = fs::last_write_time(path, ec);
    if (ec) return nullptr;
    for (Entry& e : entries) {
      std::error_code same;
      if (e.modified == modified && fs::equivalent(e.path, path, same) && (parts ? bool(e.parts) : bool(e.mesh))) return &e;
    }
    return nullptr;
  }
  void add(const std::string& path, std::shared_ptr<const Mesh> mesh, std::shared_ptr<const MeshParts> parts) {
    std::error_code ec;
    const fs::file_time_type modified = fs::last_write_time(path, ec);
    if (!ec) entries.push_back({path, modified, std::move(mesh), std::move(parts)});
  }
};

/// CLI11's type name of the options that name files: a batch file's relative paths are
/// resolved against the batch file's folder for exactly these options.
inline constexpr const char* kFile = "FILE";

// batch.cpp: the arguments of a batch's job.
/// The argument list `glint bake` gets for settings (canonical keys, later layers winning):
/// positionals first, then the options in the command's order; a flag appears when true;
/// a number is written as JSON writes it; a relative path (a FILE option) is made relative
/// to `base`, the batch file's folder.
std::vector<std::string> argumentsFor(const CLI::App& app, const std::vector<const nlohmann::ordered_json*>& layers,
                                      const fs::path& base);

// options.cpp: the job's options as the baker's.
/// The extra maps a job asks for: those with a file.
MapSet mapsOf(const BakeJob& job);
/// The job's fields as the baker's options: the one translation, which the bake and its
/// memory estimate share. Error(Usage) for a value that does not read (a size, a distance).
BakeOptions optionsOf(const BakeJob& job);

// job_asset.cpp: --asset and --preview.
/// --asset and --preview: a glTF file name, a tangent-space bake, places that can be written.
void checkAssetOptions(const BakeJob& job);
/// The bake's maps as an asset holds them: 8-bit as an 8-bit file would, the normal map in
/// OpenGL's +Y convention whatever --directx did to the loose file.
std::shared_ptr<const AssetMaps> assetMaps(const BakeJob& job, const BakeResult& result);
/// One tile's low poly as baked into the asset: one part per bake group (`groupOf`: a
/// triangle's group, empty for none), each its own material, sharing the tile's maps.
void addToAsset(Asset& asset, const Mesh& low, std::shared_ptr<const AssetMaps> maps, const std::string& tile,
                const std::function<std::string(std::size_t)>& groupOf);
/// --asset and --preview, staged with the maps; their part of the report.
void writeAsset(const BakeJob& job, Asset& asset, ToolRun& run);

}  // namespace glint::bake
