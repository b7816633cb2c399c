#pragma once
// Private: SceneCache's state (bake/scene_cache.h), used by baker.cpp.
#include "glint/bake/scene_cache.h"
#include "glint/mesh/mesh.h"
#include "glint/raytrace/raytracer.h"

#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace glint::bake {

struct SceneCache::Impl {
  struct Key {
    const void* positions;
    std::size_t vertexCount;
    const void* indices;
    std::size_t indexCount;
    int quality;
    bool operator==(const Key&) const = default;
  };
  std::mutex mutex;
  std::vector<std::pair<Key, std::shared_ptr<raytrace::Scene>>> scenes;
  std::size_t builds = 0, reuses = 0;
  /// The BVH of `mesh` at options.quality, built on the first call; `reused` says which.
  std::shared_ptr<raytrace::Scene> get(const Mesh& mesh, const raytrace::SceneOptions& options, bool& reused);
};

}  // namespace glint::bake
