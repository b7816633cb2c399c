// `glint farm cut` (cut/job.h): shard i of n on each machine (receivers grouped by region),
// then the merge, every piece a plain glint call.
#include "glint/cut/job.h"

#include "glint/core/error.h"
#include "glint/cut/cutter.h"
#include "glint/cut/output.h"
#include "glint/mesh/mesh.h"

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace glint::cut {

namespace fs = std::filesystem;

farm::Plan farmPlan(const CutJob& given, const ToolSettings& settings, const farm::Split& split) {
  if (!given.shard.empty() || !given.merge.empty())
    fail(ErrorKind::Usage, "farm cut: --shard and --merge are what the farm runs; give --shards N");
  checkJob(given, settings);
  CutJob job = given;
  for (auto& p : job.inputs) p = farm::absolutePath(p);
  for (auto& p : job.outputs) p = farm::absolutePath(p);
  farm::Plan plan{.tool = "cut"};
  plan.title = fmt::format("{} → {}", fs::path(job.inputs.front()).filename().string(),
                           fs::path(job.outputs.front()).filename().string());
  for (const auto& o : job.outputs) plan.outputs.push_back(o);
  // The estimate of the whole job (every shard loads the whole scene).
  std::vector<Light> gltfLights;
  const std::vector<fs::path> inputs(job.inputs.begin(), job.inputs.end());
  const Mesh scene = loadScene(inputs, &gltfLights);
  const std::size_t lightCount = job.lights.empty() ? gltfLights.size() : job.lights.size();
  if (lightCount == 0)
    fail(ErrorKind::Usage, "no lights: give --light x,y,z (or a glTF scene with KHR_lights_punctual lights)");
  plan.memoryMiB = farm::taskMemoryMiB(split, estimatePeakMemoryMiB(scene.triangleCount(), lightCount, split.cpusPerTask));
  const std::vector<std::string> limits = farm::pieceSettings(settings, split, plan.memoryMiB);
  for (int i = 1; i <= split.pieces; ++i) {
    CutJob piece = job;
    piece.outputs = {farm::kPieceOutput};
    piece.shard = fmt::format("{}/{}", i, split.pieces);
    farm::Piece p{.label = fmt::format("shard {}/{}", i, split.pieces), .command = {"cut"}, .extension = ".shard"};
    const auto args = arguments(piece);
    p.command.insert(p.command.end(), args.begin(), args.end());
    p.command.insert(p.command.end(), limits.begin(), limits.end());
    p.inputs = inputs;
    plan.pieces.push_back(std::move(p));
  }
  CutJob join = job;
  join.merge = {farm::kAllPieceOutputs};
  plan.join = {"cut"};
  const auto args = arguments(join);
  plan.join.insert(plan.join.end(), args.begin(), args.end());
  plan.join.insert(plan.join.end(), limits.begin(), limits.end());
  if (!settings.json.empty()) plan.join.insert(plan.join.end(), {"--json", farm::absolutePath(settings.json)});
  if (!settings.json.empty() && settings.json != "-") plan.outputs.push_back(farm::absolutePath(settings.json));
  return plan;
}

}  // namespace glint::cut
