#pragma once
// What bake's job (job.cpp) and its batches (batch.cpp) share: the high meshes of a batch.
#include "glint/bake/job.h"
#include "glint/bake/scene_cache.h"
#include "glint/mesh/mesh.h"
#include "glint/mesh/parts.h"

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace glint::bake {

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

}  // namespace glint::bake
