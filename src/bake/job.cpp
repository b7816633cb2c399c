// glint bake's job (bake/job.h): the command's options, the checks a bake makes before it
// reads an input, and the bake itself: meshes in, every map written (staged until the run
// finishes: all of a bake's maps or none), the report filled.
#include "glint/bake/job.h"

#include "glint/bake/asset.h"
#include "glint/bake/baker.h"
#include "glint/bake/groups.h"
#include "glint/bake/output.h"
#include "glint/bake/udim.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/options.h"
#include "glint/core/text.h"
#include "glint/image/image.h"
#include "job_internal.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/parallel_for_each.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <exception>
#include <fstream>
#include <functional>
#include <future>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

namespace glint::bake {

using Json = nlohmann::ordered_json;

namespace {

/// Whether a file's bytes contain `text` (names are stored as plain strings in OBJ, PLY, FBX
/// and glTF alike): a millisecond's check before reading a low poly as parts.
bool mentionsText(const std::string& path, const std::string& text) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;  // the mesh loader says what it is instead
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return bytes.find(text) != std::string::npos;
}

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

namespace {
/// The extra maps a job asks for: those with a file.
MapSet mapsOf(const BakeJob& job) {
  MapSet maps;
  for (const MapInfo& m : mapTable())
    if (m.map != Map::Normal && !job.path(m.map).empty()) maps.add(m.map);
  return maps;
}

/// The job's fields as the baker's options: the one translation, which the bake and its memory
/// estimate share. Error(Usage) for a value that does not read (a size, a distance).
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
  return options;
}

}  // namespace

double estimateMemoryMiB(const BakeJob& job) {
  BakeOptions options;
  try {
    options = optionsOf(job);
  } catch (const Error&) {
    // A job whose values do not read fails its own checks; until then, its maps and samples
    // at the default size.
    options.samples = job.samples;
    options.maps = mapsOf(job);
    options.aoSamples = job.aoSamples;
  }
  return estimatePeakMemoryMiB(options, {job.low, job.high, job.cage});
}

std::vector<FileUse> inputFiles(const BakeJob& a) {
  return {{a.lowMesh ? std::string() : a.low, "the low poly"}, {a.highMesh ? std::string() : a.high, "the high poly"},
          {a.cage, "--cage"}, {a.detail, "--height-detail"}};
}

std::vector<FileUse> outputFiles(const BakeJob& a) {
  std::vector<FileUse> files;
  if (!a.sink) {  // a sink takes the maps: no map file
    files.push_back({a.output, "-o"});
    for (const MapInfo& m : mapTable())
      if (m.map != Map::Normal) files.push_back({a.path(m.map), std::string("--") + m.name});
  }
  files.push_back({a.asset, "--asset"});
  if (!a.preview.empty()) {
    fs::path folder = fs::path(a.preview).lexically_normal();
    if (!folder.has_filename() && folder.has_parent_path()) folder = folder.parent_path();
    files.push_back({folder, "--preview"});  // the folder itself: --asset x.gltf --preview x.gltf is two outputs in one place
    for (const std::string& f : previewFiles()) files.push_back({fs::path(a.preview) / f, "--preview"});
  }
  files.push_back({a.tool.json, "--json"});
  return files;
}

namespace {

/// --asset and --preview: a glTF file name, a tangent-space bake, places that can be written.
void checkAssetOptions(const BakeJob& a) {
  if (a.asset.empty() && a.preview.empty()) return;
  if (a.space != "tangent") {
    fail(ErrorKind::Usage, "--asset and --preview hold a tangent-space normal map (glTF's normalTexture): they need "
         "--space tangent, got {}", a.space);
  }
  if (!a.asset.empty()) {
    const std::string ext = lowerExtension(a.asset);
    if (ext != ".glb" && ext != ".gltf") fail(ErrorKind::Usage, "--asset '{}': a glTF asset ends in .glb or .gltf", a.asset);
    if (hasUdimToken(a.asset)) fail(ErrorKind::Usage, "--asset '{}': one asset holds every UDIM tile; name it without <UDIM>", a.asset);
    checkWritable(a.asset);
  }
  if (!a.preview.empty()) checkPageFolder(a.preview, "--preview");
}

/// The bake's maps as an asset holds them: 8-bit as an 8-bit file would, the normal map in
/// OpenGL's +Y convention whatever --directx did to the loose file.
std::shared_ptr<const AssetMaps> assetMaps(const BakeJob& a, const BakeResult& result) {
  auto maps = std::make_shared<AssetMaps>();
  Image normal = result.normal.type() == PixelType::U8 ? result.normal : result.normal.converted(PixelType::U8);
  if (a.directX) {
    auto px = normal.pixels<std::uint8_t>();
    for (std::size_t i = 1; i < px.size(); i += std::size_t(normal.channels())) px[i] = std::uint8_t(255 - px[i]);
  }
  (*maps)[std::size_t(Map::Normal)] = std::move(normal);
  for (const MapInfo& m : mapTable())
    if (m.map != Map::Normal && !result.map(m.map).empty())  // the maps asked for, and the miss mask
      (*maps)[std::size_t(m.map)] = m.forOutput(result.map(m.map), PixelType::U8, result.stats);
  return maps;
}

/// One tile's low poly as baked (result.low: its tangents, its split vertices) into the
/// asset: one part per bake group (`groupOf`: a triangle's group, empty for none), each its
/// own material named "<tile> <group>", sharing the tile's maps.
void addToAsset(Asset& asset, const Mesh& low, std::shared_ptr<const AssetMaps> maps, const std::string& tile,
                const std::function<std::string(std::size_t)>& groupOf) {
  std::map<std::string, std::vector<std::uint32_t>> groups;  // group -> triangles
  for (std::size_t t = 0; t < low.triangleCount(); ++t) groups[groupOf ? groupOf(t) : std::string()].push_back(std::uint32_t(t));
  for (const auto& [group, triangles] : groups) {
    AssetPart part;
    part.material = int(asset.materials.size());
    std::string name = tile;
    if (!group.empty()) name = name.empty() ? group : tile + " " + group;
    asset.materials.push_back({name.empty() ? asset.name : name, maps});
    std::vector<std::uint32_t> remap(low.vertexCount(), UINT32_MAX);
    Mesh& m = part.mesh;
    for (const std::uint32_t t : triangles)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = low.indices[3 * std::size_t(t) + std::size_t(k)];
        if (remap[v] == UINT32_MAX) {
          remap[v] = std::uint32_t(m.positions.size());
          m.positions.push_back(low.positions[v]);
          m.normals.push_back(low.normals[v]);
          m.uvs.push_back(low.uvs[v]);
          m.tangents.push_back(low.tangents[v]);
        }
        m.indices.push_back(remap[v]);
      }
    asset.parts.push_back(std::move(part));
  }
}

/// --asset and --preview, staged with the maps; their part of the report.
void writeAsset(const BakeJob& a, Asset& asset, ToolRun& run) {
  ToolRun::Phase writing(run, "asset");
  Json& report = run.report();
  asset.extras = {{"low", fs::path(a.low).filename().string()}, {"high", fs::path(a.high).filename().string()},
                  {"size", a.size}, {"samples", a.samples}, {"maps", report["maps"]}};
  if (report.contains("hard_edge_vertices")) asset.extras["hard_edge_vertices"] = report["hard_edge_vertices"];
  if (!a.asset.empty()) {
    saveAsset(asset, a.asset);
    report["asset"] = a.asset;
  }
  if (!a.preview.empty()) {
    const fs::path dir = checkPageFolder(a.preview, "--preview");
    savePreview(asset, dir);
    report["preview"] = (dir / "index.html").string();
  }
  std::size_t triangles = 0;
  for (const AssetPart& p : asset.parts) triangles += p.mesh.triangleCount();
  report["asset_materials"] = asset.materials.size();
  report["asset_triangles"] = triangles;
}

/// What checkBake worked out for runBake.
struct BakePlan {
  BakeOptions options;
  ivec2 size{0};
  bool needsImageIo = false;  ///< a detail map to read or an output other than PNG
};

/// Everything a bake checks before it reads an input: options, the files (no output is an
/// input or another output, by file identity: core/file.h), writable folders, memory.
/// Fails in a millisecond, not after the bake.
BakePlan prepare(const BakeJob& a, ToolRun& run) {
  checkDistinctFiles(inputFiles(a), outputFiles(a));
  BakePlan plan;
  plan.options = optionsOf(a);
  BakeOptions& options = plan.options;
  plan.size = {options.width, options.height};
  if (a.lowSuffix.empty() || a.highSuffix.empty() || a.lowSuffix == a.highSuffix)
    fail(ErrorKind::Usage, "--low-suffix and --high-suffix must be non-empty and differ");
  validateOptions(options);
  options.normalType = outputType(a.output, a.bits);  // quantized by the baker: no float copy of the map
  std::vector<std::string> outputs{a.output};
  bool anyHolds = a.bits == 0 || holdsBits(a.output, a.bits);
  for (const std::string& path : a.maps) {
    const std::string* extra = &path;
    if (extra->empty()) continue;
    outputType(*extra, a.bits);  // an unknown format: now, not after the bake
    anyHolds = anyHolds || holdsBits(*extra, a.bits);
    outputs.push_back(*extra);
  }
  // --bits applies to the maps whose format has that depth; one no map has is a mistake.
  if (!anyHolds) {
    fail(ErrorKind::Usage, "--bits {}: no map of this bake is in a format with {}-bit channels (PNG 8/16, TGA 8, TIFF "
         "8/16, EXR 32 float)", a.bits, a.bits);
  }
  checkAssetOptions(a);
  if (a.sink) outputs.clear();  // the maps go to the sink, not to files
  if (!a.tool.json.empty() && a.tool.json != "-") outputs.push_back(a.tool.json);
  for (const auto& path : outputs) checkWritable(path);
  run.checkMemory(estimateMemoryMiB(a), fmt::format("a {}x{} bake", plan.size.x, plan.size.y));
  // OpenImageIO is needed for a detail map and for outputs other than PNG (libspng).
  plan.needsImageIo = !a.detail.empty();
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const bool json = !a.tool.json.empty() && a.tool.json != "-" && i + 1 == outputs.size();
    const std::string ext = lowerExtension(outputs[i]);
    if (!json && ext != ".png") plan.needsImageIo = true;
  }
  if (plan.needsImageIo) requireImageIo();
  return plan;
}

}  // namespace

void checkJob(const BakeJob& job, ToolRun& run) { (void)prepare(job, run); }

void runJob(const BakeJob& a, ToolRun& run, HighMeshCache* cache) {
  BakePlan plan = prepare(a, run);
  BakeOptions& options = plan.options;
  if (cache) options.progressLabel = cache->progressLabel;
  options.progress = run.showProgress();
  options.cancel = &run.cancelFlag();
  if (plan.needsImageIo) preloadImageIo();

  // Inputs (never modified: loaded into memory, prepared there).
  // The high poly (the big file) is parsed here while a second thread reads the rest;
  // errors are reported in argument order: low, high, cage, detail.
  std::optional<ToolRun::Phase> loading(std::in_place, run, "load");
  // Named parts (bake groups, material ID, vertex colour) are read through Assimp; a low
  // file that does not even contain the low suffix is read as before, in parallel with the high.
  const GroupNaming naming{a.lowSuffix, a.highSuffix};
  std::optional<MeshParts> lowParts;
  if (!a.noGroups && !a.lowMesh && mentionsText(a.low, naming.lowSuffix)) {
    lowParts = loadMeshParts(a.low);
    bool grouped = false;
    for (const std::string& name : lowParts->partNames) grouped = grouped || !groupName(name, naming.lowSuffix, false).empty();
    if (!grouped) lowParts.reset();
  }
  const bool highAsParts = lowParts || options.maps.needs(kHitTriangle);
  auto others = std::async(std::launch::async, [&] {
    Mesh low = lowParts ? lowParts->mesh : a.lowMesh ? *a.lowMesh : loadMesh(a.low);
    if (!a.cage.empty()) options.cage = loadMesh(a.cage);
    if (!a.detail.empty()) options.detail = HeightDetail{loadImage(a.detail), a.detailScale};
    return low;
  });
  // Rays need no shared vertices: skipping Assimp's vertex joining halves the load.
  std::shared_ptr<const Mesh> high;
  std::shared_ptr<const MeshParts> highParts;
  std::exception_ptr highError;
  bool highReused = false;
  try {
    if (a.highMesh) {
      if (highAsParts) highParts = std::make_shared<const MeshParts>(MeshParts{.mesh = *a.highMesh});
      else high = a.highMesh;
    } else if (HighMeshCache::Entry* e = cache ? cache->find(a.high, highAsParts) : nullptr) {
      high = e->mesh;
      highParts = e->parts;
      highReused = true;
    } else {
      if (highAsParts) highParts = std::make_shared<const MeshParts>(loadMeshParts(a.high, {.joinVertices = false}));
      else high = std::make_shared<const Mesh>(loadMesh(a.high, {.joinVertices = false}));
      if (cache && cache->usesLeft[a.high] > 1) cache->add(a.high, high, highParts);
    }
  } catch (...) {
    highError = std::current_exception();
  }
  const Mesh low = others.get();
  if (highError) std::rethrow_exception(highError);
  loading.reset();
  const Mesh& highMesh = highParts ? highParts->mesh : *high;
  if (highReused) log::info("bake: {}: high mesh reused from an earlier job of the batch (read once)", a.high);
  if (cache && (highReused || cache->usesLeft[a.high] > 1)) options.sceneCache = &cache->scenes;
  GroupMatch match;
  if (lowParts) {
    // A high file that names no part with the high suffix (a PLY has no part names): baked
    // against as one, said once, rather than a bake that stops.
    bool highNamed = false;
    for (const std::string& name : highParts->partNames) highNamed = highNamed || !groupName(name, naming.highSuffix, true).empty();
    if (!highNamed) {
      run.warn(fmt::format("bake groups: the low poly names its parts with '{}' but '{}' names no part with '{}' (no "
                           "part names): baked against the whole high poly, without groups (--no-groups says so "
                           "up front)", naming.lowSuffix, a.high, naming.highSuffix));
      lowParts.reset();
    }
  }
  if (lowParts) {
    match = matchGroups(*lowParts, *highParts, naming);
    // (unmatched parts are warned about by the bake, by name)
    log::info("bake: {} bake group{} matched by name", match.groups.size(), match.groups.size() == 1 ? "" : "s");
  }
  run.throwIfInterrupted();
  // Every map this bake writes: (its report key, the path as given), in the table's order.
  std::vector<std::pair<const char*, const std::string*>> kinds;
  for (const MapInfo& m : mapTable()) kinds.emplace_back(m.reportKey, &a.path(m.map));

  // UDIM: UVs beyond the unit square, or outputs named with <UDIM>, bake one image per tile.
  bool named = false, unnamed = false;
  for (const auto& [kind, path] : kinds) {
    if (path->empty()) continue;
    (hasUdimToken(*path) ? named : unnamed) = true;
  }
  std::vector<UdimTile> tiles;
  if (named || spansUdimTiles(low)) {
    if (unnamed && !a.sink) {  // (a sink takes tiles by number: no file names them)
      fail(ErrorKind::Usage, "bake: the low poly's UVs span UDIM tiles (or an output names <UDIM>): name every map with "
           "<UDIM> where the tile number goes, e.g. -o normal.<UDIM>.png");
    }
    UdimSplit split = splitUdimTiles(low);
    if (split.outOfRangeTriangles)
      run.warn(fmt::format("{} low-poly triangle{} with UVs outside the UDIM range (u in [0, 10), v >= 0) left out",
                           split.outOfRangeTriangles, split.outOfRangeTriangles == 1 ? "" : "s"));
    if (split.spanningTriangles)
      run.warn(fmt::format("{} low-poly triangle{} reach past their UDIM tile's edge: baked in the tile of their "
                           "centre, clipped at its edge",
                           split.spanningTriangles, split.spanningTriangles == 1 ? "" : "s"));
    if (split.tiles.empty()) fail(ErrorKind::Input, "bake: no low-poly triangle lies in the UDIM range");
    tiles = std::move(split.tiles);
  }
  const bool udim = !tiles.empty();
  if (udim) {
    // Distances given as a share of the model are the whole low poly's, in every tile.
    const float diagonal = low.bounds().diagonal();
    for (Distance* d : {&options.maxFront, &options.maxRear, &options.aoDistance, &options.thicknessDistance,
                              &options.curvatureRadius})
      *d = Distance{d->resolve(diagonal), false};
  }
  if (!udim) tiles.push_back({.number = 0, .low = low, .triangles = low.triangleCount()});
  // A UDIM tile's cage is the cage's vertices of the tile's triangles (the cage has the low
  // poly's vertices and triangles), and its bake groups are those of its triangles' parts.
  const std::optional<Mesh> wholeCage = udim ? options.cage : std::nullopt;
  const auto tileCage = [&](const UdimTile& tile) {
    Mesh cage = tile.low;
    for (std::size_t k = 0; k < tile.lowVertices.size(); ++k) cage.positions[k] = wholeCage->positions[tile.lowVertices[k]];
    return cage;
  };
  const auto tileParts = [&](const UdimTile& tile) {
    MeshParts parts{.mesh = tile.low, .partNames = lowParts->partNames};
    parts.trianglePart.reserve(tile.lowTriangles.size());
    for (const std::uint32_t t : tile.lowTriangles) parts.trianglePart.push_back(lowParts->trianglePart[t]);
    return parts;
  };

  auto& report = run.report();
  report["low"] = a.low;
  report["high"] = a.high;
  if (cache) report["high_mesh_reused"] = highReused;
  report["output"] = a.output;
  Json maps = Json::object();  // every map written, by kind
  for (const auto& [kind, path] : kinds)
    if (!path->empty()) maps[kind] = *path;
  report["maps"] = std::move(maps);
  report.update(toJson(options));
  if (match.grouped()) report.update(toJson(match));
  Json tileReports = Json::array();
  const std::string label = options.progressLabel;
  const bool wantsAsset = !a.asset.empty() || !a.preview.empty();
  Asset asset;
  asset.name = fs::path(a.low).stem().string();
  for (const UdimTile& tile : tiles) {
    const auto file = [&](const std::string& path) { return udim ? udimPath(path, tile.number) : path; };
    if (udim) options.progressLabel = fmt::format("{} tile {}", label, tile.number);
    if (udim && wholeCage) options.cage = tileCage(tile);
    BakeResult result;
    GroupMatch tileMatch;
    if (udim && lowParts) {  // the tile's parts, matched as the whole low poly's were
      const MeshParts parts = tileParts(tile);
      tileMatch = matchGroups(parts, *highParts, naming);
      result = bake(parts, *highParts, tileMatch, options);
    } else if (highParts) {
      result = bake(lowParts ? *lowParts : MeshParts{.mesh = tile.low}, *highParts, match, options);
    } else {
      result = bake(tile.low, *high, options);
    }
    if (wantsAsset) {  // the tile as baked, its groups apart
      const GroupMatch& m = udim ? tileMatch : match;
      const auto groupOf = [&m](std::size_t t) {
        const std::uint32_t g = m.grouped() ? m.lowTriangleGroup[t] : GroupMatch::kNone;
        return g == GroupMatch::kNone ? std::string() : m.groups[g].name;
      };
      addToAsset(asset, result.low, assetMaps(a, result), udim ? std::to_string(tile.number) : std::string(), groupOf);
    }
    const BakeStats& s = result.stats;
    run.addSeconds("prepare", s.prepareSeconds);
    run.addSeconds("trace", s.traceSeconds);
    run.addSeconds("dilate", s.dilateSeconds);
    if (s.bvhReused) log::info("bake: {}: BVH reused from an earlier job of the batch", a.high);

    std::optional<ToolRun::Phase> writing(std::in_place, run, "write");
    // Every map asked for, as (its option's path, the image converted for that file), the
    // files written in parallel: compressing them is most of the write phase (six 2048²
    // PNGs: 2.4 s one after another).
    if (a.sink) {  // in memory: each map as its file would hold it
      a.sink(Map::Normal, tile.number, std::move(result.normal));
      for (const MapInfo& m : mapTable())
        if (m.map != Map::Normal && !a.path(m.map).empty())
          a.sink(m.map, tile.number, m.forOutput(result.map(m.map), outputType(a.path(m.map), a.bits), s));
    }
    std::vector<std::function<void()>> writes;
    if (!a.sink) writes.emplace_back([&] { saveImage(result.normal, file(a.output)); });  // quantized as it was baked
    for (const MapInfo& m : mapTable()) {
      const std::string& path = a.path(m.map);
      if (m.map == Map::Normal || path.empty() || a.sink) continue;
      writes.emplace_back([&m, &path, &result, &s, &file, &a] {
        saveImage(m.forOutput(result.map(m.map), outputType(path, a.bits), s), file(path));
      });
    }
    tbb::parallel_for_each(writes.begin(), writes.end(), [](const std::function<void()>& write) { write(); });
    writing.reset();
    log::info("bake: {} ({} triangles) → {} ({}x{}, {} per texel): {} texels baked, {} padded; {} rays, hit ratio "
              "{:.4f}; {:.2f} s", a.high, highMesh.triangleCount(), file(a.output), options.width, options.height,
              options.samples, s.coveredTexels, s.paddedTexels, s.rays, s.hitRatio(), run.elapsed());
    for (const auto& w : result.warnings) run.recordWarning(w);
    if (!udim) {
      report.update(toJson(s));
    } else {
      Json entry = {{"tile", tile.number}, {"low_triangles_in_tile", tile.triangles}, {"output", file(a.output)}};
      entry.update(toJson(s));
      tileReports.push_back(std::move(entry));
    }
    run.throwIfInterrupted();
  }
  if (udim) report["udim_tiles"] = std::move(tileReports);
  if (wantsAsset) writeAsset(a, asset, run);
}

}  // namespace glint::bake
