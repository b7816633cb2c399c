// glint cut SCENE... -o OUT --light x,y,z — the shadow cutter: static shadows cut into the
// geometry. Thin: options → cut::CutOptions, files in and out, the report.
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/text.h"
#include "glint/cut/cutter.h"
#include "glint/cut/output.h"
#include "glint/mesh/mesh.h"

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>

namespace glint::app {

namespace {

struct CutArgs {
  std::vector<std::string> inputs, outputs, lights, merge;
  std::string shard;
  ToolSettings tool;
};

constexpr const char* kCutFooter = R"(How it works (ATI's "Pipe Dream" shadow cutting, seed 001):
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
triangles, the lowest of them) and colour).

Lights: --light x,y,z[,name], repeatable (up to 32); without --light, the point lights
of the glTF inputs (KHR_lights_punctual) are used.

A farm: cut shard i of n on each machine, then merge (same scene and lights):
  glint cut stage.glb --light 0,9,2 --shard 1/4 -o part1.shard      (and 2/4, 3/4, 4/4)
  glint cut stage.glb --light 0,9,2 --merge part1.shard part2.shard part3.shard part4.shard -o stage_cut.glb

Examples:
  glint cut room.glb -o room_cut.glb --light 0,4,0,lamp
  glint cut walls.obj pipes.ply -o cut.ply -o cut.glb --light 3,8,2,key --light -4,5,1,fill --json report.json

Exit status: 0 done, 2 bad option, 3 unreadable/unsuitable input, 4 output not
writable, 130 interrupted (Ctrl-C; no partial file is left).)";

/// One warning for the triangles whose plane contains a light, with their count per light;
/// empty when there are none.
std::string grazingWarning(const cut::CutStats& s) {
  std::uint64_t total = 0;
  std::string perLight;
  for (const cut::LightStats& l : s.lights) {
    if (l.grazingTriangles == 0) continue;
    total += l.grazingTriangles;
    perLight += fmt::format("{}{} for '{}'", perLight.empty() ? "" : ", ", l.grazingTriangles, printable(l.name));
  }
  if (total == 0) return {};
  return fmt::format("{} triangle{} graze{} a light ({}): the light lies in their plane, so none of its light reaches "
                     "them and they are tagged as shadowed for it",
                     total, total == 1 ? "" : "s", total == 1 ? "s" : "", perLight);
}

}  // namespace

Command cutCommand(CLI::App& app, const GlobalOptions& global) {
  auto a = std::make_shared<CutArgs>();
  auto* cmd = app.add_subcommand("cut", "Cut static shadows into geometry: pieces tagged with the lights that reach them");
  cmd->footer(kCutFooter);
  cmd->add_option("scene", a->inputs, "Static geometry: one or more mesh files (OBJ, PLY, glTF/GLB, FBX, ...), joined")
      ->required();
  cmd->add_option("-o,--output", a->outputs, "Output: .glb, .gltf or .ply (repeat for several); with --shard, the shard file")
      ->required();
  cmd->add_option("--light", a->lights, "Point light x,y,z[,name]; repeat for several");
  cmd->add_option("--shard", a->shard, "Cut only shard i of n (i/n, receivers grouped by region) into the -o file");
  cmd->add_option("--merge", a->merge, "Join shard files (all n of one job) into the outputs instead of cutting");
  addToolOptions(*cmd, a->tool, "triangles in and polygons out, counts and areas per light, clipped pairs, predicates");

  return Command{.run = [a, &global] {
    (void)global;
    ToolRun run("cut", a->tool);
    // No output may be an input or another output (by file identity: core/file.h).
    {
      std::vector<FileUse> in, out;
      for (const auto& path : a->inputs) in.push_back({path, "the input"});
      for (const auto& path : a->merge) in.push_back({path, "the shard"});
      for (const auto& path : a->outputs) out.push_back({path, a->shard.empty() ? "-o" : "the shard file (-o)"});
      out.push_back({a->tool.json, "--json"});
      checkDistinctFiles(in, out);
    }
    if (!a->shard.empty() && !a->merge.empty()) fail(ErrorKind::Usage, "--shard and --merge do not go together");
    std::optional<ShardSpec> shard;
    if (!a->shard.empty()) {
      shard = parseShard(a->shard, "--shard");
      if (a->outputs.size() != 1) fail(ErrorKind::Usage, "--shard writes one shard file: give one -o");
    } else {
      for (const auto& o : a->outputs) cut::checkOutputFormat(o);
    }
    cut::CutOptions options;
    for (const auto& l : a->lights) options.lights.push_back(cut::parseLight(l));
    std::vector<std::string> outputs = a->outputs;
    if (!a->tool.json.empty() && a->tool.json != "-") outputs.push_back(a->tool.json);
    for (const auto& path : outputs) checkWritable(path);
    options.progress = run.showProgress();
    options.cancel = &run.cancelFlag();

    Mesh scene;
    {
      auto timed = run.phase("load");
      // The mesh loader logs its warnings itself: they go in the report as well.
      log::WarningCapture loaderWarnings;
      // Without --light, the glTF inputs' lights (not when merging: the shards carry theirs).
      const bool gltfLights = a->lights.empty() && a->merge.empty();
      scene = cut::loadScene(std::vector<std::filesystem::path>(a->inputs.begin(), a->inputs.end()),
                             gltfLights ? &options.lights : nullptr);
      for (const auto& w : loaderWarnings.take()) run.recordWarning(w);
    }
    if (options.lights.empty() && a->merge.empty())
      fail(ErrorKind::Usage, "no lights: give --light x,y,z (or a glTF scene with KHR_lights_punctual lights)");
    run.throwIfInterrupted();
    run.checkMemory(cut::estimatePeakMemoryMiB(scene.triangleCount(), options.lights.size(), run.threads()),
                    fmt::format("cutting {} triangles for {} light(s)", scene.triangleCount(), options.lights.size()));

    auto& report = run.report();
    report["inputs"] = a->inputs;
    report["lights"] = cut::toJson(options.lights);

    if (shard) {
      options.shardIndex = shard->index - 1;
      options.shardCount = shard->count;
      const cut::Shard part = cut::cutShard(scene, options);
      run.addSeconds("prepare", part.stats.prepareSeconds);
      run.addSeconds("cut", part.stats.cutSeconds);
      for (const auto& w : part.warnings) run.recordWarning(w);
      {
        auto timed = run.phase("write");
        cut::saveShard(part, a->outputs.front());
      }
      report["shard"] = a->shard;
      report["output"] = a->outputs.front();
      report.update(cut::toJson(part));
      log::info("cut: shard {} ({} of {} triangles) → {} in {:.2f} s", a->shard, part.stats.receivers,
                part.stats.inputTriangles, a->outputs.front(), run.elapsed());
      run.finish();
      return 0;
    }

    cut::CutResult result;
    if (!a->merge.empty()) {
      std::vector<cut::Shard> shards;
      {
        auto timed = run.phase("read shards");
        for (const auto& path : a->merge) shards.push_back(cut::loadShard(path));
      }
      result = cut::mergeShards(scene, std::move(shards), options);  // checks --light against the shards'
    } else {
      result = cut::cut(scene, options);
    }
    const cut::CutStats& s = result.stats;
    run.addSeconds("prepare", s.prepareSeconds);
    run.addSeconds("cut", s.cutSeconds);
    run.addSeconds("assemble", s.assembleSeconds);
    for (const auto& w : result.warnings) run.recordWarning(w);
    if (const std::string grazing = grazingWarning(s); !grazing.empty()) run.warn(grazing);
    {
      auto timed = run.phase("write");
      for (const auto& o : a->outputs) cut::saveCutMesh(result.mesh, result.lights, o);
    }
    log::info("cut: {} triangles → {} polygons ({:.2f}×), {} lights, {} clipped pairs; {:.2f} s", s.inputTriangles,
              s.outputPolygons, double(s.outputPolygons) / double(std::max<std::uint64_t>(1, s.inputTriangles)),
              result.lights.size(), s.clippedPairs, run.elapsed());

    report["outputs"] = a->outputs;
    report.update(cut::toJson(s));
    run.finish();
    return 0;
  }, .readsImages = false};
}

}  // namespace glint::app
