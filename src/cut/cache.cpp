// Cached cuts (cut/cache.h): a small binary file per (scene, lights, versions).
#include "glint/cut/cache.h"

#include "glint/core/cache.h"
#include "glint/core/error.h"
#include "glint/core/hash.h"
#include "glint/core/file.h"
#include "glint/core/log.h"

#include "binary.h"
#include "pieces.h"

#include <chrono>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <span>

namespace glint::cut {
namespace fs = std::filesystem;

namespace {

constexpr char kCacheMagic[8] = {'G', 'L', 'I', 'N', 'T', 'C', 'T', 'R'};
constexpr std::uint32_t kFormatVersion = 1;

}  // namespace

CutTriangles cutTriangles(const CutMesh& mesh) {
  Triangles t = triangulate(mesh);
  CutTriangles out;
  out.positions = std::move(t.mesh.positions);
  out.indices = std::move(t.mesh.indices);
  out.trianglePolygon = std::move(t.trianglePolygon);
  out.polygonSource = mesh.polygonSource;
  out.polygonMask = mesh.polygonMask;
  return out;
}

std::uint64_t cutCacheKey(const Mesh& scene, const std::vector<Light>& lights, const std::vector<std::uint32_t>& mergeGroups) {
  // Each value's bytes in memory order (little-endian here, as the cache files are).
  Fnv1a h(inputHash(scene, lights));
  h.add(std::uint64_t(lights.size())).add(std::uint64_t(kCutterVersion)).add(std::uint64_t(kFormatVersion));
  if (!mergeGroups.empty()) h.add(std::uint64_t(mergeGroups.size())).add(std::span(mergeGroups));
  return h.value();
}

namespace {
/// The file's bytes, written straight to `path` (the caller makes it atomic).
void writeCutFile(const CutTriangles& t, std::uint64_t key, const fs::path& path) {
  detail::BinaryWriter w;
  for (char c : kCacheMagic) w.pod(c);
  w.pod(kFormatVersion);
  w.pod(key);
  w.array(t.positions);
  w.array(t.indices);
  w.array(t.trianglePolygon);
  w.array(t.polygonSource);
  w.array(t.polygonMask);
  const std::string& out = w.data();
  std::ofstream file(path, std::ios::binary);
  file.write(out.data(), std::streamsize(out.size()));
  file.close();
  if (!file) fail(ErrorKind::Output, "cannot write '{}'", path.string());
}
}  // namespace

void saveCutTriangles(const CutTriangles& t, std::uint64_t key, const fs::path& path) {
  writeAtomically(path, [&](const fs::path& tmp) { writeCutFile(t, key, tmp); });
}

CutTriangles loadCutTriangles(const fs::path& path, std::uint64_t expectedKey) {
  detail::BinaryReader r(readTextFile(path), fmt::format("'{}' is not a usable cut", path.string()));
  char magic[sizeof(kCacheMagic)];
  for (char& c : magic) c = r.pod<char>();
  if (std::memcmp(magic, kCacheMagic, sizeof(kCacheMagic)) != 0) r.bad("not a glint cut file");
  if (r.pod<std::uint32_t>() != kFormatVersion) r.bad("written by another version of glint");
  const auto key = r.pod<std::uint64_t>();
  if (expectedKey != 0 && key != expectedKey) r.bad("the cut of another scene");
  CutTriangles t;
  t.positions = r.array<vec3>();
  t.indices = r.array<std::uint32_t>();
  t.trianglePolygon = r.array<std::uint32_t>();
  t.polygonSource = r.array<std::uint32_t>();
  t.polygonMask = r.array<LightMask>();
  if (!r.atEnd()) r.bad("trailing bytes");
  if (t.indices.size() != 3 * t.trianglePolygon.size()) r.bad("index and triangle counts disagree");
  if (t.polygonSource.size() != t.polygonMask.size()) r.bad("polygon counts disagree");
  for (const std::uint32_t i : t.indices)
    if (i >= t.positions.size()) r.bad("vertex index out of range");
  for (const std::uint32_t p : t.trianglePolygon)
    if (p >= t.polygonMask.size()) r.bad("polygon index out of range");
  return t;
}

CachedCut cachedCut(const Mesh& scene, const std::vector<Light>& lights, const CachedCutOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  CachedCut out;
  out.key = cutCacheKey(scene, lights, options.mergeGroups);
  const fs::path directory = options.directory.empty() ? cacheDirectory() : options.directory;
  const std::string name = fmt::format("{}-{:016x}.cut", options.name, out.key);
  const auto build = [&](const fs::path& tmp) {
    log::info("cutting the static shadows of '{}' ({} triangles, {} lights) — once; kept in {}", options.name,
              scene.triangleCount(), lights.size(), directory.string());
    CutOptions cutOptions;
    cutOptions.lights = lights;
    cutOptions.progress = options.progress;
    cutOptions.cancel = options.cancel;
    cutOptions.mergeGroups = options.mergeGroups;
    CutResult result = cut(scene, cutOptions);
    out.warnings = result.warnings;
    out.triangles = cutTriangles(result.mesh);
    writeCutFile(out.triangles, out.key, tmp);  // cachedFile renames it into place
  };
  for (int attempt = 0;; ++attempt) {
    const CacheEntry entry = cachedFile(directory, name, build, attempt > 0);
    out.file = entry.path;
    out.built = entry.built;
    if (entry.built) break;  // `out.triangles` is what was just written
    try {
      out.triangles = loadCutTriangles(entry.path, out.key);
      break;
    } catch (const Error& e) {
      if (attempt > 0) throw;
      log::warn("{}; cutting it again", e.what());
    }
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace glint::cut
