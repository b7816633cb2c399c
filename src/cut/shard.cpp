// Shard files: one shard's pieces, by name, so that another process (another machine)
// can join them with the rest. Binary, native little-endian, versioned; every count is
// checked against what is left of the file before anything is allocated.
#include "glint/core/error.h"
#include "glint/core/file.h"

#include "binary.h"
#include "pieces.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

namespace glint::cut {

namespace {

constexpr char kShardMagic[8] = {'G', 'L', 'I', 'N', 'T', 'C', 'U', 'T'};
/// 2: piece positions snapped to the input's exact coordinates (exact::Geometry::snapped);
/// shards of version 1 would merge into a mesh no single run writes.
constexpr std::uint32_t kVersion = 2;

using Writer = detail::BinaryWriter;
using Reader = detail::BinaryReader;

void writeStats(Writer& w, const CutStats& s) {
  for (std::uint64_t v : {s.inputTriangles, s.receivers, s.degenerateTriangles, s.collapsedTriangles, s.candidates,
                          s.occluders, s.clippedPairs, s.cuts, s.facesBeforeMerge, s.symbolicPredicates,
                          s.filteredPredicates, s.exactPredicates})
    w.pod(v);
  w.pod(s.prepareSeconds);
  w.pod(s.cutSeconds);
  w.pod(std::uint64_t(s.lights.size()));
  for (const LightStats& l : s.lights) {
    w.string(l.name);
    w.pod(l.position);
    w.pod(l.grazingTriangles);
  }
}

CutStats readStats(Reader& r) {
  CutStats s;
  for (std::uint64_t* v : {&s.inputTriangles, &s.receivers, &s.degenerateTriangles, &s.collapsedTriangles, &s.candidates,
                           &s.occluders, &s.clippedPairs, &s.cuts, &s.facesBeforeMerge, &s.symbolicPredicates,
                           &s.filteredPredicates, &s.exactPredicates})
    *v = r.pod<std::uint64_t>();
  s.prepareSeconds = r.pod<double>();
  s.cutSeconds = r.pod<double>();
  const auto n = r.pod<std::uint64_t>();
  if (n > std::uint64_t(kMaxLights)) r.bad("truncated or corrupt");
  s.lights.resize(n);
  for (LightStats& l : s.lights) {
    l.name = r.string();
    l.position = r.pod<vec3>();
    l.grazingTriangles = r.pod<std::uint64_t>();
  }
  return s;
}

}  // namespace

void saveShard(const Shard& shard, const std::filesystem::path& path) {
  Writer w;
  for (char c : kShardMagic) w.pod(c);
  w.pod(kVersion);
  w.pod(shard.inputHash);
  w.pod(std::int32_t(shard.shardIndex));
  w.pod(std::int32_t(shard.shardCount));
  w.pod(std::uint64_t(shard.lights.size()));
  for (const Light& l : shard.lights) {
    w.pod(l.position);
    w.string(l.name);
  }
  writeStats(w, shard.stats);
  w.pod(std::uint64_t(shard.warnings.size()));
  for (const std::string& s : shard.warnings) w.string(s);
  const auto& blocks = shard.pieces->blocks;
  w.pod(std::uint64_t(blocks.size()));
  for (const PieceBlock& b : blocks) {
    w.array(b.receiver);
    w.array(b.vertexStart);
    w.array(b.vertices);
    w.array(b.positions);
    w.array(b.polygonFirst);
    w.array(b.polygonStart);
    w.array(b.corners);
    w.array(b.flags);
    w.array(b.masks);
  }
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(w.data().data(), std::streamsize(w.data().size()));
    if (!out) fail(ErrorKind::Output, "cannot write '{}'", path.string());
  });
}

Shard loadShard(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(ErrorKind::Input, "cannot read '{}'", path.string());
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Reader r(std::move(data), fmt::format("'{}' is not a usable cut shard", path.string()));
  char magic[8];
  for (char& c : magic) c = r.pod<char>();
  if (std::memcmp(magic, kShardMagic, 8) != 0) fail(ErrorKind::Input, "'{}' is not a glint cut shard", path.string());
  if (r.pod<std::uint32_t>() != kVersion) fail(ErrorKind::Input, "'{}' is a shard of another glint version", path.string());
  Shard s;
  s.inputHash = r.pod<std::uint64_t>();
  s.shardIndex = r.pod<std::int32_t>();
  s.shardCount = r.pod<std::int32_t>();
  if (s.shardCount < 1 || s.shardIndex < 0 || s.shardIndex >= s.shardCount) r.bad("truncated or corrupt");
  const auto lights = r.pod<std::uint64_t>();
  if (lights == 0 || lights > std::uint64_t(kMaxLights)) r.bad("truncated or corrupt");
  s.lights.resize(lights);
  for (Light& l : s.lights) {
    l.position = r.pod<vec3>();
    l.name = r.string();
  }
  s.stats = readStats(r);
  const auto warnings = r.pod<std::uint64_t>();
  if (warnings > 1000) r.bad("truncated or corrupt");
  for (std::uint64_t i = 0; i < warnings; ++i) s.warnings.push_back(r.string());
  s.pieces = std::make_shared<Shard::Impl>();
  const auto blocks = r.pod<std::uint64_t>();
  if (blocks > (std::uint64_t(1) << 32)) r.bad("truncated or corrupt");
  for (std::uint64_t i = 0; i < blocks; ++i) {
    PieceBlock b;
    b.receiver = r.array<std::uint32_t>();
    b.vertexStart = r.array<std::uint32_t>();
    b.vertices = r.array<exact::VertexDef>();
    b.positions = r.array<dvec3>();
    b.polygonFirst = r.array<std::uint32_t>();
    b.polygonStart = r.array<std::uint32_t>();
    b.corners = r.array<std::uint32_t>();
    b.flags = r.array<std::uint8_t>();
    b.masks = r.array<LightMask>();
    // Consistency of the offsets, so that merging never reads out of bounds.
    const std::size_t n = b.receiver.size();
    bool ok = b.vertexStart.size() == n + 1 && b.polygonFirst.size() == n + 1 && b.positions.size() == b.vertices.size() &&
              b.polygonStart.size() == b.masks.size() + 1 && b.flags.size() == b.corners.size() &&
              b.vertexStart.back() == b.vertices.size() && b.polygonFirst.back() == b.masks.size() &&
              b.polygonStart.back() == b.corners.size();
    // Every offset array non-decreasing first (then all of each lies within its last value,
    // checked above), before any is used to index (found by fuzz_cut_files).
    const auto ascending = [](const std::vector<std::uint32_t>& v) { return std::is_sorted(v.begin(), v.end()); };
    ok = ok && ascending(b.vertexStart) && ascending(b.polygonFirst) && ascending(b.polygonStart);
    for (std::size_t e = 0; ok && e < n; ++e) {
      for (std::uint32_t p = b.polygonFirst[e]; ok && p < b.polygonFirst[e + 1]; ++p) {
        ok = b.polygonStart[p] + 3 <= b.polygonStart[p + 1];
        for (std::uint32_t c = b.polygonStart[p]; ok && c < b.polygonStart[p + 1]; ++c)
          ok = b.corners[c] < b.vertexStart[e + 1] - b.vertexStart[e];
      }
    }
    if (!ok) r.bad("truncated or corrupt");
    s.pieces->blocks.push_back(std::move(b));
  }
  if (!r.atEnd()) r.bad("truncated or corrupt");
  return s;
}

}  // namespace glint::cut
