// The fast OBJ path: tinyobjloader's callback parser on several threads at once, with a
// fast lane for the common vertex and face lines (FastLane below).
//
// The file is memory-mapped and cut at line starts into chunks. A first parallel pass
// counts each chunk's `v`, `vt` and `vn` lines, so every chunk knows where its vertices
// go in the file-wide arrays and which vertex a relative (negative) index means before it
// is parsed. Then the chunks are parsed in parallel, each line by the fast lane or, when it
// declines, by tinyobjloader (LoadObjWithCallback on a stream over a run of such lines):
// vertex records are written straight into the arrays,
// faces keep their raw indices resolved to absolute ones, and `o`/`g`/`usemtl` are kept
// as events. The events are then replayed in order with Assimp's rules for where a new
// aiMesh starts (import_steps.h), so normals are generated and vertices joined per part
// exactly as the Assimp path does.
#include "import_steps.h"

#include "glint/core/error.h"
#include "glint/core/log.h"

#include <tiny_obj_loader.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <span>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <istream>
#include <set>
#include <streambuf>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint::detail {
namespace {

/// An input stream buffer over memory, which tells where reading has got to.
class MemoryBuffer : public std::streambuf {
public:
  MemoryBuffer(const char* begin, const char* end) {
    char* b = const_cast<char*>(begin);  // never written: std::streambuf is not const-correct
    setg(b, b, const_cast<char*>(end));
  }
  const char* position() const { return gptr(); }
};

/// The kinds of line tinyobjloader reports a vertex record for: `v`, `vt`, `vn` after
/// optional blanks, followed by a blank — counted exactly as it recognizes them. Faces
/// (`f`) are counted too, only to size the chunk's corner lists.
enum class Record { Other, Position, TexCoord, Normal, Face };

Record classify(const char* p, const char* end) {
  while (p < end && (*p == ' ' || *p == '\t')) ++p;
  const auto blank = [&](const char* q) { return q < end && (*q == ' ' || *q == '\t'); };
  if (p < end && *p == 'f' && blank(p + 1)) return Record::Face;
  if (p >= end || *p != 'v') return Record::Other;
  if (blank(p + 1)) return Record::Position;
  if (p + 1 < end && p[1] == 't' && blank(p + 2)) return Record::TexCoord;
  if (p + 1 < end && p[1] == 'n' && blank(p + 2)) return Record::Normal;
  return Record::Other;
}

/// A statement that starts a new aiMesh in Assimp's OBJ reader, before face `face` of its chunk.
struct Event {
  enum class Kind { Object, Group, Material } kind;
  std::size_t face;
  std::string name;
};

constexpr std::uint32_t kAbsent = 0xFFFFFFFFu;

struct Chunk {
  const char* begin = nullptr;
  const char* end = nullptr;
  std::size_t positions = 0, texCoords = 0, normals = 0;      // records in this chunk
  std::size_t faces = 0;                                      // `f` lines in this chunk
  bool anyCr = false;                                         // a CR anywhere in the chunk
  std::size_t firstPosition = 0, firstTexCoord = 0, firstNormal = 0;  // file-wide offsets
  // Faces: corner c of the chunk has vertex v[c], uv t[c], normal n[c] (absolute, kAbsent if none).
  std::vector<std::uint32_t> v, t, n;
  std::vector<std::uint32_t> faceSize;
  std::vector<std::uint8_t> faceFlags;  // bit 0: corners have uvs, bit 1: normals
  std::vector<Event> events;
  std::string error;     // first Error(Input) reason found in this chunk
  std::string declined;  // first reason to let Assimp read the file
};

/// What a parsing thread needs in tinyobjloader's callbacks.
struct ParseState {
  Chunk* chunk;
  const MemoryBuffer* buffer;  // over the run of lines tinyobjloader is reading
  const char* runBegin;        // where that run starts
  std::vector<vec3>* positions;
  std::vector<vec2>* texCoords;
  std::vector<vec3>* normals;
  std::size_t totalPositions, totalTexCoords, totalNormals;
  std::size_t localPositions = 0, localTexCoords = 0, localNormals = 0;
  bool strict = false;  // the numbers come from the fast lane: whole and finite
};

/// The line tinyobjloader has just consumed (without its line break).
std::string_view lastLine(const ParseState& s) {
  const char* b = s.runBegin;
  const char* e = s.buffer->position();
  if (e > b && e[-1] == '\n') --e;
  if (e > b && e[-1] == '\r') --e;
  const char* p = e;
  while (p > b && p[-1] != '\n' && p[-1] != '\r') --p;
  return {p, std::size_t(e - p)};
}

/// The numbers after a record's keyword, strictly: tinyobjloader reads what it cannot parse
/// ("nan", "1e", "abc") as 0, so a record with a 0 in it is read again here.
/// Returns false when a field is not a finite number.
bool strictNumbers(std::string_view line, std::vector<float>& out, std::string& bad) {
  out.clear();
  std::size_t i = line.find_first_not_of(" \t");
  i = line.find_first_of(" \t", i);  // skip the keyword
  while (i != std::string_view::npos) {
    i = line.find_first_not_of(" \t", i);
    if (i == std::string_view::npos) break;
    const std::size_t end = std::min(line.find_first_of(" \t", i), line.size());
    std::string_view field = line.substr(i, end - i);
    if (field.front() == '#') break;
    std::string_view digits = field;
    if (digits.size() > 1 && digits.front() == '+') digits.remove_prefix(1);
    float value = 0.0f;
    const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc() || ptr != digits.data() + digits.size() || !std::isfinite(value)) {
      bad = std::string(field);
      return false;
    }
    out.push_back(value);
    i = end;
  }
  return true;
}

void onPosition(void* user, float x, float y, float z, float w) {
  auto& s = *static_cast<ParseState*>(user);
  const std::size_t index = s.chunk->firstPosition + s.localPositions++;
  if (s.localPositions > s.chunk->positions) {
    if (s.chunk->declined.empty()) s.chunk->declined = "vertex records counted differently";
    return;
  }
  if (!s.strict && (x == 0.0f || y == 0.0f || z == 0.0f || w != 1.0f)) {
    // Either a real 0, a field tinyobjloader could not read, or a 4th number: a
    // homogeneous w (Assimp divides by it) or the red of a vertex colour (ignored).
    std::vector<float> numbers;
    std::string bad;
    if (!strictNumbers(lastLine(s), numbers, bad)) {
      if (s.chunk->error.empty()) s.chunk->error = fmt::format("position {} is not finite ('{}')", index, bad);
      return;
    }
    if (numbers.size() == 4) {
      if (numbers[3] == 0.0f) {
        if (s.chunk->error.empty()) s.chunk->error = fmt::format("position {} has a homogeneous w of 0", index);
        return;
      }
      x = numbers[0] / numbers[3];
      y = numbers[1] / numbers[3];
      z = numbers[2] / numbers[3];
    } else if (numbers.size() != 3 && numbers.size() != 6) {
      // Assimp skips such a record (and so shifts every later index): let it.
      if (s.chunk->declined.empty()) s.chunk->declined = fmt::format("vertex record with {} numbers", numbers.size());
      return;
    }
  }
  (*s.positions)[index] = vec3(x, y, z);
}

void onTexCoord(void* user, float u, float v, float) {
  auto& s = *static_cast<ParseState*>(user);
  const std::size_t index = s.chunk->firstTexCoord + s.localTexCoords++;
  if (s.localTexCoords > s.chunk->texCoords) {
    if (s.chunk->declined.empty()) s.chunk->declined = "texture coordinates counted differently";
    return;
  }
  if (!s.strict && (u == 0.0f || v == 0.0f)) {
    std::vector<float> numbers;
    std::string bad;
    if (!strictNumbers(lastLine(s), numbers, bad) || numbers.size() < 2 || numbers.size() > 3) {
      if (s.chunk->declined.empty()) s.chunk->declined = "a texture coordinate that is not 2 or 3 finite numbers";
      return;
    }
  }
  (*s.texCoords)[index] = vec2(u, v);
}

void onNormal(void* user, float x, float y, float z) {
  auto& s = *static_cast<ParseState*>(user);
  const std::size_t index = s.chunk->firstNormal + s.localNormals++;
  if (s.localNormals > s.chunk->normals) {
    if (s.chunk->declined.empty()) s.chunk->declined = "normals counted differently";
    return;
  }
  if (!s.strict && (x == 0.0f || y == 0.0f || z == 0.0f)) {
    std::vector<float> numbers;
    std::string bad;
    if (!strictNumbers(lastLine(s), numbers, bad) || numbers.size() < 3) {
      if (s.chunk->declined.empty()) s.chunk->declined = "a normal that is not 3 finite numbers";
      return;
    }
  }
  (*s.normals)[index] = vec3(x, y, z);
}

void onFace(void* user, tinyobj::index_t* indices, int count) {
  auto& s = *static_cast<ParseState*>(user);
  Chunk& c = *s.chunk;
  if (count < 3) {
    // Assimp keeps it as a point or line, which then splits the mesh's vertices.
    if (c.declined.empty()) c.declined = "a face with fewer than 3 corners";
    return;
  }
  // OBJ indices are 1-based; negative ones count back from the latest record.
  const auto resolve = [](int raw, std::size_t before, std::size_t total, std::uint32_t& out) {
    if (raw > 0) {
      out = std::uint32_t(raw - 1);
      return std::size_t(raw - 1) < total;
    }
    const long long absolute = (long long)before + raw;
    out = absolute >= 0 ? std::uint32_t(absolute) : kAbsent;
    return absolute >= 0;
  };
  int withUv = 0, withNormal = 0;
  for (int k = 0; k < count; ++k) {
    const tinyobj::index_t& i = indices[k];
    std::uint32_t v = 0, t = kAbsent, n = kAbsent;
    if (i.vertex_index == 0) {
      if (c.error.empty()) c.error = "a face has a vertex index that is 0 or not a number";
      return;
    }
    if (!resolve(i.vertex_index, c.firstPosition + s.localPositions, s.totalPositions, v)) {
      if (c.error.empty()) {
        c.error = fmt::format("a face refers to vertex {} of {}", i.vertex_index, s.totalPositions);
      }
      return;
    }
    if (i.texcoord_index != 0) {
      ++withUv;
      if (!resolve(i.texcoord_index, c.firstTexCoord + s.localTexCoords, s.totalTexCoords, t) && c.declined.empty()) {
        c.declined = "a texture coordinate index out of range";  // Assimp drops the mesh's uvs
      }
    }
    if (i.normal_index != 0) {
      ++withNormal;
      if (!resolve(i.normal_index, c.firstNormal + s.localNormals, s.totalNormals, n) && c.declined.empty()) {
        c.declined = "a normal index out of range";  // Assimp drops the mesh's normals
      }
    }
    c.v.push_back(v);
    c.t.push_back(t);
    c.n.push_back(n);
  }
  if ((withUv != 0 && withUv != count) || (withNormal != 0 && withNormal != count)) {
    if (c.declined.empty()) c.declined = "a face with uvs or normals on some corners only";
  }
  c.faceSize.push_back(std::uint32_t(count));
  c.faceFlags.push_back(std::uint8_t((withUv ? 1 : 0) | (withNormal ? 2 : 0)));
}

std::string trimmed(std::string_view s) {
  const std::size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  const std::size_t e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

void onObject(void* user, const char* name) {
  auto& s = *static_cast<ParseState*>(user);
  std::string first = trimmed(name);
  first = first.substr(0, first.find_first_of(" \t"));  // Assimp names an object by its first word
  s.chunk->events.push_back({Event::Kind::Object, s.chunk->faceSize.size(), first});
}

void onGroup(void* user, const char** names, int count) {
  auto& s = *static_cast<ParseState*>(user);
  std::string joined;
  for (int i = 0; i < count; ++i) joined += (i ? " " : "") + std::string(names[i]);
  s.chunk->events.push_back({Event::Kind::Group, s.chunk->faceSize.size(), trimmed(joined)});
}

void onMaterial(void* user, const char* name, int) {
  auto& s = *static_cast<ParseState*>(user);
  s.chunk->events.push_back({Event::Kind::Material, s.chunk->faceSize.size(), trimmed(name)});
}

/// The common lines, read without tinyobjloader: `v x y z`, `vn x y z`, `vt u v [w]` and
/// `f` with corners `a`, `a/b`, `a//c` or `a/b/c`, keyword first, fields apart by blanks,
/// every number whole and finite (std::from_chars: correctly rounded, and no per-line
/// string or stream). tinyobjloader reads 92 MB/s per thread here, most of it in strtoll,
/// pow and istream line copies; this lane reads such lines about 4× faster. Any other
/// line, or one of these written in any other way (a leading blank, a '+', a comment, a
/// 4th coordinate, an index 0), is left to tinyobjloader, so the grammar stays its own;
/// fuzz/mesh.cpp checks that both readings of every input agree.
class FastLane {
public:
  /// Reads line [p, e) (without its line break) into this lane's buffers; false leaves it to tinyobjloader.
  bool read(const char* p, const char* e) {
    if (e - p < 2) return false;
    if (p[0] == 'f' && blank(p[1])) return face(p + 2, e);
    if (p[0] != 'v') return false;
    if (blank(p[1])) return numbers(p + 2, e, 3, 3, Record::Position);
    if (e - p < 3 || !blank(p[2])) return false;
    if (p[1] == 'n') return numbers(p + 3, e, 3, 3, Record::Normal);
    if (p[1] == 't') return numbers(p + 3, e, 2, 3, Record::TexCoord);
    return false;
  }
  /// Hands what read() found to the callbacks tinyobjloader would have called.
  void deliver(ParseState& state) {
    state.strict = true;
    switch (m_record) {
      case Record::Position: onPosition(&state, m_values[0], m_values[1], m_values[2], 1.0f); break;
      case Record::Normal: onNormal(&state, m_values[0], m_values[1], m_values[2]); break;
      case Record::TexCoord: onTexCoord(&state, m_values[0], m_values[1], m_values[2]); break;
      case Record::Face: onFace(&state, m_corners.data(), int(m_corners.size())); break;
      case Record::Other: break;
    }
    state.strict = false;
  }

private:
  static bool blank(char c) { return c == ' ' || c == '\t'; }
  static const char* skipBlanks(const char* p, const char* e) {
    while (p < e && blank(*p)) ++p;
    return p;
  }
  bool numbers(const char* p, const char* e, int least, int most, Record record) {
    int n = 0;
    for (p = skipBlanks(p, e); p < e; p = skipBlanks(p, e)) {
      if (n == most) return false;
      float value = 0.0f;
      const auto [end, ec] = std::from_chars(p, e, value);
      if (ec != std::errc() || (end < e && !blank(*end)) || !std::isfinite(value)) return false;
      m_values[n++] = value;
      p = end;
    }
    if (n < least) return false;
    if (n == 2) m_values[2] = 0.0f;
    m_record = record;
    return true;
  }
  /// One index: a nonzero integer (negative counts back), ending at '/', a blank or the line's end.
  static bool index(const char*& p, const char* e, int& out) {
    const auto [end, ec] = std::from_chars(p, e, out);
    if (ec != std::errc() || out == 0 || (end < e && *end != '/' && !blank(*end))) return false;
    p = end;
    return true;
  }
  bool face(const char* p, const char* e) {
    m_corners.clear();
    for (p = skipBlanks(p, e); p < e; p = skipBlanks(p, e)) {
      tinyobj::index_t corner{0, 0, 0};
      if (!index(p, e, corner.vertex_index)) return false;
      if (p < e && *p == '/') {
        ++p;
        if (p < e && *p != '/' && !index(p, e, corner.texcoord_index)) return false;
        if (p < e && *p == '/') {
          ++p;
          if (!index(p, e, corner.normal_index)) return false;
        }
      }
      if (p < e && !blank(*p)) return false;
      m_corners.push_back(corner);
    }
    if (m_corners.empty()) return false;
    m_record = Record::Face;
    return true;
  }

  Record m_record = Record::Other;
  float m_values[3] = {};
  std::vector<tinyobj::index_t> m_corners;
};

/// Face ranges of the aiMeshes Assimp's OBJ reader makes (ObjFileParser: a mesh per
/// object, per group change, and per material change in a mesh that has faces).
class PartBuilder {
public:
  explicit PartBuilder(std::vector<std::pair<std::size_t, std::size_t>>& parts) : m_parts(parts) {}

  void event(const Event& e) {
    switch (e.kind) {
      case Event::Kind::Object:
        if (e.name.empty()) return;
        if (m_objectNames.count(e.name)) throw Declined("an object name used twice");
        createObject(e.name);
        return;
      case Event::Kind::Group:
        if (e.name.empty() || e.name == m_activeGroup) return;
        createObject(e.name);
        m_activeGroup = e.name;
        return;
      case Event::Kind::Material:
        if (e.name.empty() || (m_hasMaterial && m_material == e.name)) return;
        m_hasMaterial = true;
        m_material = e.name;
        if (!m_hasMesh) {
          m_hasMesh = true;  // a mesh no object owns: no face ever goes there
          m_meshOrphan = true;
          m_meshHasMaterial = false;
        } else if (m_meshHasMaterial && m_meshMaterial != e.name && m_meshFaces > 0) {
          createMesh();
        }
        m_meshHasMaterial = true;
        m_meshMaterial = e.name;
        return;
    }
  }

  void face(std::size_t index) {
    if (!m_hasObject || m_meshOrphan) createObject("defaultobject");
    if (m_meshFaces == 0) m_parts.emplace_back(index, index);  // the mesh's first face
    m_parts.back().second = index + 1;
    ++m_meshFaces;
  }

private:
  void createObject(const std::string& name) {
    m_objectNames.insert(name);
    m_hasObject = true;
    createMesh();
    if (m_hasMaterial) {
      m_meshHasMaterial = true;
      m_meshMaterial = m_material;
    }
  }
  void createMesh() {
    m_hasMesh = true;
    m_meshOrphan = false;
    m_meshFaces = 0;
    m_meshHasMaterial = false;
  }

  std::vector<std::pair<std::size_t, std::size_t>>& m_parts;
  std::set<std::string> m_objectNames;
  std::string m_activeGroup, m_material, m_meshMaterial;
  bool m_hasObject = false, m_hasMesh = false, m_meshOrphan = false, m_hasMaterial = false, m_meshHasMaterial = false;
  std::size_t m_meshFaces = 0;
};

/// Chunks of about 1 MiB, cut after a line feed, several per thread for balance.
std::vector<Chunk> splitIntoChunks(const char* data, const char* end) {
  const std::size_t size = std::size_t(end - data);
  const std::size_t threads = std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  const std::size_t target = std::max<std::size_t>(std::size_t(1) << 20, size / (threads * 8) + 1);
  std::vector<Chunk> chunks;
  for (const char* p = data; p < end;) {
    const char* cut = p + std::min<std::size_t>(target, std::size_t(end - p));
    if (cut < end) {
      const void* lf = std::memchr(cut, '\n', std::size_t(end - cut));
      cut = lf ? static_cast<const char*>(lf) + 1 : end;
    }
    Chunk& c = chunks.emplace_back();
    c.begin = p;
    c.end = cut;
    p = cut;
  }
  return chunks;
}

/// Pass 1 over one chunk: counts its vertex records and faces.
void countRecords(Chunk& c) {
  const auto count = [&c](const char* p, const char* lineEnd) {
    switch (classify(p, lineEnd)) {
      case Record::Position: ++c.positions; break;
      case Record::TexCoord: ++c.texCoords; break;
      case Record::Normal: ++c.normals; break;
      case Record::Face: ++c.faces; break;
      case Record::Other: break;
    }
  };
  // Lines end at LF, CR LF or a lone CR (as tinyobjloader reads them); memchr finds them.
  // Most files have no CR at all: one look over the chunk spares a search per line.
  c.anyCr = std::memchr(c.begin, '\r', std::size_t(c.end - c.begin)) != nullptr;
  for (const char* p = c.begin; p < c.end;) {
    const void* found = std::memchr(p, '\n', std::size_t(c.end - p));
    const char* lf = found ? static_cast<const char*>(found) : c.end;
    if (!c.anyCr) {
      count(p, lf);
      p = lf + 1;
      continue;
    }
    for (const char* q = p;;) {
      const void* cr = std::memchr(q, '\r', std::size_t(lf - q));
      if (!cr) {
        count(q, lf);
        break;
      }
      count(q, static_cast<const char*>(cr));
      q = static_cast<const char*>(cr) + 1;
      if (q >= lf) break;
    }
    p = lf + 1;
  }
}

/// The file's vertex records, each chunk writing its own slice (offsets from pass 1).
struct VertexTables {
  std::vector<vec3> positions, normals;
  std::vector<vec2> texCoords;
};

/// Gives each chunk its first record's index and sizes the tables.
VertexTables allocateVertexTables(std::vector<Chunk>& chunks) {
  std::size_t positions = 0, texCoords = 0, normals = 0;
  for (Chunk& c : chunks) {
    c.firstPosition = positions;
    c.firstTexCoord = texCoords;
    c.firstNormal = normals;
    positions += c.positions;
    texCoords += c.texCoords;
    normals += c.normals;
  }
  VertexTables tables;
  tables.positions.resize(positions);
  tables.texCoords.resize(texCoords);
  tables.normals.resize(normals);
  return tables;
}

/// Pass 2 over one chunk: v/vt/vn/f lines through the fast lane, every other run of lines
/// through tinyobjloader, in order. Errors and reasons to decline go into the chunk.
void parseChunk(Chunk& c, VertexTables& tables, bool fastLane) {
  tinyobj::callback_t callbacks;
  callbacks.vertex_cb = onPosition;
  callbacks.texcoord_cb = onTexCoord;
  callbacks.normal_cb = onNormal;
  callbacks.index_cb = onFace;
  callbacks.object_cb = onObject;
  callbacks.group_cb = onGroup;
  callbacks.usemtl_cb = onMaterial;
  // Room for triangles: growing by doubling would copy and touch fresh pages twice over.
  c.v.reserve(3 * c.faces);
  c.t.reserve(3 * c.faces);
  c.n.reserve(3 * c.faces);
  c.faceSize.reserve(c.faces);
  c.faceFlags.reserve(c.faces);
  ParseState state{&c,
                   nullptr,
                   nullptr,
                   &tables.positions,
                   &tables.texCoords,
                   &tables.normals,
                   tables.positions.size(),
                   tables.texCoords.size(),
                   tables.normals.size()};
  const char* run = nullptr;  // the first line of a run for tinyobjloader, if any
  const auto parseRun = [&](const char* runEnd) {
    if (!run) return;
    MemoryBuffer buffer(run, runEnd);
    std::istream stream(&buffer);
    state.buffer = &buffer;
    state.runBegin = run;
    std::string warn, err;
    if (!tinyobj::LoadObjWithCallback(stream, callbacks, &state, nullptr, &warn, &err) && c.error.empty()) {
      c.error = err.empty() ? "tinyobjloader failed" : err.substr(0, err.find('\n'));
    }
    run = nullptr;
  };
  FastLane lane;
  for (const char* p = c.begin; p < c.end;) {
    const void* found = std::memchr(p, '\n', std::size_t(c.end - p));
    const char* lf = found ? static_cast<const char*>(found) : c.end;
    const char* e = lf > p && lf[-1] == '\r' ? lf - 1 : lf;
    // A lone CR ends a line for tinyobjloader: such a line is its to split.
    const bool loneCr = c.anyCr && std::memchr(p, '\r', std::size_t(e - p)) != nullptr;
    if (fastLane && !loneCr && lane.read(p, e)) {
      parseRun(p);
      lane.deliver(state);
    } else if (!run) {
      run = p;
    }
    p = found ? lf + 1 : c.end;
  }
  parseRun(c.end);
  if ((state.localPositions != c.positions || state.localTexCoords != c.texCoords ||
       state.localNormals != c.normals) && c.declined.empty()) {
    c.declined = "vertex records counted differently";  // never seen: a guard, not a path
  }
}

/// The aiMeshes Assimp would make, as ranges [first, last) of the file's faces.
std::vector<std::pair<std::size_t, std::size_t>> assimpParts(const std::vector<Chunk>& chunks,
                                                             std::span<const std::size_t> firstFace) {
  std::vector<std::pair<std::size_t, std::size_t>> parts;
  PartBuilder builder(parts);
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    const Chunk& c = chunks[i];
    std::size_t e = 0;
    for (std::size_t f = 0; f < c.faceSize.size(); ++f) {
      for (; e < c.events.size() && c.events[e].face <= f; ++e) builder.event(c.events[e]);
      builder.face(firstFace[i] + f);
    }
    for (; e < c.events.size(); ++e) builder.event(c.events[e]);
  }
  return parts;
}

/// One vertex per corner for the whole file, in file order (what Assimp's OBJ reader
/// makes); `flags` gets each face's attribute bits.
PolyMesh gatherCorners(const std::vector<Chunk>& chunks, const VertexTables& tables, std::span<const std::size_t> firstFace,
                       std::span<const std::size_t> firstCorner, std::vector<std::uint8_t>& flags) {
  const std::size_t faceCount = firstFace.back(), cornerCount = firstCorner.back();
  PolyMesh all;
  all.perCorner = true;
  resizePositions(all.positions, cornerCount);
  all.corners.resize(cornerCount);
  all.faceStart.resize(faceCount + 1);
  flags.assign(faceCount, 0);
  const bool anyUv = !tables.texCoords.empty(), anyNormal = !tables.normals.empty();
  if (anyUv) all.uvs.resize(cornerCount);
  if (anyNormal) all.normals.resize(cornerCount);
  tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t i) {
    const Chunk& c = chunks[i];
    std::size_t corner = firstCorner[i];
    for (std::size_t f = 0; f < c.faceSize.size(); ++f) {
      all.faceStart[firstFace[i] + f] = std::uint32_t(corner);
      flags[firstFace[i] + f] = c.faceFlags[f];
      corner += c.faceSize[f];
    }
    for (std::size_t k = 0; k < c.v.size(); ++k) {
      const std::size_t out = firstCorner[i] + k;
      all.corners[out] = std::uint32_t(out);
      all.positions[out] = tables.positions[c.v[k]];
      if (anyUv) all.uvs[out] = c.t[k] != kAbsent ? tables.texCoords[c.t[k]] : vec2(0.0f);
      if (anyNormal) all.normals[out] = c.n[k] != kAbsent ? tables.normals[c.n[k]] : vec3(0.0f);
    }
  });
  all.faceStart[faceCount] = std::uint32_t(cornerCount);
  return all;
}

/// The parts triangulated and joined into one Mesh, each keeping the uvs and normals its
/// faces have (all or none: otherwise Assimp, which zero-fills the rest, reads the file).
/// `missingNormals` counts the parts whose normals were generated (none unless `generateNormals`).
Mesh finishParts(PolyMesh all, const std::vector<std::pair<std::size_t, std::size_t>>& parts,
                 std::span<const std::uint8_t> flags, bool joinVertices, bool generateNormals,
                 unsigned& missingNormals) {
  struct PartAttributes {
    bool uvs, normals;
  };
  std::vector<PartAttributes> attributes;
  for (const auto& [first, last] : parts) {
    std::uint8_t any = 0, every = 3;
    for (std::size_t f = first; f < last; ++f) {
      any |= flags[f];
      every &= flags[f];
    }
    if (any != every) throw Declined("uvs or normals on some faces of a mesh only");
    attributes.push_back({(any & 1) != 0, (any & 2) != 0});
  }
  const std::size_t faceCount = all.faceStart.size() - 1;
  Mesh result;
  bool generated = false;
  if (parts.size() == 1 && parts[0].first == 0 && parts[0].second == faceCount) {
    if (!attributes[0].uvs) all.uvs.clear();
    if (!attributes[0].normals) all.normals.clear();
    result = finishPart(std::move(all), joinVertices, generateNormals, generated);
    missingNormals += generated ? 1u : 0u;
    return result;
  }
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const auto [first, last] = parts[p];
    PolyMesh part;
    part.perCorner = true;
    const std::uint32_t c0 = all.faceStart[first], c1 = all.faceStart[last];
    part.positions.assign(all.positions.begin() + c0, all.positions.begin() + c1);
    if (attributes[p].uvs) part.uvs.assign(all.uvs.begin() + c0, all.uvs.begin() + c1);
    if (attributes[p].normals) part.normals.assign(all.normals.begin() + c0, all.normals.begin() + c1);
    part.corners.resize(c1 - c0);
    for (std::uint32_t k = 0; k < c1 - c0; ++k) part.corners[k] = k;
    part.faceStart.assign(all.faceStart.begin() + std::ptrdiff_t(first), all.faceStart.begin() + std::ptrdiff_t(last) + 1);
    for (std::uint32_t& start : part.faceStart) start -= c0;
    Mesh mesh = finishPart(std::move(part), joinVertices, generateNormals, generated);
    missingNormals += generated ? 1u : 0u;
    if (!mesh.indices.empty()) result.append(mesh);
  }
  return result;
}

}  // namespace

Mesh loadObjFast(const std::filesystem::path& path, const MeshLoadOptions& options, bool fastLane) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const auto ms = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  const std::string name = path.string();
  const MappedFile file(path);
  if (file.size() == 0) fail(ErrorKind::Input, "cannot read mesh '{}': the file is empty", name);

  std::vector<Chunk> chunks = splitIntoChunks(file.data(), file.data() + file.size());
  tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t i) { countRecords(chunks[i]); });
  VertexTables tables = allocateVertexTables(chunks);
  const auto t1 = Clock::now();

  tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t i) { parseChunk(chunks[i], tables, fastLane); });
  const auto t2 = Clock::now();
  for (const Chunk& c : chunks) {
    if (!c.error.empty()) fail(ErrorKind::Input, "cannot read mesh '{}': {}", name, c.error);
  }
  for (const Chunk& c : chunks) {
    if (!c.declined.empty()) throw Declined(c.declined);
  }

  std::vector<std::size_t> firstFace(chunks.size() + 1, 0), firstCorner(chunks.size() + 1, 0);
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    firstFace[i + 1] = firstFace[i] + chunks[i].faceSize.size();
    firstCorner[i + 1] = firstCorner[i] + chunks[i].v.size();
  }
  if (firstFace.back() == 0) fail(ErrorKind::Input, "cannot read mesh '{}': it has no triangles", name);
  const auto parts = assimpParts(chunks, firstFace);
  std::vector<std::uint8_t> flags;
  PolyMesh all = gatherCorners(chunks, tables, firstFace, firstCorner, flags);
  chunks.clear();
  tables = {};
  const auto t3 = Clock::now();

  unsigned missingNormals = 0;
  Mesh result = finishParts(std::move(all), parts, flags, options.joinVertices, options.generateNormals, missingNormals);
  warnMissingNormals(name, missingNormals, unsigned(parts.size()));
  log::debug("'{}': {:.1f} MB, {} chunks: map + count {:.0f} ms, parse {:.0f} ms, gather {:.0f} ms, finish {:.0f} ms",
             name, double(file.size()) / 1e6, firstFace.size() - 1, ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t3, Clock::now()));
  return result;
}

}  // namespace glint::detail
