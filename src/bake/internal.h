#pragma once
// Private pieces of the baker, split out so each file stays readable.
#include "glint/bake/baker.h"

#include <cstdint>
#include <string>
#include <vector>

namespace glint::bake::detail {

/// The inputs after checking and preparation.
struct Prepared {
  Mesh low;                                   ///< normals ensured, MikkTSpace tangents, split vertices
  std::vector<std::uint32_t> originalIndices; ///< low.indices before splitting (for the cage)
  Mesh highWithNormals;                       ///< only used when the high poly had no normals
  const Mesh* high = nullptr;                 ///< the high poly to trace (input or the copy above)
  float diagonal = 0.0f;                      ///< low poly bounding-box diagonal
};

/// Checks options and meshes (one-line errors), generates what is missing, fills the
/// low-poly related stats and warnings.
Prepared prepareInputs(const Mesh& low, const Mesh& high, const BakeOptions& options, BakeStats& stats,
                       std::vector<std::string>& warnings);

/// Where a bake's rays go (device.cpp): the GPU or the CPU, why, and the GPU it started.
struct DeviceChoice {
  bool gpu = false;
  std::string reason;
  GpuInfo info;
};
/// BakeOptions::device for a high poly of `triangles` triangles: starts options.gpu when it
/// may be used; Error(NoGpu) when Device::Gpu cannot be had.
DeviceChoice chooseDevice(const BakeOptions& options, std::size_t triangles);

/// The samples a GPU wave takes at most (baker.cpp, bakeSlabs): enough rays to keep a large
/// GPU busy for a few dispatches (2^26), between 2^16 samples (1,024 rays each) and 2^18.
std::size_t waveSamples(const BakeOptions& options);
/// The host memory a sample of a GPU wave holds while the wave runs (its input, geometry,
/// first ray and hit, the hit settled, its result and jobs): about 460 bytes, rounded up.
inline constexpr double kWaveBytesPerSample = 512.0;

/// Bilinear, wrapping sample of channel 0 of a height map at UV (v up).
float sampleHeight(const Image& height, vec2 uv);
/// Tangent-space normal of the height map at uv (central differences, one texel apart).
vec3 detailNormal(const HeightDetail& detail, vec2 uv);
/// Reoriented normal mapping: `detail` (tangent space, around +Z) rotated onto `base`.
vec3 combineDetail(const vec3& base, const vec3& detail);

}  // namespace glint::bake::detail

namespace glint::bake {
/// frameLowPoly's last steps (bake/asset.h), in place: unit normals, then MikkTSpace
/// tangents; returns the vertices added. prepareInputs and the asset share it, so the
/// asset's tangents are the frames the baker encoded against.
std::size_t frameLowPolyInPlace(Mesh& low);
}  // namespace glint::bake
