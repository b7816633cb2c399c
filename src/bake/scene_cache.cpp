// BVHs kept between bakes of the same high poly (bake/scene_cache.h).
#include "glint/bake/scene_cache.h"

#include "scene_cache_internal.h"

#include <mutex>

namespace glint::bake {

SceneCache::SceneCache() : m_impl(std::make_unique<Impl>()) {}
SceneCache::~SceneCache() = default;
void SceneCache::release(const Mesh& mesh) {
  std::lock_guard lock(m_impl->mutex);
  std::erase_if(m_impl->scenes, [&](const auto& entry) { return entry.first.positions == mesh.positions.data(); });
}
std::size_t SceneCache::builds() const { return m_impl->builds; }
std::size_t SceneCache::reuses() const { return m_impl->reuses; }

std::shared_ptr<raytrace::Scene> SceneCache::Impl::get(const Mesh& mesh, const raytrace::SceneOptions& options,
                                                       bool& reused) {
  const Key key{mesh.positions.data(), mesh.positions.size(), mesh.indices.data(), mesh.indices.size(),
                int(options.quality)};
  std::lock_guard lock(mutex);
  for (const auto& [k, scene] : scenes) {
    if (k == key) {
      ++reuses;
      reused = true;
      return scene;
    }
  }
  auto scene = std::make_shared<raytrace::Scene>(mesh, options);
  scenes.emplace_back(key, scene);
  ++builds;
  reused = false;
  return scene;
}

}  // namespace glint::bake
