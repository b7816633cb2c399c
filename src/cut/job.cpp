// glint cut's job (cut/job.h): the command's options, checks and run, and its farm plan.
#include "glint/cut/job.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/options.h"
#include "glint/core/text.h"
#include "glint/cut/cutter.h"
#include "glint/cut/output.h"
#include "glint/mesh/mesh.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>

namespace glint::cut {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFooter = R"(How it works (ATI's "Pipe Dream" shadow cutting, WWDC 2003 session 212):
  A beam is "a pyramid-shaped volume": from the light through a polygon, bounded by
  three planes through the light and the polygon's edges, and by the polygon's own
  plane. The part between the light and the polygon is its near beam; the part beyond
  it, its far beam. "For every polygon in our scene one at a time we're going to dice
  it up": for polygon A, every polygon B in A's near beam takes "its far beam and cut[s]
  into" A "with those three planes" (and its own), and each resulting piece is tagged
  "as in or out of light". Pieces with the same tags are merged back ("an
  optimization step"), across triangles too where neighbours of one surface lie in one
  plane (a floor's grid, a box's face): only the corners where shadow outlines turn
  stay, so a floor of a thousand cells in one light is a handful of polygons. With several lights every piece carries a light mask: bit l
  is set when light l reaches it, so a renderer can draw shadowed pieces with a cheaper
  shader and write how many lights already shadow them (the destination-alpha dim).

  glint decides every cut exactly (the original planes of B and the light, exact
  arithmetic), so overlapping, touching, coplanar and cyclically overlapping polygons
  ("the root of all evil") come out right, and a watertight input stays watertight.

Outputs (one or more -o): .glb/.gltf (one primitive per light mask, the mask in its
extras, grey vertex colours, the lights as KHR_lights_punctual) and .ply (the convex
polygons with per-face light_mask, source triangle (for pieces merged across coplanar
triangles, the lowest of them) and colour). All of them are written, or none: a run that
fails at its last output (a full disk) leaves the earlier ones as they were.

Lights: --light x,y,z[,name], repeatable (up to 32); without --light, the point lights
of the glTF inputs (KHR_lights_punctual) are used.

A farm: cut shard i of n on each machine, then merge (same scene and lights):
  glint cut stage.glb --light 0,9,2 --shard 1/4 -o part1.shard      (and 2/4, 3/4, 4/4)
  glint cut stage.glb --light 0,9,2 --merge part1.shard part2.shard part3.shard part4.shard -o stage_cut.glb
or `glint farm cut stage.glb -o stage_cut.glb --light 0,9,2 --shards 4` on a Slurm cluster.

Examples:
  glint cut room.glb -o room_cut.glb --light 0,4,0,lamp
  glint cut walls.obj pipes.ply -o cut.ply -o cut.glb --light 3,8,2,key --light -4,5,1,fill --json report.json

Exit status: 0 done, 2 bad option, 3 unreadable/unsuitable input, 4 output not
writable (a full disk: "no space left on device"), 6 out of memory, 130 interrupted
(Ctrl-C; no partial file is left).)";

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

void addOptions(CLI::App& cmd, CutJob& job) {
  cmd.add_option("scene", job.inputs, "Static geometry: one or more mesh files (OBJ, PLY, glTF/GLB, FBX, ...), joined")
      ->required();
  cmd.add_option("-o,--output", job.outputs, "Output: .glb, .gltf or .ply (repeat for several; all are written or none); "
                                             "with --shard, the shard file")
      ->required();
  cmd.add_option("--light", job.lights, "Point light x,y,z[,name]; repeat for several");
  cmd.add_option("--shard", job.shard, "Cut only shard i of n (i/n, receivers grouped by region) into the -o file");
  cmd.add_option("--merge", job.merge, "Join shard files (all n of one job) into the outputs instead of cutting");
}

const char* helpFooter() { return kFooter; }

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

std::vector<std::string> arguments(const CutJob& job) {
  std::vector<std::string> argv = job.inputs;
  for (const auto& o : job.outputs) argv.insert(argv.end(), {"-o", o});
  for (const auto& l : job.lights) argv.insert(argv.end(), {"--light", l});
  if (!job.shard.empty()) argv.insert(argv.end(), {"--shard", job.shard});
  if (!job.merge.empty()) {
    argv.push_back("--merge");
    argv.insert(argv.end(), job.merge.begin(), job.merge.end());
  }
  return argv;
}

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
  const Mesh scene = loadScene(paths(job.inputs), &gltfLights);
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
    p.inputs = paths(job.inputs);
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
