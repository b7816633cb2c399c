#pragma once
// Private to the baker: the state a bake shares between its tiles, and the ray casting
// and shading of one texel's samples (trace.cpp). baker.cpp rasterizes the UV layout
// into samples and drives the tiles.
#include "glint/bake/baker.h"
#include "glint/bake/gpu_backend.h"
#include "glint/raytrace/raytracer.h"
#include "internal.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace glint::bake::detail {

/// A low-poly triangle in texel space (x = u·W, y = v·H; y up).
struct UvTriangle {
  vec2 a, b, c;
  float invArea = 0.0f;  ///< 1 / signed area (negative for mirrored UVs); 0: skip
  ivec2 lo, hi;          ///< inclusive texel bounds
};

/// One sample position: which low-poly triangle, where in it.
struct Slot {
  int tri = -1;
  vec2 w{0.0f};  ///< barycentric weights of corners 1 and 2
};

/// Per-tile counters, summed at the end (integers: exact in any order).
struct Counters {
  std::uint64_t covered = 0, conservative = 0, samples = 0, hits = 0, misses = 0, rays = 0, aoRays = 0, overlaps = 0,
                inward = 0, thicknessRays = 0, curvatureRays = 0, vertexMeasurements = 0;
};

struct Context;

/// Thickness and curvature measured once per high-poly vertex and interpolated across the
/// triangles that are small against the scale those maps measure at (longest edge at most
/// half the thickness distance, the curvature radius): what they measure changes little
/// across such a triangle, and a dense mesh under a large bake would otherwise measure
/// nearly the same point for every texel its triangles cover (a 262k-triangle torus at
/// 2048²: 16 texels a triangle). Larger triangles are measured at each hit, as without the
/// cache, and so is every triangle of a bake with fewer samples than the mesh has vertices.
/// Vertices are the scene's corners joined where position and normal are equal, so a
/// hard edge keeps a value per side. Built per scene (a bake group has its own).
struct VertexCache {
  enum : std::uint8_t { kThickness = 1, kCurvature = 2 };
  /// One map's values: measured on first use, exactly once (trace.cpp, cachedAtVertex).
  struct Values {
    std::unique_ptr<std::atomic<std::uint8_t>[]> state;  ///< per vertex: unmeasured, being measured, measured
    std::unique_ptr<float[]> value;
  };
  const Mesh* mesh = nullptr;                 ///< the scene's triangles: corner 3t + k is mesh->indices[3t + k]
  std::vector<std::uint32_t> vertexOfCorner;  ///< per scene corner
  std::vector<std::uint32_t> cornerOfVertex;  ///< per vertex, one of its corners
  std::vector<std::uint8_t> small;            ///< per scene triangle: the maps interpolated on it
  Values thickness, curvature;

  vec3 position(std::uint32_t corner) const { return mesh->positions[mesh->indices[corner]]; }
};

struct Context {
  const BakeOptions& options;
  const Prepared& in;
  const raytrace::Scene& scene;
  std::vector<UvTriangle> tris;
  std::vector<std::vector<int>> bins;  ///< triangles per tile, ascending
  int tilesX = 0, tilesY = 0, root = 1;
  std::vector<vec2> sampleOffsets;  ///< root² sample positions within a texel
  float front = 0, rear = 0, aoDistance = 0, thicknessDistance = 0, curvatureRadius = 0;
  float epsilon = 0;  ///< offsets off a surface, and the nudge of a retried ray (scene units)
  mat3 worldNormalMatrix{1.0f};
  int channels = 3;  ///< floats per texel: the normal (3), then each map asked for, in the table's order (bake/maps.h)
  std::array<int, kMapCount> channel = [] {  ///< each map's first float in a texel; -1: not baked
    std::array<int, kMapCount> c{};
    c.fill(-1);
    return c;
  }();
  int channelOf(Map m) const { return channel[std::size_t(m)]; }
  bool baking(Map m) const { return channelOf(m) >= 0; }
  bool hemisphere = false;  ///< AO rays are cast (for AO or bent normals)
  /// Some map casts rays from the hit (AO, bent normals, thickness, curvature): the sweep's lean path
  /// (traceGroup) is not taken.
  bool hitWork = false;
  bool extraMaps = false;  ///< bent normals, thickness, curvature, position or opacity (storeExtraMaps)
  /// width × height × channels, row 0 = bottom (v = 0). Left uninitialized: a texel is only
  /// read once covered is set for it (the bake or the dilation wrote it), and zeroing 12 MB
  /// on one thread before the bake cost more than the workers touching the pages themselves.
  std::unique_ptr<float[]> texelStorage;
  std::span<float> texels;
  std::vector<std::uint8_t> covered;  ///< per texel
  /// The high poly's three corner normals per triangle, side by side (corner k of triangle
  /// t at [3t + k]): one cache line per hit instead of four scattered reads (indices, then
  /// three normals) on million-triangle meshes. Points into the mesh's own normals when its
  /// indices are 0, 1, 2, ... (a mesh loaded without joining vertices, as `glint bake`
  /// loads the high poly), else into highCornerNormalCopy.
  const vec3* highCornerNormals = nullptr;
  std::vector<vec3> highCornerNormalCopy;
  /// The low poly's corners per triangle, side by side, for the same reason; as 4-float
  /// vectors (position xyz0, normal xyz0, tangent xyzw) so interpolating one attribute is
  /// three vector multiply-adds.
  using Float4 = float __attribute__((vector_size(16)));
  struct LowCorners {
    std::array<Float4, 3> position, normal, tangent;
  };
  std::vector<LowCorners> lowCorners;
  // Bake groups and the maps of the high poly's parts (parts.cpp, bake/groups.h).
  const struct PartsTables* parts = nullptr;      ///< material/colour tables, when those maps are asked
  const std::uint32_t* highTriangleIds = nullptr; ///< the scene's triangle → the high poly's (null: the same)
  std::vector<std::uint32_t> texelMaterial;       ///< per texel material index + 1 (0: off the islands; detail::kMaterialMissed: no hit), with a material ID map
  std::unique_ptr<VertexCache> vertexCache;       ///< with thickness or curvature, where some triangles are small
  GpuScene* gpu = nullptr;  ///< the scene on the GPU (--device gpu): tiles are traced in waves (traceWave)
};

/// The vertex cache of the scene `mesh` (its triangles as the scene's, corner normals as
/// ctx.highCornerNormals) for the maps ctx asks for; null when no triangle is small enough
/// or neither map is asked for. Called after the channels are set up.
std::unique_ptr<VertexCache> buildVertexCache(const Context& ctx, const Mesh& mesh);

/// One sample to trace: its slot, UV and random seed.
struct SampleInput {
  Slot slot;
  vec2 uv{0.0f};
  std::uint64_t seed = 0;
};

struct SampleResult {
  vec3 value{0.0f};  ///< unit vector in the output space
  float ao = 1.0f;
  float height = 0.0f;
  vec3 bent{0.0f};      ///< unit bent normal in the output space (when asked)
  float thickness = 0.0f;
  float curvature = 0.0f;  ///< signed mean curvature at the hit (when asked)
  vec3 position{0.0f};  ///< the hit point, or the low poly's position on a miss (when asked)
  bool hit = false;
  bool inward = false;  ///< the high poly's normal at the hit faces against the low poly's
  std::int32_t triangle = -1;  ///< the hit's triangle in the scene (-1: a miss)
  vec2 hitUv{0.0f};             ///< its barycentrics (Embree's u, v)
};

/// The most samples traceGroup takes at once.
inline constexpr std::size_t kMaxGroup = 128;

/// Traces and shades a group of neighbouring samples (a few texels' worth, at most
/// kMaxGroup). `prediction`
/// carries, from group to group of a tile, which side of the low poly the hits were on
/// (+1 in front, −1 behind, 0 not known yet: start a tile with 0). It only changes how
/// many rays are cast, not the answers. Rays are logged when `rayLog` is set.
void traceGroup(const Context& ctx, std::span<const SampleInput> samples, std::span<SampleResult> results,
                Counters& counters, std::vector<raytrace::Ray>* rayLog, int& prediction);

/// The same for many samples at once on the GPU (ctx.gpu), in stages over the whole span:
/// the samples' first rays on the GPU; each hit settled and shaded on the CPU (with its rare
/// second rays: behind the low poly, a retry); then every hit's AO, thickness and curvature
/// rays on the GPU, as jobs (bake/gpu_backend.h) made from the same seeds and sets, and the
/// results finished on the CPU. What the samples get is traceGroup's, but for rays that
/// graze an edge (the GPU's triangle test is watertight, Embree's is not) and the last bits
/// of the GPU's arithmetic.
void traceWave(const Context& ctx, std::span<const SampleInput> samples, std::span<SampleResult> results, Counters& counters);

}  // namespace glint::bake::detail
