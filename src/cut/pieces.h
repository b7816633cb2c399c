#pragma once
// Receivers' pieces stored flat, block by block (a block: consecutive receivers of one
// shard, cut by one task), and what cutShard and mergeShards share.
#include "glint/cut/cutter.h"
#include "glint/mesh/adjacency.h"

#include "receiver.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace glint::cut {

using Clock = std::chrono::steady_clock;
/// Seconds since `start`, for CutStats' phases.
inline double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct PieceBlock {
  std::vector<std::uint32_t> receiver;      ///< triangle per entry
  std::vector<std::uint32_t> vertexStart;   ///< entry e: vertices[vertexStart[e] .. vertexStart[e+1])
  std::vector<exact::VertexDef> vertices;
  std::vector<dvec3> positions;
  std::vector<std::uint32_t> polygonFirst;  ///< entry e: polygons [polygonFirst[e] .. polygonFirst[e+1])
  std::vector<std::uint32_t> polygonStart;  ///< polygon p: corners[polygonStart[p] .. polygonStart[p+1])
  std::vector<std::uint32_t> corners;       ///< entry-local vertex indices
  std::vector<std::uint8_t> flags;          ///< CornerFlag bits
  std::vector<LightMask> masks;

  PieceBlock();
  void append(std::uint32_t triangle, const ReceiverPieces& pieces);
  std::size_t entries() const { return receiver.size(); }
};

struct Shard::Impl {
  std::vector<PieceBlock> blocks;
};

/// The scene prepared for cutting: welded points, triangle states, the BVH.
struct Prepared {
  enum State : std::uint8_t {
    kUsable = 0,      ///< positive area
    kDegenerate = 1,  ///< collinear corners: zero area
    kCollapsed = 2,   ///< two corners weld to one point: no edges, dropped
  };
  EdgeMap edges;
  std::unique_ptr<SceneData> scene;
  std::vector<std::uint8_t> state;
  std::uint64_t hash = 0;
  std::vector<std::string> warnings;
};

/// Validates and prepares (prepare.cpp); `bvh` false skips the BVH, the convex solids and
/// the light warnings (merging).
Prepared prepare(const Mesh& mesh, const std::vector<Light>& lights, bool bvh);

/// Error(Usage) unless options.mergeGroups is empty or has one group per triangle.
void checkMergeGroups(const Mesh& mesh, const CutOptions& options);

/// The hash of a scene and its lights that shards carry.
std::uint64_t inputHash(const Mesh& mesh, const std::vector<Light>& lights);

}  // namespace glint::cut
