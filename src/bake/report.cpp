// What a bake job needs and what it reports: the memory estimate and the JSON fields of
// `glint bake --json` (core/tool.h adds the fields every tool shares).
#include "glint/bake/baker.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <vector>

namespace glint::bake {

namespace {

const char* spaceName(NormalSpace space) {
  switch (space) {
    case NormalSpace::Object: return "object";
    case NormalSpace::World: return "world";
    case NormalSpace::Tangent: break;
  }
  return "tangent";
}

}  // namespace

double estimatePeakMemoryMiB(const BakeOptions& options, const std::vector<std::filesystem::path>& inputs) {
  std::error_code ec;
  double inputBytes = 0.0;
  for (const std::filesystem::path& in : inputs) {
    if (!in.empty()) inputBytes += double(std::filesystem::file_size(in, ec)) * (ec ? 0.0 : 1.0);
  }
  const double texels = double(options.width) * double(options.height);
  double extraChannels = 0.0;  // the maps' float channels per texel (bake/maps.h)
  for (const MapInfo& m : mapTable())
    if (m.map != Map::Normal && options.maps.has(m.map)) extraChannels += m.memoryChannels;
  // Thickness and curvature may keep per-vertex tables of the high poly (trace.h,
  // VertexCache: ~40 bytes a triangle while they are built), about 1.5× a binary PLY's bytes.
  const double vertexTables = options.maps.needs(kInwardRays | kCurvatureRays) ? 1.5 * inputBytes : 0.0;
  // A bake that may trace on the GPU (--device auto or gpu) holds a wave's samples at once
  // (trace.h, traceWave: at most 2^18 of them, ~128 MiB), the GL context and its batch
  // buffers (~56 MiB), and the GPU's copy of the hierarchy (raytrace/bvh.h) while it is
  // uploaded, or for good on a software renderer: about as much again as the meshes'.
  // Measured: the 262k-triangle studded torus at 2048² on llvmpipe, 357 MiB (the CPU: 146).
  const double gpu = options.device == Device::Cpu
                         ? 0.0
                         : detail::kWaveBytesPerSample *
                                   std::min(double(detail::waveSamples(options)), texels * double(options.samples)) +
                               56.0 * double(1 << 20) + 2.0 * inputBytes;
  return 64.0 + (2.0 * inputBytes + vertexTables + gpu + texels * (19.5 + 8.0 * extraChannels)) / (1 << 20);
}

nlohmann::ordered_json toJson(const BakeOptions& options) {
  nlohmann::ordered_json report = nlohmann::ordered_json::object();
  report["width"] = options.width;
  report["height"] = options.height;
  report["samples_per_texel"] = options.samples;
  report["space"] = spaceName(options.space);
  report["directx"] = options.directX;
  return report;
}

nlohmann::ordered_json toJson(const BakeStats& s) {
  nlohmann::ordered_json report = nlohmann::ordered_json::object();
  report["low_triangles"] = s.lowTriangles;
  report["high_triangles"] = s.highTriangles;
  report["texels"] = s.texels;
  report["covered_texels"] = s.coveredTexels;
  report["conservative_texels"] = s.conservativeTexels;
  report["padded_texels"] = s.paddedTexels;
  report["samples"] = s.samples;
  report["rays"] = s.rays;
  report["ao_rays"] = s.aoRays;
  report["thickness_rays"] = s.thicknessRays;
  report["curvature_rays"] = s.curvatureRays;
  report["vertex_measurements"] = s.vertexMeasurements;
  report["hits"] = s.hits;
  report["inward_hits"] = s.inwardHits;
  report["misses"] = s.misses;
  report["hit_ratio"] = s.hitRatio();
  report["max_front"] = s.frontDistance;
  report["max_rear"] = s.rearDistance;
  if (s.thicknessDistance > 0) report["thickness_distance"] = s.thicknessDistance;
  if (s.curvatureRadius > 0) report["curvature_radius"] = s.curvatureRadius;
  if (s.positionBounds) {
    const vec3 &lo = s.positionBounds->min, &hi = s.positionBounds->max;
    report["position_min"] = {lo.x, lo.y, lo.z};
    report["position_max"] = {hi.x, hi.y, hi.z};
  }
  report["rays_per_second"] = s.traceSeconds > 0 ? double(s.rays + s.aoRays + s.thicknessRays + s.curvatureRays) / s.traceSeconds : 0.0;
  report["bvh_mib"] = double(s.bvhBytes) / (1024.0 * 1024.0);
  report["bvh_quality"] = s.lowQualityBvh ? "low" : "medium";
  report["device"] = s.device;
  report["device_reason"] = s.deviceReason;
  if (!s.gpuRenderer.empty()) report["gpu_renderer"] = s.gpuRenderer;
  if (s.device == "gpu") {
    report["gpu_mib"] = double(s.gpuBytes) / (1024.0 * 1024.0);
    if (s.gpuFreeBytes) report["gpu_free_mib"] = double(s.gpuFreeBytes) / (1024.0 * 1024.0);
    report["gpu_dispatches"] = s.gpuDispatches;
    report["gpu_longest_dispatch_ms"] = s.gpuLongestDispatchMs;
  }
  if (s.bvhReused) report["bvh_reused"] = true;
  return report;
}

}  // namespace glint::bake
