// What a cut job needs and what it reports: the memory estimate and the JSON fields of
// `glint cut --json` (core/tool.h adds the fields every tool shares).
#include "glint/cut/cutter.h"

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace glint::cut {

double estimatePeakMemoryMiB(std::uint64_t triangles, std::size_t lights, int threads) {
  // Fitted to measured peaks (docs/cut.md, "Memory"); each term a little above them.
  constexpr double kMiB = 1 << 20;
  const double n = double(triangles), l = double(std::max<std::size_t>(lights, 1));
  if (threads <= 0) threads = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  const double perThread = std::min(4.0 + 6.0 * l, 2048.0 * n * l / kMiB);
  return 28.0 + double(threads) * perThread + n * (700.0 + 400.0 * l) / kMiB;
}

nlohmann::ordered_json toJson(const std::vector<Light>& lights) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const Light& l : lights) out.push_back({{"name", l.name}, {"position", {l.position.x, l.position.y, l.position.z}}});
  return out;
}

nlohmann::ordered_json toJson(const CutStats& s) {
  nlohmann::ordered_json report = nlohmann::ordered_json::object();
  report["input_triangles"] = s.inputTriangles;
  report["output_polygons"] = s.outputPolygons;
  report["output_triangles"] = s.outputTriangles;
  report["output_vertices"] = s.outputVertices;
  report["polygons_per_input_triangle"] = double(s.outputPolygons) / double(std::max<std::uint64_t>(1, s.inputTriangles));
  report["triangles_per_input_triangle"] = double(s.outputTriangles) / double(std::max<std::uint64_t>(1, s.inputTriangles));
  report["pieces_before_merge"] = s.facesBeforeMerge;
  report["merged_patches"] = s.mergedPatches;
  report["degenerate_triangles"] = s.degenerateTriangles;
  report["collapsed_triangles"] = s.collapsedTriangles;
  report["dropped_slivers"] = s.droppedSlivers;
  nlohmann::ordered_json perLight = nlohmann::ordered_json::array();
  for (const LightStats& l : s.lights)
    perLight.push_back({{"name", l.name},
                        {"lit_polygons", l.litPolygons},
                        {"shadowed_polygons", l.shadowedPolygons},
                        {"lit_area", l.litArea},
                        {"shadowed_area", l.shadowedArea},
                        {"grazing_triangles", l.grazingTriangles}});
  report["per_light"] = perLight;
  report["candidates"] = s.candidates;
  report["occluders"] = s.occluders;
  report["clipped_pairs"] = s.clippedPairs;
  report["cuts"] = s.cuts;
  report["clipped_pairs_per_second"] = s.cutSeconds > 0 ? double(s.clippedPairs) / s.cutSeconds : 0.0;
  report["predicates"] = {{"symbolic", s.symbolicPredicates}, {"interval", s.filteredPredicates}, {"exact", s.exactPredicates}};
  return report;
}

nlohmann::ordered_json toJson(const Shard& shard) {
  nlohmann::ordered_json report = nlohmann::ordered_json::object();
  report["input_triangles"] = shard.stats.inputTriangles;
  report["receivers"] = shard.stats.receivers;
  report["clipped_pairs"] = shard.stats.clippedPairs;
  return report;
}

}  // namespace glint::cut
