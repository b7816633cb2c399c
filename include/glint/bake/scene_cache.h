#pragma once
// glint/bake/scene_cache.h — BVHs kept between bakes of the same high poly (`glint bake
// --batch`: jobs that share a high mesh build its BVH once).
//
// A bake given a cache (BakeOptions::sceneCache) looks its high poly up by identity: the
// address and size of its vertex and index arrays, and the BVH quality the bake wants.
// The caller keeps the meshes alive and unchanged while the cache holds their BVHs (they
// are read in place), e.g. by loading each file once and keeping it for the batch.
// Bakes with bake groups, or whose high poly has no normals (the baker works on a copy),
// build their own BVH as before.

#include <cstddef>
#include <memory>

namespace glint {
struct Mesh;
}

namespace glint::bake {

class SceneCache {
public:
  SceneCache();
  ~SceneCache();
  SceneCache(const SceneCache&) = delete;
  SceneCache& operator=(const SceneCache&) = delete;

  /// Drops the BVHs of `mesh` (before the mesh goes away or changes).
  void release(const Mesh& mesh);
  std::size_t builds() const;  ///< BVHs built through the cache
  std::size_t reuses() const;  ///< bakes that found theirs built

  struct Impl;
  Impl& impl() { return *m_impl; }

private:
  std::unique_ptr<Impl> m_impl;
};

}  // namespace glint::bake
