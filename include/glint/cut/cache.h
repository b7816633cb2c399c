#pragma once
// glint/cut/cache.h — a scene's cut, kept on disk and used again: what a renderer loads.
//
// Contents
//   CutTriangles   the cut as triangles, each with its polygon, the input triangle it is a
//                  piece of, and the polygon's light mask
//   cutTriangles   a CutMesh → CutTriangles (triangulate)
//   cutCacheKey    the hash that names a cut: scene, lights, cutter and file versions
//   cachedCut      load the cut of (scene, lights) from the cache, or cut and store it
//   save/loadCutTriangles   the file format (binary, versioned, checked on reading)
//
// A scene whose static geometry is made in code (the `pipedream` stage) cuts it once and
// keeps the result under glint's cache directory (core/cache.h), named by a hash of
// everything that decides it — the positions and indices, the light positions,
// kCutterVersion and the file format — so any change to them is a new file, built on first
// use (with a progress bar on a terminal), and an unchanged scene loads in a fraction of a
// second. Several processes asking at once (ctest -j) build it once: the first cuts under a
// lock, the others wait and load. A file that fails to load (truncated, foreign, another
// key) is rebuilt. Clearing the cache is deleting the directory.
//
/// ```cpp
/// const glint::Mesh scene = glint::loadMesh("stage.ply");
/// const std::vector<glint::cut::Light> lights = {{.position = {0, 4, 0}, .name = "lamp"}};
/// const glint::cut::CachedCut cut = glint::cut::cachedCut(scene, lights, {.name = "stage", .progress = true});
/// const std::size_t t = 0;
/// const bool lit = cut.triangles.polygonMask[cut.triangles.trianglePolygon[t]] & 1u;  // light 0 reaches triangle t
/// ```

#include "glint/cut/cutter.h"

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint::cut {

/// The cut's triangles (cutter.h's triangulate: n − 2 per convex polygon, no zero area).
struct CutTriangles {
  std::vector<vec3> positions;
  std::vector<std::uint32_t> indices;          ///< 3 per triangle, counter-clockwise
  std::vector<std::uint32_t> trianglePolygon;  ///< the polygon each triangle is part of
  std::vector<std::uint32_t> polygonSource;    ///< the input triangle each polygon is a piece of
  std::vector<LightMask> polygonMask;          ///< the lights that reach each polygon

  std::size_t triangleCount() const { return trianglePolygon.size(); }
  std::size_t polygonCount() const { return polygonMask.size(); }
  /// The light mask of triangle t.
  LightMask mask(std::size_t t) const { return polygonMask[trianglePolygon[t]]; }
  /// The input triangle triangle t is a piece of.
  std::uint32_t source(std::size_t t) const { return polygonSource[trianglePolygon[t]]; }
};

/// The triangles of a cut mesh, with its polygons' sources and masks.
CutTriangles cutTriangles(const CutMesh& mesh);

/// Names a cut: FNV-1a over the scene's positions and indices, the light positions,
/// kCutterVersion, the cache file's format version and the merge groups (when given).
std::uint64_t cutCacheKey(const Mesh& scene, const std::vector<Light>& lights,
                          const std::vector<std::uint32_t>& mergeGroups = {});

struct CachedCutOptions {
  std::filesystem::path directory;  ///< empty: glint's cache directory (core/cache.h)
  std::string name = "cut";         ///< file name prefix: <name>-<key in hex>.cut
  bool progress = false;            ///< the cutter's progress bar while building (on a terminal)
  const std::atomic<bool>* cancel = nullptr;  ///< passed to the cutter: Error(Interrupted), nothing written
  std::vector<std::uint32_t> mergeGroups;     ///< CutOptions::mergeGroups
};

struct CachedCut {
  CutTriangles triangles;
  std::filesystem::path file;  ///< where it is kept
  std::uint64_t key = 0;
  bool built = false;          ///< this call cut it (false: loaded)
  double seconds = 0.0;        ///< cutting and writing when built, reading otherwise
  std::vector<std::string> warnings;  ///< the cutter's, when built
};

/// The cut of `scene` by `lights` from the cache, cut and stored first when missing or
/// unreadable (see above). Errors as cut() (the scene, the lights), Error(Output) when the
/// cache directory cannot be written.
CachedCut cachedCut(const Mesh& scene, const std::vector<Light>& lights, const CachedCutOptions& options = {});

/// Writes a cut (binary: magic, format version, key, counts, arrays) atomically.
void saveCutTriangles(const CutTriangles& triangles, std::uint64_t key, const std::filesystem::path& path);
/// Reads a file written by saveCutTriangles. Error(Input) when it is missing, truncated,
/// of another format version, inconsistent (indices, polygons out of range), or has a key
/// other than `expectedKey` (0: any key).
CutTriangles loadCutTriangles(const std::filesystem::path& path, std::uint64_t expectedKey = 0);

}  // namespace glint::cut
