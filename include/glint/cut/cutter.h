#pragma once
// glint/cut/cutter.h — the shadow cutter: static shadows cut into the geometry, exactly.
//
// Contents
//   Light, CutOptions     point lights and how to run
//   CutMesh               the result: convex polygons, each a piece of one input triangle,
//                         with a light mask (which lights reach it)
//   cut                   the whole job on one machine
//   cutShard, mergeShards the same job spread over machines (--shard i/n, --merge)
//   estimatePeakMemoryMiB what a job will need, before it starts (`--max-memory`)
//   toJson                the report of a cut or a shard (`glint cut --json`)
//   triangulate           the polygons as triangles (for renderers and glTF)
//
// The method (WWDC 2003 session 212, ATI's "Pipe Dream" shadow cutting): for every polygon A and every
// light, the polygons B in A's *near beam* (the volume between A and the light) cut A with
// their *far beam* (the three planes through the light and B's edges, and B's own plane);
// the pieces inside a far beam are tagged as in shadow for that light. Afterwards pieces
// of one input polygon with the same tags are merged again. Because every piece is cut
// from A by beams, cyclically overlapping polygons (which no depth order can sort) come
// out right.
//
// What glint adds, spelled out
//   Exact.     Every decision is a sign of a polynomial in the input numbers: vertices are
//              named by the original planes that meet there (B's planes and the light), never
//              by rounded coordinates of earlier splits, and the signs are computed exactly
//              (interval arithmetic, then multi-precision where needed; docs/cut.md). Coplanar,
//              touching and edge-sharing polygons, slivers and degenerate input cannot make
//              it crash, loop or crack.
//   A mesh.    Splits are made consistently on shared edges: a watertight input stays
//              watertight (no T-junctions). Output vertices are rounded to float only at the
//              end; pieces that rounding would flatten to nothing are dropped.
//   Shadow.    A piece is lit by a light when the open segment from its points to the light
//              meets no other polygon (Embree's shadow rays agree: tests/cut). A polygon whose
//              plane contains the light ("grazing") gets no light from it. Facing is not
//              part of the mask: a renderer's N·L darkens back faces anyway.
//   Speed.     Candidates from a BVH query of each near beam, receivers in parallel, big
//              shadows first, shadowed pieces never cut again (numbers in docs/cut.md).
//   Determinism. The output does not depend on the thread count, bit for bit.
//
// Example: a cut as `glint cut room.glb -o room_cut.glb --light 0,4,0,lamp --json -` runs
// it, with its memory estimate and its report's fields (core/tool.h adds the common ones).
//
/// ```cpp
/// #include <glint/cut/output.h>
/// #include <nlohmann/json.hpp>
/// #include <iostream>
/// const glint::Mesh scene = glint::loadMesh("room.glb");
/// glint::cut::CutOptions options;
/// options.lights = {{.position = {0, 4, 0}, .name = "lamp"}};
/// const double mib = glint::cut::estimatePeakMemoryMiB(scene.triangleCount(), options.lights.size());
/// glint::cut::CutResult result = glint::cut::cut(scene, options);
/// glint::cut::saveCutMesh(result.mesh, result.lights, "room_cut.glb");
/// const bool litByLamp = result.mesh.polygonMask[0] & 1;  // polygon 0 is lit by "lamp"
/// std::cout << glint::cut::toJson(result.stats).dump(2) << '\n' << mib << ' ' << litByLamp << '\n';
/// ```

#include "glint/core/math.h"
#include "glint/mesh/mesh.h"

#include <nlohmann/json_fwd.hpp>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace glint::cut {

using dvec3 = glm::dvec3;

/// The cutter's version: raised whenever cut() gives different output for the same input
/// (a fix, a change to merging or rounding), so that cached cuts (cut/cache.h) keyed by it
/// are rebuilt. 2: vertices on input points and on axis-aligned input planes keep the
/// input's exact coordinates. 3: each light-mask region of a receiver is triangulated with
/// only the vertices where its outline turns.
constexpr std::uint32_t kCutterVersion = 3;

/// Bit l set: light l reaches the piece.
using LightMask = std::uint32_t;
/// Lights per run (the bits of a LightMask).
constexpr int kMaxLights = 32;

/// A point light.
struct Light {
  vec3 position{0.0f};
  std::string name;  ///< for reports; "light<i>" when empty
};

/// `glint cut --light`'s text: "x,y,z" or "x,y,z,name" (core/text.h's strict numbers).
/// Error(Usage) for anything else.
Light parseLight(std::string_view text);

struct CutOptions {
  std::vector<Light> lights;  ///< 1 to kMaxLights
  /// Cut only the receivers of shard `shardIndex` (0-based) of `shardCount` (cutShard):
  /// receivers are grouped by region (sorted along a space-filling curve), so a shard's
  /// receivers are near each other and share occluders.
  int shardIndex = 0;
  int shardCount = 1;
  /// Per input triangle, or empty: pieces of coplanar neighbours merge only when their
  /// triangles have the same value here (e.g. a material and a smoothing group, when the
  /// caller interpolates attributes across each input triangle). Empty: every coplanar
  /// neighbour of one surface may merge.
  std::vector<std::uint32_t> mergeGroups;
  bool progress = false;                       ///< a progress bar on stderr (when a terminal)
  const std::atomic<bool>* cancel = nullptr;   ///< polled; when set, cut() throws Error(Interrupted)
};

/// The cut mesh: convex polygons (counter-clockwise), each in the plane of its source: a
/// piece of one input triangle, or of a *patch* of coplanar neighbours of one surface
/// merged where they have the same light mask (WWDC 2003 session 212's optimization step across
/// triangles; docs/cut.md).
struct CutMesh {
  std::vector<vec3> positions;              ///< output vertices, rounded to float
  std::vector<dvec3> precisePositions;      ///< the same points to about a double's precision
  std::vector<std::uint32_t> polygonStart;  ///< polygon p: corners[polygonStart[p] .. polygonStart[p+1])
  std::vector<std::uint32_t> corners;       ///< vertex indices
  std::vector<std::uint8_t> straight;       ///< per corner: 1 when it lies on a straight side (no turn)
  std::vector<std::uint32_t> polygonSource; ///< the input triangle each polygon is a piece of (of a patch: its lowest triangle)
  std::vector<LightMask> polygonMask;       ///< per polygon: the lights that reach it
  /// Per input triangle: the lowest triangle of its patch (itself when it has no coplanar
  /// neighbour to merge with), so pieces of triangle t are the polygons whose source is
  /// trianglePatch[t]. Empty for a mesh loaded from a file.
  std::vector<std::uint32_t> trianglePatch;

  std::size_t polygonCount() const { return polygonMask.size(); }
  std::size_t cornerCount(std::size_t polygon) const { return polygonStart[polygon + 1] - polygonStart[polygon]; }
};

/// Counts for one light.
struct LightStats {
  std::string name;
  vec3 position{0.0f};
  std::uint64_t litPolygons = 0, shadowedPolygons = 0;
  double litArea = 0.0, shadowedArea = 0.0;
  std::uint64_t grazingTriangles = 0;  ///< input triangles whose plane contains the light
};

struct CutStats {
  std::uint64_t inputTriangles = 0;
  std::uint64_t receivers = 0;          ///< triangles cut (this shard's, for cutShard)
  std::uint64_t degenerateTriangles = 0;  ///< zero area: carried through unlit, never cast shadows
  std::uint64_t collapsedTriangles = 0;   ///< two corners at one position: dropped
  std::uint64_t outputPolygons = 0, outputTriangles = 0, outputVertices = 0;
  std::uint64_t droppedSlivers = 0;     ///< pieces that rounding to float flattened
  std::uint64_t mergedPatches = 0;      ///< patches of coplanar triangles whose pieces merged
  std::uint64_t candidates = 0;         ///< (receiver, triangle) pairs from the near-beam queries
  std::uint64_t occluders = 0;          ///< of those, the ones whose far beam may reach the receiver
  std::uint64_t clippedPairs = 0;       ///< (piece, far beam) pairs clipped exactly
  std::uint64_t cuts = 0;               ///< of those, the ones that cut a shadow
  std::uint64_t facesBeforeMerge = 0;   ///< pieces before the merge step
  std::uint64_t symbolicPredicates = 0, filteredPredicates = 0, exactPredicates = 0;
  double prepareSeconds = 0.0, cutSeconds = 0.0, assembleSeconds = 0.0;
  std::vector<LightStats> lights;
};

struct CutResult {
  CutMesh mesh;
  CutStats stats;
  std::vector<Light> lights;          ///< the lights cut with (for a merge, the shards'): saveCutMesh's
  std::vector<std::string> warnings;  ///< already logged
};

/// Cuts the shadows of `options.lights` into `scene`. Error(Input) for an empty mesh,
/// NaN/infinite coordinates or bad indices; Error(Usage) for no lights, more than
/// kMaxLights or a non-finite light position; Error(Interrupted) when cancelled.
/// Warnings (logged and returned): degenerate triangles, a light on a surface, a light
/// inside a closed mesh.
CutResult cut(const Mesh& scene, const CutOptions& options);

// ------------------------------------------------------------------ shards
/// One shard's work: the pieces of its receivers, by name (exact), before the shared edges
/// are made consistent. Files written by saveShard hold exactly this.
struct Shard {
  std::uint64_t inputHash = 0;   ///< of the scene's positions and indices and the lights
  int shardIndex = 0, shardCount = 1;
  std::vector<Light> lights;
  CutStats stats;
  std::vector<std::string> warnings;
  struct Impl;
  std::shared_ptr<Impl> pieces;  ///< the receivers' pieces (opaque)
};

/// Cuts the receivers of shard options.shardIndex of options.shardCount.
Shard cutShard(const Mesh& scene, const CutOptions& options);
/// Writes a shard (binary, versioned) atomically; Error(Output) when it cannot.
void saveShard(const Shard& shard, const std::filesystem::path& path);
/// Error(Input) for a missing, truncated or foreign file.
Shard loadShard(const std::filesystem::path& path);
/// Joins shards of one job into the cut mesh, cut with the shards' lights (and their
/// names). Of the options, `lights` is checked: when not empty, Error(Usage) unless it has
/// the shards' light positions in order; `cancel` is polled between the merge's steps
/// (Error(Interrupted)). The shard fields are not used (each shard says which it is), nor is
/// `progress` (merging takes a small part of a cut's time). Error(Usage) for no shards;
/// Error(Input) when they are not of this scene and these lights, or when a shard is
/// missing or given twice.
CutResult mergeShards(const Mesh& scene, std::vector<Shard> shards, const CutOptions& options = {});

// ------------------------------------------------------------------ estimates and reports
/// The peak memory (MiB) of `glint cut` on `triangles` input triangles for `lights` lights
/// (at least one counted) with `threads` worker threads (0: as many as oneTBB will use
/// now), one machine: an upper bound fitted to the peak resident set measured on the
/// machine-room stand-in (14 to 554k triangles, 1 to 4 lights, 1 and 2 threads, .glb and
/// .ply written; docs/cut.md, "Memory"): 18 to 25 % above it from 140k triangles on, up to
/// twice it on small scenes (tens of MiB):
///   28 MiB                                   the process (the measured floor is 20 MiB)
/// + threads × min(4 + 6 × lights MiB,        each thread's scratch: the pieces and names of
///                 2 KiB × triangles × lights)  the receiver it cuts, no bigger than the scene's
/// + triangles × (700 + 400 × lights) bytes   the scene, beams, pieces, the merge and the output
/// e.g. 14 triangles, 1 light: 28 MiB (measured 20); 554k triangles, 2 lights, 2 threads:
/// 853 MiB (measured 697).
double estimatePeakMemoryMiB(std::uint64_t triangles, std::size_t lights, int threads = 0);

/// The lights as a report lists them: [{"name", "position": [x, y, z]}, ...] (names as
/// given, possibly empty).
nlohmann::ordered_json toJson(const std::vector<Light>& lights);
/// The report of a cut, key by key: input_triangles, output_polygons, output_triangles,
/// output_vertices, polygons_per_input_triangle, triangles_per_input_triangle,
/// pieces_before_merge, merged_patches, degenerate_triangles,
/// collapsed_triangles, dropped_slivers, per_light [{name, lit_polygons, shadowed_polygons,
/// lit_area, shadowed_area, grazing_triangles}], candidates, occluders, clipped_pairs, cuts,
/// clipped_pairs_per_second, predicates {symbolic, interval, exact}.
nlohmann::ordered_json toJson(const CutStats& stats);
/// The report of one shard: input_triangles, receivers, clipped_pairs.
nlohmann::ordered_json toJson(const Shard& shard);

// ------------------------------------------------------------------ triangles
/// The polygons as triangles: n − 2 per polygon of n corners, none of zero area (ears
/// clipped at corners that turn; corners on straight sides are kept, so neighbours still
/// share every vertex), no vertex added. `trianglePolygon[t]` is the polygon triangle t
/// belongs to.
struct Triangles {
  Mesh mesh;  ///< positions and indices (counter-clockwise); no normals
  std::vector<std::uint32_t> trianglePolygon;
};
Triangles triangulate(const CutMesh& mesh);

/// Area of polygon p from the precise positions.
double polygonArea(const CutMesh& mesh, std::size_t polygon);

}  // namespace glint::cut
