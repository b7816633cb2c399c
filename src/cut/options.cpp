// glint cut's options (cut/job.h): the command line the command, `glint farm cut` and the
// Python module bind, its help footer, and a job back as arguments (what a farm piece runs).
#include "glint/cut/job.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace glint::cut {

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

}  // namespace glint::cut
