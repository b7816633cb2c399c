// glint bake's options (bake/job.h): the command line the command, `glint farm bake`, batch
// files and the Python module bind (addOptions), its help footer, the options as data
// (describe: what the Blender add-on builds its controls from), and the one translation of
// a job's options into the baker's (optionsOf).
#include "glint/bake/job.h"

#include "glint/bake/baker.h"
#include "glint/bake/maps.h"
#include "glint/core/error.h"
#include "glint/core/options.h"
#include "glint/core/text.h"
#include "job_internal.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <sstream>
#include <string>
#include <vector>

namespace glint::bake {

using Json = nlohmann::ordered_json;

namespace {

/// "5%" → 5 % of the low poly's diagonal; "0.2" → 0.2 scene units.
Distance parseDistance(const std::string& text, const char* option) {
  std::string number = text;
  const bool relative = !number.empty() && number.back() == '%';
  if (relative) number.pop_back();
  float value = -1.0f;
  try {
    value = parseFloat(number, option);  // the whole text, finite, no locale
  } catch (const Error&) {
    value = -1.0f;
  }
  if (!(value >= 0.0f)) {
    fail(ErrorKind::Usage, "{} must be a distance like 0.2 (scene units) or 5% (of the low poly's size), got '{}'",
         option, text);
  }
  return {relative ? value / 100.0f : value, relative};
}

mat4 parseMatrix(const std::string& text) {
  std::vector<float> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    v.push_back(parseFloat(item, "--world-matrix"));
  }
  if (v.size() != 16) fail(ErrorKind::Usage, "--world-matrix needs 16 comma-separated numbers (row by row), got {}", v.size());
  mat4 m;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) m[col][row] = v[std::size_t(row * 4 + col)];
  return m;
}

constexpr const char* kFooter = R"(UDIM: a low poly whose UVs reach past the unit square (u in 0..10, v >= 0) bakes one map
per tile: name every map with <UDIM> where the tile number goes, e.g. -o normal.<UDIM>.png
--ao ao.<UDIM>.png writes normal.1001.png, normal.1002.png, ... (one bake, every tile).

Examples:
  glint bake car_low.obj car_high.ply -o car_normal.png
  glint bake head_low.fbx head_high.fbx -o head.png --size 2048x2048 --samples 36 \
        --height-detail pores.png --detail-scale 4 --ao head_ao.png --json report.json
  glint bake rock_low.obj rock_high.ply -o n.png --ao ao.png --bent-normal bent.png \
        --thickness thick.png --curvature curv.png --position pos.exr \
        --opacity alpha.png                                            # every map, one pass
  glint bake --batch jobs.json          # every job of a batch file, one after another
  glint bake --batch jobs.json --job 3  # job 3 only (0-based), as a render-farm task runs it
  glint bake --batch jobs.json --list   # the jobs as `glint bake ...` command lines

Batch files (JSON; relative paths are relative to the file; docs/bake.md, "Batches"):
  {"defaults": {"size": "1024x1024", "samples": 4, "max-front": "2%"},
   "bakes": [{"low": "crate_low.obj", "high": "crate_high.ply", "output": "crate_n.png",
              "ao": "crate_ao.png"},
             {"low": "barrel_low.obj", "high": "barrel_high.ply", "output": "barrel_n.png",
              "size": "2048x2048"}]}
  A key is an option's long name ("low", "high" and "output" for LOW, HIGH and -o); a
  flag is true or false. A job's key overrides the defaults; options given on the command
  line with --batch (e.g. --threads, -q, --samples) override both, for every job. Every job
  is checked before the first one runs; a failed job does not stop the others (the exit
  status is the first failure's); --json writes one report listing every job's.

)";

/// After the map list.
constexpr const char* kFooterAfterMaps = R"(
Bake groups (docs/bake.md, "Bake groups"): when the low file's parts are named
<name>_low, each bakes only against the high parts <name>_high and <name>_high_*, so
parts that touch or interpenetrate bake as if exploded. --low-suffix/--high-suffix
change the suffixes; unmatched parts are reported by name (low ones are not baked). A high
file without part names (a PLY) is baked against as one, with a warning; --no-groups bakes
without groups.

How it works: for every texel, rays start on the low poly (interpolated position) and
follow its interpolated normal forwards (--max-front) and backwards (--max-rear): the
low poly may be inside, outside or through the high poly. The hit's high-poly normal is
stored relative to the low poly's MikkTSpace tangent frame (the frame Blender, Unity,
Unreal, glTF and glint's renderer use), so the map decodes exactly where it is used.

Notes for artists:
  Shared normals   Rays follow the low poly's interpolated normals. At a hard edge (two
                   normals at one point) the rays fan apart and the high-poly detail in
                   the gap is never seen. Use smooth, shared normals on the low poly;
                   glint warns about hard edges. Or bake through a --cage.
  UV spacing       A normal map holds vectors, not colours: a texel that bleeds in from a
                   neighbouring island bends the lighting. Leave gaps between islands
                   (twice the padding at the smallest mip you use) and keep --padding on;
                   bilinear filtering and mipmaps read across island borders.
  Mirrored UVs     Fine in tangent space (the bitangent sign flips); overlapping UVs
                   share texels, so only one of the overlapping parts is baked.
  Micro detail     Model the big shapes, paint scars and pores into a height map and
                   combine them here (--height-detail): smooth ray-cast shape plus detail.

Every map of a bake is written, or none: a bake that fails at its last map (a full disk)
leaves the earlier ones as they were.

Exit status: 0 done, 2 bad option (or a bake estimated above --max-memory or, without it,
this machine's memory), 3 unreadable/unsuitable input, 4 output not writable (a full disk:
"no space left on device"), 6 out of memory, 130 interrupted (Ctrl-C; no partial file is
left).)";


}  // namespace

void addOptions(CLI::App& cmd, BakeJob& a, Meshes meshes) {
  if (meshes != Meshes::None) {
    CLI::Option* low = cmd.add_option("low", a.low, "Low-poly mesh: positions, normals, one UV set (OBJ, PLY, glTF/GLB, "
                                      "FBX, ...)")->type_name(kFile);
    CLI::Option* high = cmd.add_option("high", a.high, "High-poly mesh: positions and normals")->type_name(kFile);
    CLI::Option* output = cmd.add_option("-o,--output", a.output, mapInfo(Map::Normal).help)->type_name(kFile);
    if (meshes == Meshes::Required)
      for (CLI::Option* option : {low, high, output}) option->required();
  }
  cmd.add_option("--size", a.size, "Map size WIDTHxHEIGHT, any size")->capture_default_str();
  cmd.add_option("--samples", a.samples, fmt::format("Rays per texel, a square: 1, 4, 9, 16, ... {} (stratified √N×√N "
                 "grid, averaged; 36 is smooth)", kMaxSamples))->capture_default_str();
  cmd.add_option("--space", a.space, "tangent (MikkTSpace), object, or world (see --world-matrix)")
      ->check(CLI::IsMember({"tangent", "object", "world"}))->capture_default_str();
  cmd.add_option("--world-matrix", a.worldMatrix, "Object-to-world matrix for --space world: 16 numbers, row by row");
  cmd.add_flag("--directx", a.directX, "Flip green (DirectX/Unreal convention); the default is OpenGL's +Y");
  cmd.add_option("--bits", a.bits, "Bits per channel of the maps whose format has that depth: 8 or 16 for PNG/TIFF, 32 "
                 "for EXR (the others keep their own: 8 PNG/TGA, 16 TIFF, 32 float EXR)")
      ->check(CLI::IsMember({8, 16, 32}));
  cmd.add_option("--max-front", a.maxFront, "How far in front of the low poly rays look: 0.2 (scene units) or 5% "
                 "(of its bounding-box diagonal)")->capture_default_str();
  cmd.add_option("--max-rear", a.maxRear, "How far behind the low poly rays look (negative rays)")->capture_default_str();
  cmd.add_option("--device", a.device, "Where the rays are traced: auto (the GPU when its renderer is hardware and the "
                 "bake fits its memory, else the CPU; the report says which and why), cpu, or gpu (an error without "
                 "one; a software renderer such as llvmpipe counts)")
      ->check(CLI::IsMember({"auto", "cpu", "gpu"}))->capture_default_str();
  cmd.add_flag("--front-first", a.frontFirst, "Prefer hits in front of the low poly; default: the closest hit either way");
  cmd.add_option("--cage", a.cage, "Cage mesh: the low poly with vertices pushed outwards (same vertices and "
                 "triangles); rays then go from the cage inwards")->type_name(kFile);
  cmd.add_option("--padding", a.padding, "Texels of dilation around UV islands (0: none)")->capture_default_str();
  cmd.add_flag("--fill-all", a.fillAll, "Dilate until every texel is filled");
  cmd.add_option("--height-detail", a.detail, "Painted height map (scars, pores) combined with the baked normals; "
                 "tiled over the UVs")->type_name(kFile);
  cmd.add_option("--detail-scale", a.detailScale, "Bumpiness of --height-detail: the height of its 0..1 range in "
                 "texel widths (8: a black-to-white ramp over 8 texels is 45°; negative engraves)")->capture_default_str();
  cmd.add_option("--ao-samples", a.aoSamples, "AO rays per sample (bent normals share them; thickness casts as many "
                 "into the surface)")->capture_default_str();
  cmd.add_option("--ao-distance", a.aoDistance, "AO ray length: scene units or % of the low poly's diagonal")
      ->capture_default_str();
  cmd.add_option("--thickness-distance", a.thicknessDistance, "Thickness ray length, the distance that reads 1: scene "
                 "units or % of the low poly's diagonal")->capture_default_str();
  cmd.add_option("--curvature-radius", a.curvatureRadius, "The scale curvature is measured at (detail smaller is "
                 "averaged away; a bend this tight reads white/black in 8/16-bit): scene units or % of the low poly's "
                 "diagonal")->capture_default_str();
  // Every other map: one option each, from the table (bake/maps.h).
  for (const MapInfo& m : mapTable()) {
    if (m.map == Map::Normal) continue;
    cmd.add_option(std::string("--") + m.name, a.maps[std::size_t(m.map)], m.help)->type_name(kFile);
  }
  cmd.add_option("--asset", a.asset, "The low poly with its maps as a glTF asset (.glb, or .gltf with everything "
                 "inside): MikkTSpace tangents, the normal map (OpenGL +Y) and AO wired into a PBR material, the "
                 "other maps as images named in its extras; one material per UDIM tile or bake group")
      ->type_name(kFile);
  cmd.add_option("--preview", a.preview, "A folder for a web page that shows the bake on its model (orbit, a "
                 "toggle per map); opens offline, from disk or any web server")->type_name("DIR");
  cmd.add_option("--low-suffix", a.lowSuffix, "Bake groups: low parts are named <group><suffix>")->capture_default_str();
  cmd.add_option("--high-suffix", a.highSuffix, "Bake groups: high parts are named <group><suffix> or "
                 "<group><suffix>_*")->capture_default_str();
  cmd.add_flag("--no-groups", a.noGroups, "Bake the low poly as one, even when its parts are named <group>_low");
  addToolOptions(cmd, a.tool, "texels, rays, hit ratio, misses, BVH size");
  cmd.get_option("--json")->type_name(kFile);
}


nlohmann::ordered_json describe() {
  BakeJob job;
  CLI::App app;
  addOptions(app, job, Meshes::Optional);
  Json options = Json::object();
  for (const CLI::Option* option : app.get_options()) {
    if (option == app.get_help_ptr()) continue;
    const std::string& name = option->get_single_name();
    Json entry = {{"help", option->get_description()}};
    if (option->get_expected_max() == 0) {
      entry["kind"] = "flag";
    } else {
      entry["kind"] = option->get_type_name() == kFile ? "file" : "value";
      if (!option->get_default_str().empty()) entry["default"] = option->get_default_str();
    }
    options[name] = std::move(entry);
  }
  Json maps = Json::array();
  for (const MapInfo& m : mapTable()) {
    std::string label = m.reportKey;
    std::replace(label.begin(), label.end(), '_', ' ');
    label[0] = char(std::toupper(static_cast<unsigned char>(label[0])));
    if (m.map == Map::Ao) label = "AO";
    else if (m.map == Map::MaterialId) label = "Material ID";
    maps.push_back({{"name", m.reportKey}, {"option", m.name}, {"label", label}, {"help", m.help}, {"summary", m.summary},
                    {"channels", m.channels}, {"colour", isColourMap(m.map)},
                    // Read from the hit triangle's part (its material, its vertex colours): a
                    // mesh made from arrays (glint.Mesh) has no parts to read.
                    {"parts", (m.work & kHitTriangle) != 0}});
  }
  Json samples = sampleCounts();
  return {{"version", ToolRun::version()},
          {"maps", std::move(maps)},
          {"options", std::move(options)},
          {"samples", std::move(samples)},
          {"size", {{"min", 1}, {"max", kMaxImageSide}}},
          {"ao_samples", {{"min", 1}, {"max", kMaxAoSamples}}}};
}

std::string helpFooter() {
  // The map list from the table (bake/maps.h): an option, then what a texel holds.
  std::string maps = "Maps (each its own file, baked in the same pass as the normal map; docs/bake.md, \"Maps\"):\n";
  for (const MapInfo& m : mapTable()) {
    const std::string option = m.map == Map::Normal ? std::string("-o") : std::string("--") + m.name;
    maps += fmt::format("  {:<14} {}\n", option, m.summary);
  }
  return std::string(kFooter) + maps + kFooterAfterMaps;
}

MapSet mapsOf(const BakeJob& job) {
  MapSet maps;
  for (const MapInfo& m : mapTable())
    if (m.map != Map::Normal && !job.path(m.map).empty()) maps.add(m.map);
  return maps;
}

BakeOptions optionsOf(const BakeJob& a) {
  BakeOptions options;
  const ivec2 size = parseSize(a.size);
  options.width = size.x;
  options.height = size.y;
  options.samples = a.samples;
  options.space = a.space == "object" ? NormalSpace::Object
                : a.space == "world"  ? NormalSpace::World
                                      : NormalSpace::Tangent;
  if (!a.worldMatrix.empty()) options.objectToWorld = parseMatrix(a.worldMatrix);
  options.directX = a.directX;
  options.maxFront = parseDistance(a.maxFront, "--max-front");
  options.maxRear = parseDistance(a.maxRear, "--max-rear");
  options.selection = a.frontFirst ? HitSelection::FrontFirst : HitSelection::Closest;
  options.padding = a.padding;
  options.fillAll = a.fillAll;
  options.maps = mapsOf(a);
  // An asset always carries the miss mask: glint view shows where the rays missed.
  if (!a.asset.empty() || !a.preview.empty()) options.maps.add(Map::MissMask);
  options.aoSamples = a.aoSamples;
  options.aoDistance = parseDistance(a.aoDistance, "--ao-distance");
  options.thicknessDistance = parseDistance(a.thicknessDistance, "--thickness-distance");
  options.curvatureRadius = parseDistance(a.curvatureRadius, "--curvature-radius");
  options.device = a.device == "cpu" ? Device::Cpu : a.device == "gpu" ? Device::Gpu : Device::Auto;
  options.gpuDebug = a.glDebug;
  return options;
}

}  // namespace glint::bake
