// The post-processing the fast importers share with Assimp's reading of the same files:
// each step reproduces the Assimp 5.2 step named in its comment (same rule, same order,
// float arithmetic where the result depends on it), so the fast paths give Assimp's Mesh.
#include "import_steps.h"

#include "glint/core/error.h"
#include "glint/core/hash.h"
#include "glint/core/log.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace glint::detail {
namespace {

/// Assimp's aiVector3D::Normalize: divides by the length through its reciprocal.
vec3 assimpNormalize(vec3 v) {
  const float length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  if (length == 0.0f) return v;
  const float inverse = 1.0f / length;
  return v * inverse;
}

float dot3(const vec3& a, const vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// Signed area of the 2-D triangle (Assimp's GetArea2D, in double).
double area2d(const vec2& a, const vec2& b, const vec2& c) {
  return 0.5 * (a.x * (double(c.y) - b.y) + b.x * (double(a.y) - c.y) + c.x * (double(b.y) - a.y));
}

bool pointInTriangle2d(const vec2& p0, const vec2& p1, const vec2& p2, const vec2& pp) {
  const vec2 v0 = p1 - p0, v1 = p2 - p0, v2 = pp - p0;
  double dot00 = v0.x * v0.x + v0.y * v0.y;
  double dot11 = v1.x * v1.x + v1.y * v1.y;
  const double dot01 = v0.x * v1.x + v0.y * v1.y;
  const double dot02 = v0.x * v2.x + v0.y * v2.y;
  const double dot12 = v1.x * v2.x + v1.y * v2.y;
  const double denom = dot00 * dot11 - dot01 * dot01;
  if (denom == 0.0) return false;
  const double inverse = 1.0 / denom;
  dot11 = (dot11 * dot02 - dot01 * dot12) * inverse;
  dot00 = (dot00 * dot12 - dot01 * dot02) * inverse;
  return dot11 > 0 && dot00 > 0 && dot11 + dot00 < 1;
}

/// Assimp's ear cutting for a polygon of n > 4 corners (TriangulateProcess): projected on
/// the plane of its Newell normal, ears cut from the front; a polygon with no ear left
/// (not simple) keeps the triangles cut so far, as Assimp does.
void earCut(const PolyMesh& mesh, std::uint32_t start, int n, std::vector<std::uint32_t>& out) {
  std::vector<vec3> v3(std::size_t(n) + 2);
  std::vector<vec2> v2(std::size_t(n) + 2);
  std::vector<char> done(std::size_t(n), 0);
  for (int i = 0; i < n; ++i) v3[std::size_t(i)] = mesh.positions[mesh.corners[start + std::uint32_t(i)]];
  v3[std::size_t(n)] = v3[0];
  v3[std::size_t(n) + 1] = v3[1];
  float sxy = 0, syz = 0, szx = 0;
  for (int t = 1; t <= n; ++t) {
    const vec3 &c = v3[std::size_t(t)], &lo = v3[std::size_t(t - 1)], &hi = v3[std::size_t(t + 1)];
    sxy += c.x * (hi.y - lo.y);
    syz += c.y * (hi.z - lo.z);
    szx += c.z * (hi.x - lo.x);
  }
  const vec3 normal(syz, szx, sxy);
  const float ax = std::fabs(normal.x), ay = std::fabs(normal.y), az = std::fabs(normal.z);
  int ac = 0, bc = 1;
  float inv = normal.z;
  if (ax > ay) {
    if (ax > az) {
      ac = 1;
      bc = 2;
      inv = normal.x;
    }
  } else if (ay > az) {
    ac = 2;
    bc = 0;
    inv = normal.y;
  }
  if (inv < 0.0f) std::swap(ac, bc);
  for (int i = 0; i < n; ++i) v2[std::size_t(i)] = vec2(v3[std::size_t(i)][ac], v3[std::size_t(i)][bc]);

  const std::size_t firstOut = out.size();
  int num = n, ear = 0, prev = n - 1, next = 0;
  while (num > 3) {
    int found = 0;
    for (ear = next;; prev = ear, ear = next) {
      for (next = ear + 1; done[std::size_t(next >= n ? next = 0 : next)]; ++next) {
      }
      if (next < ear && ++found == 2) break;
      const vec2 &p1 = v2[std::size_t(ear)], &p0 = v2[std::size_t(prev)], &p2 = v2[std::size_t(next)];
      if (area2d(p0, p1, p2) > 0) continue;  // OnLeftSideOfLine2D(p0, p2, p1): a reflex corner
      int t = 0;
      for (; t < n; ++t) {
        const vec2& q = v2[std::size_t(t)];
        if (q != p1 && q != p2 && q != p0 && pointInTriangle2d(p0, p1, p2, q)) break;
      }
      if (t != n) continue;
      break;
    }
    if (found == 2) {
      log::debug("mesh import: polygon with no ear left (not simple); Assimp keeps the triangles cut so far");
      num = 0;
      break;
    }
    out.insert(out.end(), {std::uint32_t(prev), std::uint32_t(ear), std::uint32_t(next)});
    done[std::size_t(ear)] = 1;
    --num;
  }
  if (num > 0) {
    int t = 0;
    for (; done[std::size_t(t)]; ++t) {
    }
    const int a = t;
    for (++t; done[std::size_t(t)]; ++t) {
    }
    const int b = t;
    for (++t; done[std::size_t(t)]; ++t) {
    }
    out.insert(out.end(), {std::uint32_t(a), std::uint32_t(b), std::uint32_t(t)});
  }
  for (std::size_t i = firstOut; i < out.size(); ++i) out[i] += start;
}

/// Hash of a position's values (not bits: +0 and -0 compare equal, so they hash equal).
std::size_t positionHash(const vec3& p) {
  const vec3 canonical = p + vec3(0.0f);  // -0 → +0
  return std::size_t(Fnv1a().add(canonical).value());
}

float squareDistance(const vec3& a, const vec3& b) {
  const vec3 d = a - b;
  return d.x * d.x + d.y * d.y + d.z * d.z;
}

}  // namespace

MappedFile::MappedFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(ErrorKind::Input, "cannot read '{}': {}", path.string(), std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    fail(ErrorKind::Input, "cannot read '{}': {}", path.string(), std::strerror(errno));
  }
  m_size = std::size_t(st.st_size);
  if (m_size > 0) {
    void* data = ::mmap(nullptr, m_size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (data == MAP_FAILED) {
      ::close(fd);
      fail(ErrorKind::Input, "cannot read '{}': {}", path.string(), std::strerror(errno));
    }
    m_data = static_cast<const char*>(data);
  }
  ::close(fd);
}

MappedFile::~MappedFile() {
  if (m_data) ::munmap(const_cast<char*>(m_data), m_size);
}

void triangulate(const PolyMesh& mesh, std::size_t first, std::size_t last, std::vector<std::uint32_t>& out,
                 std::vector<std::uint32_t>* perFace) {
  for (std::size_t f = first; f < last; ++f) {
    const std::size_t before = out.size();
    const std::uint32_t s = mesh.faceStart[f];
    const int n = int(mesh.faceStart[f + 1] - s);
    if (n == 3) {
      out.insert(out.end(), {s, s + 1, s + 2});
    } else if (n == 4) {
      // A quad has at most one concave corner; Assimp fans from it (else from corner 0).
      const auto p = [&](unsigned i) { return mesh.positions[mesh.corners[s + (i % 4)]]; };
      unsigned startCorner = 0;
      for (unsigned i = 0; i < 4; ++i) {
        const vec3 v = p(i);
        const vec3 left = assimpNormalize(p(i + 3) - v), diag = assimpNormalize(p(i + 2) - v),
                   right = assimpNormalize(p(i + 1) - v);
        const float angle = std::acos(dot3(left, diag)) + std::acos(dot3(right, diag));
        if (angle > kPi) {
          startCorner = i;
          break;
        }
      }
      const auto c = [&](unsigned i) { return s + (startCorner + i) % 4; };
      out.insert(out.end(), {c(0), c(1), c(2), c(0), c(2), c(3)});
    } else if (n > 4) {
      earCut(mesh, s, n, out);
    }
    // Faces of 1–2 corners are points and lines: the fast paths decline files with them.
    if (perFace) perFace->push_back(std::uint32_t((out.size() - before) / 3));
  }
}

void encodeNgons(std::vector<std::uint32_t>& triangles, const std::vector<std::uint32_t>& perFace,
                 const std::vector<std::uint32_t>& faceSize) {
  std::uint32_t last = 0xFFFFFFFFu;
  std::size_t t = 0;
  for (std::size_t f = 0; f < perFace.size(); ++f) {
    std::uint32_t* tri = triangles.data() + 3 * t;
    if (faceSize[f] == 4 && perFace[f] == 2) {
      if (tri[0] == last) {
        // (a b c) → (c a b) and (a c d) → (c d a): both still start alike.
        std::swap(tri[0], tri[2]);
        std::swap(tri[1], tri[2]);
        std::swap(tri[4], tri[5]);
        std::swap(tri[3], tri[5]);
      }
      last = tri[0];
    } else {
      for (std::uint32_t k = 0; k < perFace[f]; ++k, tri += 3) {
        if (tri[0] == last) {
          std::swap(tri[0], tri[2]);
          std::swap(tri[1], tri[2]);
        }
        last = tri[0];
      }
    }
    t += perFace[f];
  }
}

void expandPerCorner(PolyMesh& mesh) {
  PolyMesh out;
  const std::size_t n = mesh.corners.size();
  resizePositions(out.positions, n);
  if (!mesh.uvs.empty()) out.uvs.resize(n);
  if (!mesh.normals.empty()) out.normals.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t v = mesh.corners[i];
    out.positions[i] = mesh.positions[v];
    if (!out.uvs.empty()) out.uvs[i] = mesh.uvs[v];
    if (!out.normals.empty()) out.normals[i] = mesh.normals[v];
  }
  out.corners.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.corners[i] = std::uint32_t(i);
  out.faceStart = std::move(mesh.faceStart);
  out.perCorner = true;
  mesh = std::move(out);
}

namespace {

/// Each triangle's unit normal on its three vertices (a later triangle's wins); NaN on a
/// vertex that no triangle uses.
std::vector<vec3> faceNormals(const std::vector<vec3>& positions, const std::vector<std::uint32_t>& triangles) {
  const std::size_t n = positions.size();
  const float qnan = std::numeric_limits<float>::quiet_NaN();
  std::vector<vec3> faceNormal(n, vec3(qnan));
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const vec3 &a = positions[triangles[t]], &b = positions[triangles[t + 1]], &c = positions[triangles[t + 2]];
    const vec3 e1 = b - a, e2 = c - a;
    vec3 normal(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    const float length = std::sqrt(dot3(normal, normal));
    if (length > 0.0f) normal *= 1.0f / length;
    for (int k = 0; k < 3; ++k) faceNormal[triangles[t + std::size_t(k)]] = normal;
  }
  return faceNormal;
}

/// Finds the vertices at one position: positions within ε = 1e-4 · bounding-box diagonal
/// (Assimp's ComputePositionEpsilon) are one, and a grid of ε cells finds them in the 27
/// cells around a vertex.
class PositionGrid {
public:
  explicit PositionGrid(const std::vector<vec3>& positions) : m_positions(positions) {
    measure();
    sortByCell();
    buildRuns();
  }

  /// Appends the vertices within ε of vertex i to `found`, cell by cell.
  void near(std::size_t i, std::vector<std::uint32_t>& found) const {
    const vec3 p = m_positions[i];
    const glm::i64vec3 c = cellOf(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const glm::i64vec3 neighbour = c + glm::i64vec3(dx, dy, dz);
          const Run* run = runOf(key(neighbour));
          for (std::uint32_t k = run ? run->begin : 0; run && k != run->end; ++k) {
            const std::uint32_t j = m_entries[k].index;
            const vec3 d = m_positions[j] - p;
            if (cellOf(m_positions[j]) == neighbour && dot3(d, d) < m_squareEpsilon) found.push_back(j);
          }
        }
  }

private:
  struct Entry {
    std::uint64_t key;
    std::uint32_t index;
  };
  struct Run {
    std::uint64_t key = 0;
    std::uint32_t begin = 0, end = 0;  // end == begin: an empty slot
  };

  /// The bounding box's low corner, ε and the cell size.
  void measure() {
    const std::size_t n = m_positions.size();
    vec3 hi(-std::numeric_limits<float>::max());
    for (const vec3& p : m_positions) {
      m_lo = glm::min(m_lo, p);
      hi = glm::max(hi, p);
    }
    const float epsilon = n == 0 ? 0.0f : std::sqrt(dot3(hi - m_lo, hi - m_lo)) * 1e-4f;
    m_squareEpsilon = epsilon * epsilon;
    // Cells in double: a box wider than float's range makes ε infinite, and a float cell
    // index could then be NaN or past 2⁶³ (undefined to convert; found by fuzz/mesh.cpp).
    const glm::dvec3 extent = glm::dvec3(hi) - glm::dvec3(m_lo);
    const double diagonal = std::sqrt(glm::dot(extent, extent));
    m_cell = epsilon > 0.0f && std::isfinite(epsilon) ? double(epsilon)
             : diagonal > 0.0 && std::isfinite(diagonal) ? diagonal * 1e-4 : 1.0;
  }

  glm::i64vec3 cellOf(const vec3& p) const {
    return glm::i64vec3(std::floor((double(p.x) - double(m_lo.x)) / m_cell),
                        std::floor((double(p.y) - double(m_lo.y)) / m_cell),
                        std::floor((double(p.z) - double(m_lo.z)) / m_cell));
  }
  static std::uint64_t key(const glm::i64vec3& c) {
    return hashKey(std::uint64_t(c.x), std::uint64_t(c.y), std::uint64_t(c.z));
  }

  // The grid as a flat table: the vertices sorted by cell key (in parallel), and an
  // open-addressing table from a key to its run of vertices. (A hash multimap of one node
  // per vertex spent 3/4 of a small bake of a 262k-triangle OBJ chasing its bucket lists.)

  /// Sorts the vertices by cell key, then index.
  void sortByCell() {
    const std::size_t n = m_positions.size();
    m_entries.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) m_entries[i] = {key(cellOf(m_positions[i])), std::uint32_t(i)};
    });
    tbb::parallel_sort(m_entries.begin(), m_entries.end(), [](const Entry& a, const Entry& b) {
      return a.key < b.key || (a.key == b.key && a.index < b.index);
    });
  }

  /// Fills the open-addressing table with each key's run of sorted vertices.
  void buildRuns() {
    const std::size_t n = m_positions.size();
    while (m_capacity < 2 * n) m_capacity *= 2;
    m_runs.resize(m_capacity);
    for (std::size_t i = 0; i < n;) {
      std::size_t j = i + 1;
      while (j < n && m_entries[j].key == m_entries[i].key) ++j;
      std::size_t slot = slotOf(m_entries[i].key);
      while (m_runs[slot].end != m_runs[slot].begin) slot = (slot + 1) & (m_capacity - 1);
      m_runs[slot] = {m_entries[i].key, std::uint32_t(i), std::uint32_t(j)};
      i = j;
    }
  }

  std::size_t slotOf(std::uint64_t k) const { return std::size_t(k * 0x9E3779B97F4A7C15ull >> 20) & (m_capacity - 1); }
  const Run* runOf(std::uint64_t k) const {
    for (std::size_t slot = slotOf(k);; slot = (slot + 1) & (m_capacity - 1)) {
      const Run& run = m_runs[slot];
      if (run.end == run.begin) return nullptr;
      if (run.key == k) return &run;
    }
  }

  const std::vector<vec3>& m_positions;
  vec3 m_lo{std::numeric_limits<float>::max()};
  float m_squareEpsilon = 0.0f;
  double m_cell = 1.0;
  std::vector<Entry> m_entries;
  std::size_t m_capacity = 16;
  std::vector<Run> m_runs;
};

}  // namespace

std::vector<vec3> smoothNormals(const std::vector<vec3>& positions, const std::vector<std::uint32_t>& triangles) {
  const std::size_t n = positions.size();
  const std::vector<vec3> faceNormal = faceNormals(positions, triangles);
  const PositionGrid grid(positions);

  std::vector<vec3> result(n, vec3(0.0f));
  std::vector<char> had(n, 0);
  std::vector<std::uint32_t> found;
  for (std::size_t i = 0; i < n; ++i) {
    if (had[i]) continue;
    found.clear();
    grid.near(i, found);
    vec3 sum(0.0f);
    for (std::uint32_t j : found) {
      if (!std::isnan(faceNormal[j].x)) sum += faceNormal[j];
    }
    const float length = std::sqrt(dot3(sum, sum));
    if (length > 0.0f) sum *= 1.0f / length;
    for (std::uint32_t j : found) {
      result[j] = sum;
      had[j] = 1;
    }
  }
  return result;
}

void joinVertices(Mesh& mesh) {
  // Assimp's rule: vertices at exactly the same position are one when their normals and
  // uvs differ by at most 1e-5; a vertex joins the most recent earlier representative it
  // is that close to (Assimp's hash map finds that one first), else becomes one itself.
  // Positions are grouped in parallel in a lock-free open-addressing table whose slot
  // keeps the position's first vertex; representatives are then chosen in vertex order.
  const std::size_t n = mesh.positions.size();
  const bool hasNormals = mesh.hasNormals(), hasUvs = mesh.hasUvs();
  std::vector<std::atomic<std::uint8_t>> used(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.indices.size(), 1 << 16), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) used[mesh.indices[k]].store(1, std::memory_order_relaxed);
  });
  std::size_t capacity = 16;
  while (capacity < 2 * n) capacity *= 2;
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::vector<std::atomic<std::uint32_t>> table(capacity);
  for (auto& slot : table) slot.store(kNone, std::memory_order_relaxed);
  std::vector<std::uint32_t> slotOf(n, kNone);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (!used[i].load(std::memory_order_relaxed)) continue;
      const vec3& p = mesh.positions[i];
      for (std::size_t s = positionHash(p) & (capacity - 1);; s = (s + 1) & (capacity - 1)) {
        std::uint32_t held = table[s].load(std::memory_order_acquire);
        if (held == kNone) {
          if (table[s].compare_exchange_strong(held, std::uint32_t(i), std::memory_order_acq_rel)) {
            slotOf[i] = std::uint32_t(s);
            break;
          }
          // Lost the race: `held` is the winner now; compare with it.
        }
        if (mesh.positions[held] == p) {
          slotOf[i] = std::uint32_t(s);
          break;
        }
      }
    }
  });
  constexpr float kSquareEpsilon = 1e-5f * 1e-5f;
  // Per position (slot): its newest representative; per representative: the one before.
  std::vector<std::uint32_t> replace(n, 0), latest(capacity, kNone), previous(n, kNone);
  Mesh out;
  out.positions.reserve(n + 1);  // see resizePositions
  for (std::size_t i = 0; i < n; ++i) {
    if (slotOf[i] == kNone) continue;
    std::uint32_t& newest = latest[slotOf[i]];
    std::uint32_t rep = newest;
    for (; rep != kNone; rep = previous[rep]) {
      if ((!hasNormals || squareDistance(mesh.normals[rep], mesh.normals[i]) <= kSquareEpsilon) &&
          (!hasUvs || squareDistance(vec3(mesh.uvs[rep], 0.0f), vec3(mesh.uvs[i], 0.0f)) <= kSquareEpsilon)) {
        break;
      }
    }
    if (rep != kNone) {
      replace[i] = replace[rep];
      continue;
    }
    previous[i] = newest;
    newest = std::uint32_t(i);
    replace[i] = std::uint32_t(out.positions.size());
    out.positions.push_back(mesh.positions[i]);
    if (hasNormals) out.normals.push_back(mesh.normals[i]);
    if (hasUvs) out.uvs.push_back(mesh.uvs[i]);
  }
  out.indices = std::move(mesh.indices);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.indices.size(), 1 << 16), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) out.indices[k] = replace[out.indices[k]];
  });
  mesh = std::move(out);
}

Mesh finishPart(PolyMesh&& part, bool join, bool generateNormals, bool& generatedNormals) {
  generatedNormals = generateNormals && part.normals.empty();
  if (generatedNormals && !part.perCorner) expandPerCorner(part);

  // Triangulate in parallel blocks of faces, then concatenate in order.
  const std::size_t faces = part.faceStart.size() - 1;
  constexpr std::size_t kBlock = 1 << 16;
  const std::size_t blocks = (faces + kBlock - 1) / kBlock;
  bool polygons = false;
  for (std::size_t f = 0; f < faces && !polygons; ++f) polygons = part.faceStart[f + 1] - part.faceStart[f] > 3;
  std::vector<std::vector<std::uint32_t>> pieces(blocks), perFace(polygons ? blocks : 0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    pieces[b].reserve(kBlock * 3);
    triangulate(part, b * kBlock, std::min(faces, (b + 1) * kBlock), pieces[b], polygons ? &perFace[b] : nullptr);
  });
  Mesh mesh;
  std::size_t total = 0;
  for (const auto& piece : pieces) total += piece.size();
  mesh.indices.resize(total);
  {
    std::vector<std::size_t> offsets(blocks + 1, 0);
    for (std::size_t b = 0; b < blocks; ++b) offsets[b + 1] = offsets[b] + pieces[b].size();
    // Corner positions → vertex indices on the way.
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
      std::uint32_t* dst = mesh.indices.data() + offsets[b];
      for (std::uint32_t c : pieces[b]) *dst++ = part.corners[c];
    });
  }
  if (polygons) {
    // Assimp's NGON encoding, sequential by nature: a triangle starting at the vertex the
    // previous one started at is rotated, so one polygon's triangles can be told apart.
    std::vector<std::uint32_t> counts, sizes(faces);
    counts.reserve(faces);
    for (const auto& piece : perFace) counts.insert(counts.end(), piece.begin(), piece.end());
    for (std::size_t f = 0; f < faces; ++f) sizes[f] = part.faceStart[f + 1] - part.faceStart[f];
    encodeNgons(mesh.indices, counts, sizes);
  }
  mesh.positions = std::move(part.positions);
  mesh.uvs = std::move(part.uvs);
  // Assimp joins before glint normalizes (the identity node transform in loadMesh's
  // Mesh::transform), so joining compares the normals as read or generated.
  mesh.normals = generatedNormals ? smoothNormals(mesh.positions, mesh.indices) : std::move(part.normals);
  if (join) joinVertices(mesh);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.normals.size(), 1 << 16),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        vec3& n = mesh.normals[i];
                        const float length = glm::length(n);
                        n = length > 0.0f ? n / length : n;
                      }
                    });
  return mesh;
}

void warnMissingNormals(const std::string& name, unsigned missing, unsigned meshes) {
  if (missing > 0) log::warn("'{}': {} of {} meshes have no normals; generating smooth normals", name, missing, meshes);
}

}  // namespace glint::detail

namespace glint {

void generateSmoothNormals(Mesh& mesh) {
  // One vertex per corner, as the file readers make them before Assimp's rule runs; every
  // corner of a vertex then has the same sum, which the vertex takes.
  const std::size_t corners = mesh.indices.size();
  std::vector<vec3> expanded(corners);
  std::vector<std::uint32_t> identity(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    expanded[c] = mesh.positions[mesh.indices[c]];
    identity[c] = std::uint32_t(c);
  }
  const std::vector<vec3> sums = detail::smoothNormals(expanded, identity);
  mesh.normals.assign(mesh.positions.size(), vec3(0.0f));
  for (std::size_t c = 0; c < corners; ++c) {
    const vec3& n = sums[c];
    const float length = glm::length(n);
    mesh.normals[mesh.indices[c]] = length > 0.0f ? n / length : n;
  }
}

}  // namespace glint
