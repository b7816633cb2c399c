#pragma once
// glint/bake/baker.h — the normal mapper: high-poly detail baked into a texture for a
// low-poly mesh (ATI's "normal mapper" tool, WWDC 2003, rebuilt on Embree).
//
// Contents
//   HitSelection, Distance                how rays are cast (NormalSpace, the space normals
//                                         are stored in, is image/normalmap.h's)
//   HeightDetail                          painted micro detail combined with the bake
//   BakeOptions                           everything bake() can be told (defaults are good)
//   BakeStats, BakeResult                 the maps, and what it took to make them
//   bake                                  the whole pipeline, GL-free, deterministic
//   validateOptions, estimatePeakMemoryMiB the checks and the memory a job needs, before it starts
//   toJson                                the report of a bake (`glint bake --json`)
//
// How it works
//   For every texel of the output, N stratified sample points (a √N × √N grid) are
//   located in the low poly's UV layout. At each sample the low poly's position, normal
//   and MikkTSpace tangent frame are interpolated; a ray is cast from the position along
//   the interpolated normal, forwards up to maxFront and backwards up to maxRear ("negative
//   rays": the low poly may be inside, outside or through the high poly). The chosen hit's
//   interpolated high-poly normal is expressed in the requested space, the samples of a
//   texel are averaged and normalized. Texels that UV triangles touch but whose samples all
//   miss them (thin slivers on island borders) get one sample at the closest point of the
//   triangle, so island borders are never empty. Finally the map is dilated into unused
//   texels so bilinear fetches and mipmaps do not pull in the background.
//
// Maps (bake/maps.h's table, by Map; each only when asked in BakeOptions::maps: a plain
// normal bake does no extra work; all in the same pass, sharing the BVH and the normal-pass
// rays; texel values average the texel's samples)
//   normal       the hit's high-poly normal in `space` (above)
//   ao           open fraction of aoSamples cosine-weighted hemisphere rays, aoDistance long,
//                around the high-poly normal at the hit (1 = unoccluded)
//   height       signed distance along the low poly's normal to the hit (+ in front)
//   miss mask    fraction of the texel's samples whose rays found nothing (not dilated)
//   bent normal  normalize(sum of the AO rays that escaped): the direction light mostly
//                comes from; the high-poly normal where every ray is blocked, the low
//                poly's where the sample missed. Same space and encoding as `normal`
//                (painted detail is not applied). Casts the AO rays even without `ao`.
//   thickness    from the hit, aoSamples rays into the surface (cosine-distributed around
//                the negated normal, the AO sequence with its own per-sample rotation):
//                mean of min(distance to the first surface, D) / D, D = thicknessDistance;
//                1 = thick (nothing within D), 0 = a paper-thin wall. Averaged over the
//                texel's samples that hit; 0 where none did. For subsurface scattering and
//                translucency (a sphere of radius r reads 4r / 3D: the mean cosine-weighted
//                chord).
//   position     the hit point in object space (the low poly's position where a sample
//                missed), averaged over the texel's hits; float files keep coordinates,
//                8/16-bit files map stats.positionBounds (the high poly's box) to 0..1.
//   curvature    signed mean curvature H = (κ1 + κ2) / 2 of the high poly at the hit, in
//                1 / scene units, measured at the scale r = curvatureRadius: 8 points at
//                distance r around the hit in its tangent plane (evenly spaced, turned by
//                the sample's random angle) are dropped onto the high poly along −normal
//                (a ray from 1 r above to 1 r below; the first hit facing the same way;
//                halving r up to 3 times where none is found), and each gives the normal
//                curvature (n(q) − n(p))·(q − p) / |q − p|² from the interpolated normals;
//                H is their mean (exact on a sphere at any r; on a smooth surface the
//                error falls as r², opposite points cancelling the first-order term).
//                Convex (bending away from the normal, a sphere's outside) is positive:
//                a sphere of radius R reads 1/R. Detail smaller than r is averaged away.
//                0 where no sample hit. 8/16-bit files hold 0.5 + 0.5·clamp(H·r, −1, 1)
//                (output.h's curvatureForOutput): mid-grey flat, white for a convex
//                bend of radius r or tighter, black for a concave one.
//   opacity      hits / samples per texel (samples outside the UV islands count as
//                misses, so island borders are antialiased), 0 outside the islands; not
//                dilated. A texel filled by the closest-point rule counts its one sample.
//   material ID  a flat colour per high-poly material (majority of the texel's hits; dilation
//                copies, never blends); vertex colour the high poly's interpolated vertex
//                colour: both need the high poly's parts, see bake/groups.h (bake groups too)
//
// Notes for artists (from the original tool's authors)
//   - Shared normals. Rays follow the interpolated low-poly normals. Where the low poly has
//     a hard edge (two normals at one position) the rays fan apart and a wedge of the high
//     poly is never sampled. Use smooth (shared) normals on the low poly; bake() warns about
//     hard edges.
//   - UV spacing. A normal map is vectors, not colours: a texel bleeding in from a
//     neighbouring island bends the lighting. Leave space between islands (at least twice
//     the padding at the smallest mip level you care about) and keep the padding on.
//   - Tangent space. Maps are baked in MikkTSpace (glint/mesh/tangents.h), the frame the
//     renderer reconstructs; the low poly's own tangents, if any, are ignored.
//
// Determinism: the result depends only on the inputs and options, not on the thread
// count or scheduling (tiles are independent; AO uses per-texel random sequences).
//
// Example: a bake as `glint bake low.obj high.ply -o normal.png --size 2048x2048 --json -`
// runs it, with its checks, memory estimate and report's fields (core/tool.h adds the
// common ones; bake/output.h has the file formats).
//
/// ```cpp
/// #include <glint/bake/output.h>
/// #include <nlohmann/json.hpp>
/// #include <iostream>
/// glint::bake::BakeOptions options;
/// options.width = options.height = 2048;
/// options.normalType = glint::bake::outputType("normal.png");  // U8: quantized as it is baked
/// glint::bake::validateOptions(options);                        // before loading anything
/// const double mib = glint::bake::estimatePeakMemoryMiB(options, {"low.obj", "high.ply"});
/// const glint::Mesh low = glint::loadMesh("low.obj");
/// const glint::Mesh high = glint::loadMesh("high.ply", {.joinVertices = false});
/// const glint::bake::BakeResult result = glint::bake::bake(low, high, options);
/// glint::saveImage(result.normal, "normal.png");
/// nlohmann::ordered_json report = glint::bake::toJson(options);
/// report.update(glint::bake::toJson(result.stats));
/// std::cout << report.dump(2) << '\n' << mib << '\n';
/// ```

#include "glint/bake/gpu_backend.h"
#include "glint/bake/maps.h"
#include "glint/core/math.h"
#include "glint/image/image.h"
#include "glint/image/normalmap.h"
#include "glint/mesh/mesh.h"

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace glint::raytrace {
struct Ray;
}

namespace glint::bake {

/// The most samples per texel (--samples: a square, 32²) and AO rays per sample (--ao-samples).
inline constexpr int kMaxSamples = 1024;
inline constexpr int kMaxAoSamples = 4096;

/// Whether `samples` per texel can be baked: a square (a stratified √N×√N grid), 1..kMaxSamples.
/// The one rule: the baker's check, `--samples`' help and `glint bake --describe` (the
/// add-on's menu) read it.
constexpr bool validSampleCount(int samples) {
  if (samples < 1 || samples > kMaxSamples) return false;
  int root = 1;
  while (root * root < samples) ++root;
  return root * root == samples;
}

/// The valid counts, ascending: 1, 4, 9, ..., kMaxSamples.
inline std::vector<int> sampleCounts() {
  std::vector<int> counts;
  for (int n = 1; n <= kMaxSamples; ++n)
    if (validSampleCount(n)) counts.push_back(n);
  return counts;
}

enum class HitSelection {
  Closest,    ///< the hit with the smallest |t|, in front or behind (default)
  FrontFirst  ///< any hit in front of the low poly wins over hits behind it
};

/// A distance along the ray: absolute (scene units) or a fraction of the diagonal of the
/// low poly's bounding box (the default: it scales with the model).
struct Distance {
  float value = 0.05f;
  bool relative = true;
  float resolve(float diagonal) const { return relative ? value * diagonal : value; }
};

/// A painted height map combined with the baked normals ("scars and pores"): the bake gives
/// the smooth shape, the height map the micro detail. Tiled over the low poly's UVs.
struct HeightDetail {
  Image height;        ///< channel 0 is the height, 0..1 (any pixel type); row 0 is v = 1
  float scale = 1.0f;  ///< slope per height-map texel: a height step of 1/scale across one
                       ///< texel tilts the normal by 45°; negative values engrave
};

struct BakeOptions {
  int width = 1024;   ///< output size in texels (any W × H)
  int height = 1024;
  int samples = 1;    ///< samples per texel: validSampleCount (1, 4, 9, 16, ... kMaxSamples)
  NormalSpace space = NormalSpace::Tangent;
  bool directX = false;           ///< flip green (DirectX/Unreal convention; OpenGL is +Y up)
  mat4 objectToWorld{1.0f};       ///< for NormalSpace::World (normals use its inverse transpose)
  Distance maxFront{0.05f, true}; ///< how far in front of the low poly (along its normal) to look
  Distance maxRear{0.05f, true};  ///< how far behind it
  HitSelection selection = HitSelection::Closest;
  /// Optional cage: the low poly with every vertex pushed outwards (same vertex count and
  /// triangles). Rays then start on the cage and travel towards the low poly's surface,
  /// accepting the first hit up to maxRear beyond it; maxFront is not used.
  std::optional<Mesh> cage;
  int padding = 16;               ///< texels of dilation around the islands (0: none)
  bool fillAll = false;           ///< dilate until every texel is filled
  std::optional<HeightDetail> detail;

  /// The maps to bake besides the normal map (bake/maps.h: AO, height, miss mask, bent
  /// normals, thickness, curvature, position, opacity, material ID, vertex colour). Bent
  /// normals cast the AO rays (aoSamples, aoDistance) whether or not AO is asked; thickness
  /// casts aoSamples rays from the high-poly hit into the surface, cosine-distributed around
  /// the negated normal, the mean distance to where they leave it, each capped at
  /// thicknessDistance, divided by it; curvature is the high poly's signed mean curvature
  /// (convex positive), measured by the normals at curvatureRadius around the hit (8
  /// closest-hit rays per sample hit); material ID and vertex colour need the high poly read
  /// as parts (bake/groups.h: bake() of plain meshes gives one material colour, and no vertex
  /// colours: Error(Input)).
  MapSet maps;
  int aoSamples = 16;             ///< AO rays per sample (cosine-weighted, stratified)
  Distance aoDistance{0.1f, true};///< AO ray length
  Distance thicknessDistance{0.1f, true};  ///< thickness ray length, and the distance that reads 1
  Distance curvatureRadius{0.01f, true};   ///< the scale curvature is measured at; also the radius that reads white/black in 8/16-bit files
  /// Pixel type of BakeResult::normal: F32, or U8/U16 quantized as Image::converted does —
  /// what an integer file holds, without a float copy of the map on the way.
  PixelType normalType = PixelType::F32;

  bool progress = true;           ///< draw a progress bar (only on a terminal, see core/progress.h)
  std::string progressLabel = "bake";  ///< the bar's label (`glint bake --batch`: "bake 2/3")
  /// Polled between tiles; when it becomes true bake() throws Error(Interrupted).
  const std::atomic<bool>* cancel = nullptr;
  /// BVHs kept between bakes (bake/scene_cache.h): a bake of a high poly the cache has seen
  /// (same arrays, same BVH quality) reuses its BVH. Null: built for this bake only.
  class SceneCache* sceneCache = nullptr;
  /// Where the rays are traced (bake/gpu_backend.h): Auto takes the GPU when `gpu` is given,
  /// its renderer is hardware and the bake fits its memory; Gpu insists (Error(NoGpu)
  /// otherwise). BakeStats::device and deviceReason say which and why.
  Device device = Device::Auto;
  /// The GPU's side (scenes/bake_gpu.h's bakeGpuBackend()); null: the CPU only. Its context
  /// is made on the thread that calls bake().
  GpuBackend* gpu = nullptr;
  bool gpuDebug = false;  ///< the GPU's context with GL debug output (`glint --gl-debug`, tests)
  /// Benchmarks only: receives every ray the normal pass casts, in a deterministic order
  /// (32 bytes per ray; keep bakes small).
  std::vector<raytrace::Ray>* rayLog = nullptr;
};

struct BakeStats {
  std::size_t lowTriangles = 0;         ///< of the low poly as given
  std::size_t highTriangles = 0;        ///< of the high poly
  std::uint64_t texels = 0;             ///< width × height
  std::uint64_t coveredTexels = 0;      ///< texels with at least one sample on the low poly
  std::uint64_t conservativeTexels = 0; ///< of those, filled by the closest-point rule
  std::uint64_t paddedTexels = 0;       ///< filled by dilation
  std::uint64_t samples = 0;            ///< sample points on the low poly
  std::uint64_t hits = 0;               ///< samples whose rays found the high poly
  std::uint64_t misses = 0;             ///< samples whose rays found nothing
  std::uint64_t inwardHits = 0;         ///< hits where the high poly's normal faces against the low poly's
  std::uint64_t rays = 0;               ///< normal-pass rays (front + rear)
  std::uint64_t aoRays = 0;             ///< hemisphere rays (AO and bent normals share them)
  std::uint64_t thicknessRays = 0;      ///< rays into the surface (thickness)
  std::uint64_t curvatureRays = 0;      ///< rays dropping points onto the high poly (curvature)
  /// High-poly vertices whose thickness or curvature was measured once and interpolated over
  /// the small triangles around them, instead of measured at every hit (docs/bake.md,
  /// "Thickness and curvature at vertices"); counted once per map.
  std::uint64_t vertexMeasurements = 0;
  std::uint64_t overlappingSamples = 0; ///< samples inside more than one UV triangle
  std::size_t mirroredTriangles = 0;    ///< low-poly triangles with mirrored UVs
  std::size_t degenerateUvTriangles = 0;///< low-poly triangles with zero UV area (skipped)
  std::size_t hardEdgeVertices = 0;     ///< low-poly positions with more than one normal
  std::size_t addedVertices = 0;        ///< vertices split by tangent generation
  float frontDistance = 0, rearDistance = 0, aoDistance = 0;  ///< resolved, scene units
  float thicknessDistance = 0;          ///< resolved, scene units (0 without a thickness map)
  float curvatureRadius = 0;            ///< resolved, scene units (0 without a curvature map)
  /// With a position map: the box its 8/16-bit files are normalized to, the high poly's
  /// bounding box (every hit point lies inside it). p = min + value · (max − min).
  std::optional<Bounds> positionBounds;
  std::string device = "cpu";           ///< where the rays were traced: "cpu" or "gpu"
  std::string deviceReason;             ///< why ("--device auto: the GL renderer is software (llvmpipe)")
  std::string gpuRenderer;              ///< the GL renderer, when a context was made
  std::uint64_t gpuBytes = 0;           ///< GPU memory the bake held (BVH, normals, batches)
  std::uint64_t gpuFreeBytes = 0;       ///< free GPU memory the driver reported before upload (0: not reported)
  std::size_t gpuDispatches = 0;        ///< compute dispatches
  double gpuLongestDispatchMs = 0;      ///< the longest (the bake's promise: ~30 ms, a desktop stays responsive)
  std::size_t bvhBytes = 0;             ///< Embree memory for the high poly
  bool bvhReused = false;               ///< the BVH came from BakeOptions::sceneCache
  bool lowQualityBvh = false;           ///< BVH built at Embree's low quality (few rays per triangle), else medium
  // The three phases add up to the whole of bake():
  double prepareSeconds = 0;            ///< checks, tangents, BVH build, per-triangle tables
  double traceSeconds = 0;              ///< rasterizing samples and casting rays (wall clock)
  double traceCpuSeconds = 0;           ///< the same phase in process CPU time (all threads)
  double dilateSeconds = 0;             ///< dilation and the maps as images
  double hitRatio() const { return samples ? double(hits) / double(samples) : 0.0; }
};

struct BakeResult {
  Image normal;     ///< RGB encoded 0..1 (encodeNormal, image/normalmap.h), green flipped if directX; F32
                    ///< unless BakeOptions::normalType says otherwise
  /// The other maps asked for (BakeOptions::maps), by bake/maps.h's Map, F32 (maps[Map::Normal]
  /// stays empty: the normal map is `normal`): AO R 0..1 (1 = unoccluded); height R signed
  /// distance in scene units; miss mask R 0..1 fraction of missed samples (not dilated); bent
  /// normal RGB encoded like `normal`; thickness R 0..1 (1 = no exit within
  /// thicknessDistance); curvature R signed mean curvature, 1 / scene units (convex +);
  /// position RGB object-space hit points; opacity R 0..1 hits / samples per texel, 0 outside
  /// islands (not dilated); material ID RGB, each channel k/255 (materialColor); vertex colour
  /// RGB. MapInfo::forOutput turns each into a file's pixels.
  std::array<Image, kMapCount> maps;
  /// Any map by name: `normal` for Map::Normal, else maps[map].
  const Image& map(Map m) const { return m == Map::Normal ? normal : maps[std::size_t(m)]; }
  Image coverage;   ///< R U8: 255 inside UV islands, 128 padding, 0 unused
  Mesh low;         ///< the low poly as baked: MikkTSpace tangents, split vertices — render this
  BakeStats stats;
  std::vector<std::string> warnings;  ///< also logged as they happen
};

/// Bakes `high` onto `low`. Error(Input) with one line when the low poly has no UVs, a mesh
/// is empty or has non-finite values, the cage does not match the low poly, or the detail
/// map is empty; Error(Usage) for bad options (size, samples). Missing normals are generated
/// (smooth) with a warning; mirrored or overlapping UVs and hard edges are warned about and
/// baked anyway. Throws Error(Interrupted) when options.cancel becomes true.
BakeResult bake(const Mesh& low, const Mesh& high, const BakeOptions& options = {});

/// Error(Usage) naming the first bad option (size, samples, AO samples when AO, bent
/// normals or thickness are asked, distances, a zero thickness distance or curvature radius, padding). bake() calls it too; front ends call it before loading anything.
void validateOptions(const BakeOptions& options);

/// The peak memory (MiB) of a bake with these options, from the sizes of its mesh files
/// (`inputs`: low, high and cage; a missing file counts as empty): ~64 MiB of process,
/// about twice the input files (meshes and BVH), ~19.5 bytes per texel for the normal map
/// and its buffers and ~8 for each extra map channel (AO, height, miss mask, thickness,
/// curvature, opacity: one; bent normals, position, vertex colour: three; material ID: two, its
/// 4-byte index per texel and its RGB image: a float in the texel buffer and one in the
/// result image). Measured on the studded-torus pair (1024² → 16384², 262k triangles;
/// 16384²: 4,959 MiB; the extra channels at 2048²: 8.0 bytes each, PNG outputs). A bake that
/// may trace on the GPU (device Auto or Gpu) adds a wave of samples held at once (512 bytes
/// each, at most 2^18: 128 MiB), ~56 MiB for the GL context and its batches, and twice the
/// input files again for the GPU's copy of the hierarchy (host memory on a software
/// renderer, and while it is uploaded). The GPU's own memory is checked apart.
double estimatePeakMemoryMiB(const BakeOptions& options, const std::vector<std::filesystem::path>& inputs);

/// The options in a report: width, height, samples_per_texel, space ("tangent", "object"
/// or "world"), directx.
nlohmann::ordered_json toJson(const BakeOptions& options);
/// The report of a bake, key by key: low_triangles, high_triangles, texels, covered_texels,
/// conservative_texels, padded_texels, samples, rays, ao_rays, thickness_rays,
/// curvature_rays, hits, inward_hits, misses, hit_ratio, max_front, max_rear (scene units),
/// rays_per_second, bvh_mib, bvh_quality ("low" or "medium"), device ("cpu" or "gpu"),
/// device_reason (why: "--device auto: the GL renderer is software (llvmpipe ...)"), on the
/// GPU gpu_renderer, gpu_mib, gpu_free_mib (when the driver says), gpu_dispatches and
/// gpu_longest_dispatch_ms (gpu_renderer also when auto made a context and chose the CPU); with a thickness map
/// thickness_distance, with a curvature map curvature_radius (scene units), with a
/// position map position_min and position_max ([x, y, z]: positionBounds).
nlohmann::ordered_json toJson(const BakeStats& stats);

}  // namespace glint::bake
