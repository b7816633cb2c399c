// glint cut's job (cut/job.h): the checks a cut makes before it reads an input, and the run
// (options.cpp has its options, farm_plan.cpp its farm plan).
#include "glint/cut/job.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/options.h"
#include "glint/core/text.h"
#include "glint/cut/cutter.h"
#include "glint/cut/output.h"
#include "glint/mesh/mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>

namespace glint::cut {

namespace fs = std::filesystem;

namespace {



/// One warning for the triangles whose plane contains a light, with their count per light;
/// empty when there are none.
std::string grazingWarning(const CutStats& s) {
  std::uint64_t total = 0;
  std::string perLight;
  for (const LightStats& l : s.lights) {
    if (l.grazingTriangles == 0) continue;
    total += l.grazingTriangles;
    perLight += fmt::format("{}{} for '{}'", perLight.empty() ? "" : ", ", l.grazingTriangles, printable(l.name));
  }
  if (total == 0) return {};
  return fmt::format("{} triangle{} graze{} a light ({}): the light lies in their plane, so none of its light reaches "
                     "them and they are tagged as shadowed for it",
                     total, total == 1 ? "" : "s", total == 1 ? "s" : "", perLight);
}

std::vector<fs::path> paths(const std::vector<std::string>& texts) { return {texts.begin(), texts.end()}; }

}  // namespace

void checkJob(const CutJob& job, const ToolSettings& settings) {
  // No output may be an input or another output (by file identity: core/file.h).
  std::vector<FileUse> in, out;
  for (const auto& path : job.inputs) in.push_back({path, "the input"});
  for (const auto& path : job.merge) in.push_back({path, "the shard"});
  for (const auto& path : job.outputs) out.push_back({path, job.shard.empty() ? "-o" : "the shard file (-o)"});
  out.push_back({settings.json, "--json"});
  checkDistinctFiles(in, out);
  if (job.inputs.empty()) fail(ErrorKind::Usage, "cut: give the scene's files");
  if (job.outputs.empty()) fail(ErrorKind::Usage, "cut: give -o OUTPUT");
  if (!job.shard.empty() && !job.merge.empty()) fail(ErrorKind::Usage, "--shard and --merge do not go together");
  if (!job.shard.empty()) {
    (void)parseShard(job.shard, "--shard");
    if (job.outputs.size() != 1) fail(ErrorKind::Usage, "--shard writes one shard file: give one -o");
  } else {
    for (const auto& o : job.outputs) checkOutputFormat(o);
  }
  for (const auto& l : job.lights) (void)parseLight(l);
  std::vector<std::string> outputs = job.outputs;
  if (!settings.json.empty() && settings.json != "-") outputs.push_back(settings.json);
  for (const auto& path : outputs) checkWritable(path);
}

void runJob(const CutJob& job, ToolRun& run) {
  checkJob(job, run.settings());
  CutOptions options;
  for (const auto& l : job.lights) options.lights.push_back(parseLight(l));
  options.progress = run.showProgress();
  options.cancel = &run.cancelFlag();

  Mesh scene;
  {
    auto timed = run.phase("load");
    // The mesh loader logs its warnings itself: they go in the report as well.
    log::WarningCapture loaderWarnings;
    // Without --light, the glTF inputs' lights (not when merging: the shards carry theirs).
    const bool gltfLights = job.lights.empty() && job.merge.empty();
    scene = loadScene(paths(job.inputs), gltfLights ? &options.lights : nullptr);
    for (const auto& w : loaderWarnings.take()) run.recordWarning(w);
  }
  if (options.lights.empty() && job.merge.empty())
    fail(ErrorKind::Usage, "no lights: give --light x,y,z (or a glTF scene with KHR_lights_punctual lights)");
  run.throwIfInterrupted();
  run.checkMemory(estimatePeakMemoryMiB(scene.triangleCount(), options.lights.size(), run.threads()),
                  fmt::format("cutting {} triangles for {} light(s)", scene.triangleCount(), options.lights.size()));

  auto& report = run.report();
  report["inputs"] = job.inputs;
  report["lights"] = toJson(options.lights);

  if (!job.shard.empty()) {
    const ShardSpec shard = parseShard(job.shard, "--shard");
    options.shardIndex = shard.index - 1;
    options.shardCount = shard.count;
    const Shard part = cutShard(scene, options);
    run.addSeconds("prepare", part.stats.prepareSeconds);
    run.addSeconds("cut", part.stats.cutSeconds);
    for (const auto& w : part.warnings) run.recordWarning(w);
    {
      auto timed = run.phase("write");
      saveShard(part, job.outputs.front());
    }
    report["shard"] = job.shard;
    report["output"] = job.outputs.front();
    report.update(toJson(part));
    log::info("cut: shard {} ({} of {} triangles) → {} in {:.2f} s", job.shard, part.stats.receivers,
              part.stats.inputTriangles, job.outputs.front(), run.elapsed());
    return;
  }

  CutResult result;
  if (!job.merge.empty()) {
    std::vector<Shard> shards;
    {
      auto timed = run.phase("read shards");
      for (const auto& path : job.merge) shards.push_back(loadShard(path));
    }
    result = mergeShards(scene, std::move(shards), options);  // checks --light against the shards'
  } else {
    result = cut(scene, options);
  }
  const CutStats& s = result.stats;
  run.addSeconds("prepare", s.prepareSeconds);
  run.addSeconds("cut", s.cutSeconds);
  run.addSeconds("assemble", s.assembleSeconds);
  for (const auto& w : result.warnings) run.recordWarning(w);
  if (const std::string grazing = grazingWarning(s); !grazing.empty()) run.warn(grazing);
  {
    auto timed = run.phase("write");
    for (const auto& o : job.outputs) saveCutMesh(result.mesh, result.lights, o);  // staged: all or none
  }
  log::info("cut: {} triangles → {} polygons ({:.2f}×), {} lights, {} clipped pairs; {:.2f} s", s.inputTriangles,
            s.outputPolygons, double(s.outputPolygons) / double(std::max<std::uint64_t>(1, s.inputTriangles)),
            result.lights.size(), s.clippedPairs, run.elapsed());
  report["outputs"] = job.outputs;
  report.update(toJson(s));
}

}  // namespace glint::cut
