// Cached cuts (cut/cache.h): a small binary file per (scene, lights, versions).
#include "glint/cut/cache.h"

#include "glint/core/cache.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"

#include "pieces.h"

#include <chrono>
#include <cstring>
#include <fstream>

namespace glint::cut {
namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'G', 'L', 'I', 'N', 'T', 'C', 'T', 'R'};
constexpr std::uint32_t kFormatVersion = 1;

std::uint64_t mix(std::uint64_t h, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) {
    h ^= (value >> (8 * i)) & 0xFF;
    h *= 1099511628211ull;
  }
  return h;
}

template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <typename T>
void putArray(std::string& out, const std::vector<T>& v) {
  put(out, std::uint64_t(v.size()));
  out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

class Reader {
public:
  Reader(std::string data, fs::path path) : m_data(std::move(data)), m_path(std::move(path)) {}
  template <typename T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, m_data.data() + m_pos, sizeof(T));
    m_pos += sizeof(T);
    return v;
  }
  template <typename T>
  std::vector<T> getArray() {
    const auto n = get<std::uint64_t>();
    if (n > (m_data.size() - m_pos) / sizeof(T)) bad("truncated");
    std::vector<T> v(n);
    std::memcpy(v.data(), m_data.data() + m_pos, n * sizeof(T));
    m_pos += n * sizeof(T);
    return v;
  }
  bool atEnd() const { return m_pos == m_data.size(); }
  [[noreturn]] void bad(std::string_view why) const {
    fail(ErrorKind::Input, "'{}' is not a usable cut: {}", m_path.string(), why);
  }

private:
  void need(std::size_t n) const {
    if (n > m_data.size() - m_pos) bad("truncated");
  }
  std::string m_data;
  fs::path m_path;
  std::size_t m_pos = 0;
};

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

std::uint64_t cutCacheKey(const Mesh& scene, const std::vector<Light>& lights) {
  std::uint64_t h = inputHash(scene, lights);
  h = mix(h, lights.size());
  h = mix(h, kCutterVersion);
  return mix(h, kFormatVersion);
}

namespace {
/// The file's bytes, written straight to `path` (the caller makes it atomic).
void writeCutFile(const CutTriangles& t, std::uint64_t key, const fs::path& path) {
  std::string out;
  out.append(kMagic, sizeof(kMagic));
  put(out, kFormatVersion);
  put(out, key);
  putArray(out, t.positions);
  putArray(out, t.indices);
  putArray(out, t.trianglePolygon);
  putArray(out, t.polygonSource);
  putArray(out, t.polygonMask);
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
  Reader r(readTextFile(path), path);
  char magic[sizeof(kMagic)];
  for (char& c : magic) c = r.get<char>();
  if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) r.bad("not a glint cut file");
  if (r.get<std::uint32_t>() != kFormatVersion) r.bad("written by another version of glint");
  const auto key = r.get<std::uint64_t>();
  if (expectedKey != 0 && key != expectedKey) r.bad("the cut of another scene");
  CutTriangles t;
  t.positions = r.getArray<vec3>();
  t.indices = r.getArray<std::uint32_t>();
  t.trianglePolygon = r.getArray<std::uint32_t>();
  t.polygonSource = r.getArray<std::uint32_t>();
  t.polygonMask = r.getArray<LightMask>();
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
  out.key = cutCacheKey(scene, lights);
  const fs::path directory = options.directory.empty() ? cacheDirectory() : options.directory;
  const std::string name = fmt::format("{}-{:016x}.cut", options.name, out.key);
  const auto build = [&](const fs::path& tmp) {
    log::info("cutting the static shadows of '{}' ({} triangles, {} lights) — once; kept in {}", options.name,
              scene.triangleCount(), lights.size(), directory.string());
    CutOptions cutOptions;
    cutOptions.lights = lights;
    cutOptions.progress = options.progress;
    cutOptions.cancel = options.cancel;
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
