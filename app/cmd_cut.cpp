// glint cut SCENE... -o OUT --light x,y,z — the shadow cutter: static shadows cut into the
// geometry. Thin: options → cut::CutOptions, files in and out, the report.
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/cut/cutter.h"
#include "glint/cut/output.h"
#include "glint/mesh/mesh.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

namespace glint::app {

namespace {

struct CutArgs {
  std::vector<std::string> inputs, outputs, lights, merge;
  std::string shard;
  ToolSettings tool;
};

/// "i/n" (1-based) → (i − 1, n).
std::pair<int, int> parseShard(const std::string& text) {
  int i = 0, n = 0;
  char slash = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &i, &slash, &n, &extra) != 3 || slash != '/' || n < 1 || i < 1 || i > n)
    fail(ErrorKind::Usage, "--shard must be i/n with 1 ≤ i ≤ n, got '{}'", text);
  return {i - 1, n};
}

constexpr const char* kFooter = R"(How it works (ATI's "Pipe Dream" shadow cutting, seed 001):
  A beam is "a pyramid-shaped volume": from the light through a polygon, bounded by
  three planes through the light and the polygon's edges, and by the polygon's own
  plane. The part between the light and the polygon is its near beam; the part beyond
  it, its far beam. "For every polygon in our scene one at a time we're going to dice
  it up": for polygon A, every polygon B in A's near beam takes "its far beam and cut[s]
  into" A "with those three planes" (and its own), and each resulting piece is tagged
  "as in or out of light". Pieces of one polygon with the same tags are merged back
  ("an optimization step"). With several lights every piece carries a light mask: bit l
  is set when light l reaches it, so a renderer can draw shadowed pieces with a cheaper
  shader and write how many lights already shadow them (the destination-alpha dim).

  glint decides every cut exactly (the original planes of B and the light, exact
  arithmetic), so overlapping, touching, coplanar and cyclically overlapping polygons
  ("the root of all evil") come out right, and a watertight input stays watertight.

Outputs (one or more -o): .glb/.gltf (one primitive per light mask, the mask in its
extras, grey vertex colours, the lights as KHR_lights_punctual) and .ply (the convex
polygons with per-face light_mask, source triangle and colour).

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

}  // namespace

Command cutCommand(CLI::App& app, const GlobalOptions& global) {
  auto a = std::make_shared<CutArgs>();
  auto* cmd = app.add_subcommand("cut", "Cut static shadows into geometry: pieces tagged with the lights that reach them");
  cmd->footer(kFooter);
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
    if (!a->shard.empty() && !a->merge.empty()) fail(ErrorKind::Usage, "--shard and --merge do not go together");
    std::optional<std::pair<int, int>> shard;
    if (!a->shard.empty()) {
      shard = parseShard(a->shard);
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
      for (const auto& input : a->inputs) {
        const Mesh part = loadMesh(input);
        if (scene.positions.empty()) scene = part;
        else scene.append(part);
        if (a->lights.empty() && a->merge.empty())
          for (cut::Light& l : cut::loadGltfLights(input)) options.lights.push_back(std::move(l));
      }
    }
    if (options.lights.empty() && a->merge.empty())
      fail(ErrorKind::Usage, "no lights: give --light x,y,z (or a glTF scene with KHR_lights_punctual lights)");
    run.throwIfInterrupted();
    // Peak memory, measured on the machine-room scene with two lights (9.4k → 1.01M → 2.03M
    // triangles: 206 → 1,369 → 2,602 MiB): ~200 MiB, and ~0.65 KB per input triangle plus
    // ~0.3 KB per triangle and light (beams, pieces, output).
    run.checkMemory(200.0 + double(scene.triangleCount()) * (650.0 + 300.0 * double(std::max<std::size_t>(options.lights.size(), 2))) / (1 << 20),
                    fmt::format("cutting {} triangles for {} light(s)", scene.triangleCount(), options.lights.size()));

    auto& report = run.report();
    report["inputs"] = a->inputs;
    nlohmann::ordered_json lights = nlohmann::ordered_json::array();
    for (const auto& l : options.lights) lights.push_back({{"name", l.name}, {"position", {l.position.x, l.position.y, l.position.z}}});
    report["lights"] = lights;

    if (shard) {
      options.shardIndex = shard->first;
      options.shardCount = shard->second;
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
      report["input_triangles"] = part.stats.inputTriangles;
      report["receivers"] = part.stats.receivers;
      report["clipped_pairs"] = part.stats.clippedPairs;
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
      if (!a->lights.empty()) {
        const auto& theirs = shards.front().lights;
        bool same = theirs.size() == options.lights.size();
        for (std::size_t i = 0; same && i < theirs.size(); ++i) same = theirs[i].position == options.lights[i].position;
        if (!same) fail(ErrorKind::Usage, "--light differs from the lights the shards were cut with (leave it out to use theirs)");
      }
      options.lights = shards.front().lights;
      result = cut::mergeShards(scene, std::move(shards), options);
    } else {
      result = cut::cut(scene, options);
    }
    const cut::CutStats& s = result.stats;
    run.addSeconds("prepare", s.prepareSeconds);
    run.addSeconds("cut", s.cutSeconds);
    run.addSeconds("assemble", s.assembleSeconds);
    for (const auto& w : result.warnings) run.recordWarning(w);
    {
      auto timed = run.phase("write");
      for (const auto& o : a->outputs) cut::saveCutMesh(result.mesh, options.lights, o);
    }
    log::info("cut: {} triangles → {} polygons ({:.2f}×), {} lights, {} clipped pairs; {:.2f} s", s.inputTriangles,
              s.outputPolygons, double(s.outputPolygons) / double(std::max<std::uint64_t>(1, s.inputTriangles)),
              options.lights.size(), s.clippedPairs, run.elapsed());

    report["outputs"] = a->outputs;
    report["input_triangles"] = s.inputTriangles;
    report["output_polygons"] = s.outputPolygons;
    report["output_triangles"] = s.outputTriangles;
    report["output_vertices"] = s.outputVertices;
    report["polygons_per_input_triangle"] = double(s.outputPolygons) / double(std::max<std::uint64_t>(1, s.inputTriangles));
    report["pieces_before_merge"] = s.facesBeforeMerge;
    report["degenerate_triangles"] = s.degenerateTriangles;
    report["collapsed_triangles"] = s.collapsedTriangles;
    report["dropped_slivers"] = s.droppedSlivers;
    nlohmann::ordered_json perLight = nlohmann::ordered_json::array();
    for (const auto& l : s.lights)
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
    run.finish();
    return 0;
  }, .readsImages = false};
}

}  // namespace glint::app
