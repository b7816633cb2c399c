// glint bake LOW HIGH -o OUT — the normal mapper: high-poly detail into a texture for the
// low poly. Thin: options → bake::BakeOptions, files in and out, the report.
//
// glint bake --batch JOBS.json [--job I | --list] — many bakes from one file. Each job is
// turned into a `glint bake` argument list (generically: a key is any option's long name)
// and parsed by the same option definitions (addBakeOptions), checked by the same checks
// (checkBake) and run by the same code (runBake) as the command line.
#include "common.h"

#include "glint/bake/baker.h"
#include "glint/bake/groups.h"
#include "glint/bake/output.h"
#include "glint/bake/scene_cache.h"
#include "glint/bake/udim.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"
#include "glint/mesh/parts.h"

#include <fmt/format.h>
#include <tbb/parallel_for_each.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

namespace glint::app {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

/// CLI11's type name of the options that name files. A batch file's relative paths are
/// resolved against the batch file's folder for exactly these options.
constexpr const char* kFile = "FILE";

struct BakeArgs {
  std::string low, high, output, size = "1024x1024", space = "tangent", worldMatrix;
  std::string maxFront = "5%", maxRear = "5%", aoDistance = "10%", thicknessDistance = "10%", curvatureRadius = "1%";
  std::string cage, detail, ao, height, missMask, bentNormal, thickness, curvature, position, opacity, materialId,
      vertexColor;
  std::string lowSuffix = "_low", highSuffix = "_high";
  int samples = 1, padding = 16, bits = 0, aoSamples = 16;
  float detailScale = 8.0f;
  bool directX = false, frontFirst = false, fillAll = false;
  ToolSettings tool;
};

/// Whether a file's bytes contain `text` (names are stored as plain strings in OBJ, PLY, FBX
/// and glTF alike): a millisecond's check before reading a low poly as parts.
bool mentionsText(const std::string& path, const std::string& text) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return bytes.find(text) != std::string::npos;
}

/// "5%" → 5 % of the low poly's diagonal; "0.2" → 0.2 scene units.
bake::Distance parseDistance(const std::string& text, const char* option) {
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

constexpr const char* kFooter = R"(Examples:
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

Maps (each its own file, baked in the same pass as the normal map; docs/bake.md, "Maps"):
  -o             high-poly normal in --space, encoded (n + 1) / 2
  --ao           open fraction of --ao-samples hemisphere rays (1 = unoccluded)
  --height       signed distance along the low poly's normal (+ in front)
  --bent-normal  mean unoccluded direction of the AO rays, encoded like -o
  --thickness    mean distance through the surface / --thickness-distance (1 = thick)
  --curvature    mean curvature at --curvature-radius: mid-grey flat, bright convex
                 (ridges), dark concave (creases); EXR: signed, 1 / scene units
  --position     hit point, object space: EXR raw, 8/16-bit over the high poly's box
  --opacity      fraction of a texel's samples that hit, 0 outside islands
  --miss-mask    fraction of samples whose rays found nothing (debug)
  --material-id  flat colour per high-poly material (a stable colour of its name)
  --vertex-color the high poly's vertex colours, interpolated at the hits

Bake groups (docs/bake.md, "Bake groups"): when the low file's parts are named
<name>_low, each bakes only against the high parts <name>_high and <name>_high_*, so
parts that touch or interpenetrate bake as if exploded. --low-suffix/--high-suffix
change the suffixes; unmatched parts are reported by name (low ones are not baked).

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

Exit status: 0 done, 2 bad option, 3 unreadable/unsuitable input, 4 output not
writable, 130 interrupted (Ctrl-C; no partial file is left).)";


/// Every option of `glint bake` but the batch ones, bound to `a`: the command line and each
/// job of a batch file go through this one definition. `required`: LOW, HIGH and -o must be
/// given (a job; the command line checks them itself, since --batch replaces them).
void addBakeOptions(CLI::App& cmd, BakeArgs& a, bool required) {
  CLI::Option* low = cmd.add_option("low", a.low, "Low-poly mesh: positions, normals, one UV set (OBJ, PLY, glTF/GLB, "
                                    "FBX, ...)")->type_name(kFile);
  CLI::Option* high = cmd.add_option("high", a.high, "High-poly mesh: positions and normals")->type_name(kFile);
  CLI::Option* output = cmd.add_option("-o,--output", a.output, "Normal map to write; format from the extension: .png "
                                       ".tga .tif .exr")->type_name(kFile);
  if (required)
    for (CLI::Option* option : {low, high, output}) option->required();
  cmd.add_option("--size", a.size, "Map size WIDTHxHEIGHT, any size")->capture_default_str();
  cmd.add_option("--samples", a.samples, "Rays per texel, a square: 1, 4, 9, 16, 36, 64 (stratified √N×√N grid, "
                 "averaged; 36 is smooth)")->capture_default_str();
  cmd.add_option("--space", a.space, "tangent (MikkTSpace), object, or world (see --world-matrix)")
      ->check(CLI::IsMember({"tangent", "object", "world"}))->capture_default_str();
  cmd.add_option("--world-matrix", a.worldMatrix, "Object-to-world matrix for --space world: 16 numbers, row by row");
  cmd.add_flag("--directx", a.directX, "Flip green (DirectX/Unreal convention); the default is OpenGL's +Y");
  cmd.add_option("--bits", a.bits, "Bits per channel of every map written: 8 or 16 for PNG/TIFF (default: 8 PNG/TGA, "
                 "16 TIFF, 32 float EXR)")
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
  cmd.add_option("--ao", a.ao, "Also bake ambient occlusion (hemisphere rays against the high poly) to this file")
      ->type_name(kFile);
  cmd.add_option("--ao-samples", a.aoSamples, "AO rays per sample (bent normals share them; thickness casts as many "
                 "into the surface)")->capture_default_str();
  cmd.add_option("--ao-distance", a.aoDistance, "AO ray length: scene units or % of the low poly's diagonal")
      ->capture_default_str();
  cmd.add_option("--height", a.height, "Also bake height/displacement (signed ray distance) to this file; 8/16-bit "
                 "files map ±max(--max-front, --max-rear) to 0..1, EXR keeps distances")->type_name(kFile);
  cmd.add_option("--miss-mask", a.missMask, "Also write the fraction of each texel's rays that found nothing (debug)")
      ->type_name(kFile);
  cmd.add_option("--bent-normal", a.bentNormal, "Also bake bent normals (the mean unoccluded direction of the AO rays; "
                 "casts them without --ao too), in --space, encoded like the normal map")->type_name(kFile);
  cmd.add_option("--thickness", a.thickness, "Also bake thickness for subsurface/translucency: --ao-samples rays into "
                 "the surface, mean distance to where they leave it / --thickness-distance (1 = thick)")->type_name(kFile);
  cmd.add_option("--thickness-distance", a.thicknessDistance, "Thickness ray length, the distance that reads 1: scene "
                 "units or % of the low poly's diagonal")->capture_default_str();
  cmd.add_option("--curvature", a.curvature, "Also bake curvature (convex bright, concave dark, mid-grey flat; EXR: "
                 "signed mean curvature in 1/scene units), from the high poly's normals at --curvature-radius")
      ->type_name(kFile);
  cmd.add_option("--curvature-radius", a.curvatureRadius, "The scale curvature is measured at (detail smaller is "
                 "averaged away; a bend this tight reads white/black in 8/16-bit): scene units or % of the low poly's "
                 "diagonal")->capture_default_str();
  cmd.add_option("--position", a.position, "Also bake the high-poly hit point (object space): EXR keeps coordinates, "
                 "8/16-bit maps the high poly's bounding box to 0..1 (position_min/max in the report)")->type_name(kFile);
  cmd.add_option("--opacity", a.opacity, "Also bake coverage/opacity: the fraction of each texel's samples that hit the "
                 "high poly, 0 outside UV islands (not dilated)")->type_name(kFile);
  cmd.add_option("--material-id", a.materialId, "Also bake a material ID map: a flat colour per high-poly material "
                 "(majority of the texel's hits, never blended), stable from the material's name")->type_name(kFile);
  cmd.add_option("--vertex-color", a.vertexColor, "Also bake the high poly's vertex colours (OBJ 'v x y z r g b', PLY "
                 "red/green/blue, glTF COLOR_0), averaged over each texel's hits")->type_name(kFile);
  cmd.add_option("--low-suffix", a.lowSuffix, "Bake groups: low parts are named <group><suffix>")->capture_default_str();
  cmd.add_option("--high-suffix", a.highSuffix, "Bake groups: high parts are named <group><suffix> or "
                 "<group><suffix>_*")->capture_default_str();
  addToolOptions(cmd, a.tool, "texels, rays, hit ratio, misses, BVH size");
  cmd.get_option("--json")->type_name(kFile);
}

/// The files a bake reads and writes, named as its messages name them.
struct BakeFiles {
  std::vector<FileUse> inputs, outputs;
};

BakeFiles bakeFiles(const BakeArgs& a) {
  return {{{a.low, "the low poly"}, {a.high, "the high poly"}, {a.cage, "--cage"}, {a.detail, "--height-detail"}},
          {{a.output, "-o"}, {a.ao, "--ao"}, {a.height, "--height"}, {a.missMask, "--miss-mask"},
           {a.bentNormal, "--bent-normal"}, {a.thickness, "--thickness"}, {a.curvature, "--curvature"},
           {a.position, "--position"}, {a.opacity, "--opacity"}, {a.materialId, "--material-id"},
           {a.vertexColor, "--vertex-color"}, {a.tool.json, "--json"}}};
}

/// What checkBake worked out for runBake.
struct BakePlan {
  bake::BakeOptions options;
  ivec2 size{0};
  bool needsImageIo = false;  ///< a detail map to read or an output other than PNG
};

/// Everything a bake checks before it reads an input: options, the files (no output is an
/// input or another output, by file identity: core/file.h), writable folders, memory.
/// Fails in a millisecond, not after the bake.
BakePlan checkBake(const BakeArgs& a, ToolRun& run) {
  const BakeFiles files = bakeFiles(a);
  checkDistinctFiles(files.inputs, files.outputs);
  BakePlan plan;
  bake::BakeOptions& options = plan.options;
  plan.size = parseSize(a.size);
  options.width = plan.size.x;
  options.height = plan.size.y;
  options.samples = a.samples;
  options.space = a.space == "object" ? NormalSpace::Object
                : a.space == "world"  ? NormalSpace::World
                                      : NormalSpace::Tangent;
  if (!a.worldMatrix.empty()) options.objectToWorld = parseMatrix(a.worldMatrix);
  options.directX = a.directX;
  options.maxFront = parseDistance(a.maxFront, "--max-front");
  options.maxRear = parseDistance(a.maxRear, "--max-rear");
  options.selection = a.frontFirst ? bake::HitSelection::FrontFirst : bake::HitSelection::Closest;
  options.padding = a.padding;
  options.fillAll = a.fillAll;
  options.ambientOcclusion = !a.ao.empty();
  options.aoSamples = a.aoSamples;
  options.aoDistance = parseDistance(a.aoDistance, "--ao-distance");
  options.heightMap = !a.height.empty();
  options.missMask = !a.missMask.empty();
  options.bentNormals = !a.bentNormal.empty();
  options.thickness = !a.thickness.empty();
  options.thicknessDistance = parseDistance(a.thicknessDistance, "--thickness-distance");
  options.curvature = !a.curvature.empty();
  options.curvatureRadius = parseDistance(a.curvatureRadius, "--curvature-radius");
  options.positionMap = !a.position.empty();
  options.opacity = !a.opacity.empty();
  options.materialId = !a.materialId.empty();
  options.vertexColor = !a.vertexColor.empty();
  if (a.lowSuffix.empty() || a.highSuffix.empty() || a.lowSuffix == a.highSuffix)
    fail(ErrorKind::Usage, "--low-suffix and --high-suffix must be non-empty and differ");
  bake::validateOptions(options);
  options.normalType = bake::outputType(a.output, a.bits);  // quantized by the baker: no float copy of the map
  std::vector<std::string> outputs{a.output};
  for (const std::string* extra : {&a.ao, &a.height, &a.missMask, &a.bentNormal, &a.thickness, &a.curvature, &a.position,
                                   &a.opacity, &a.materialId, &a.vertexColor}) {
    if (extra->empty()) continue;
    bake::outputType(*extra, a.bits);  // --bits applies to every map: check them all now
    outputs.push_back(*extra);
  }
  if (!a.tool.json.empty() && a.tool.json != "-") outputs.push_back(a.tool.json);
  for (const auto& path : outputs) checkWritable(path);
  run.checkMemory(bake::estimatePeakMemoryMiB(options, {a.low, a.high, a.cage}),
                  fmt::format("a {}x{} bake", plan.size.x, plan.size.y));
  // OpenImageIO is needed for a detail map and for outputs other than PNG (libspng).
  plan.needsImageIo = !a.detail.empty();
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const bool json = !a.tool.json.empty() && a.tool.json != "-" && i + 1 == outputs.size();
    std::string ext = fs::path(outputs[i]).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (!json && ext != ".png") plan.needsImageIo = true;
  }
  if (plan.needsImageIo) requireImageIo();
  return plan;
}

/// Within one `--batch` run: the high meshes read so far, by path and modification time,
/// and their BVHs, so that jobs sharing a high poly read it and build its BVH once.
struct HighCache {
  struct Entry {
    fs::path path;
    fs::file_time_type modified;
    std::shared_ptr<const Mesh> mesh;        ///< read with loadMesh
    std::shared_ptr<const MeshParts> parts;  ///< read with loadMeshParts
  };
  std::vector<Entry> entries;
  bake::SceneCache scenes;  // after `entries`: destroyed first (its BVHs read their meshes)
  /// Jobs still to run per high-mesh path as given: a mesh is kept only while one will use it.
  std::map<std::string, int> usesLeft;

  /// After a job: forget its high mesh (and BVH) when no later job reads the same path.
  void done(const std::string& path) {
    if (--usesLeft[path] > 0) return;
    std::erase_if(entries, [&](const Entry& e) {
      std::error_code ec;
      if (!fs::equivalent(e.path, path, ec)) return false;
      scenes.release(e.parts ? e.parts->mesh : *e.mesh);
      return true;
    });
  }

  Entry* find(const std::string& path, bool parts) {
    std::error_code ec;
    const fs::file_time_type modified = fs::last_write_time(path, ec);
    if (ec) return nullptr;
    for (Entry& e : entries) {
      std::error_code same;
      if (e.modified == modified && fs::equivalent(e.path, path, same) && (parts ? bool(e.parts) : bool(e.mesh))) return &e;
    }
    return nullptr;
  }
  void add(const std::string& path, std::shared_ptr<const Mesh> mesh, std::shared_ptr<const MeshParts> parts) {
    std::error_code ec;
    const fs::file_time_type modified = fs::last_write_time(path, ec);
    if (!ec) entries.push_back({path, modified, std::move(mesh), std::move(parts)});
  }
};

/// Loads the meshes, bakes, writes the maps and fills the run's report (finish() is the
/// caller's). `cache`: a batch's high meshes and BVHs, shared between its jobs.
void runBake(const BakeArgs& a, BakePlan plan, ToolRun& run, HighCache* cache = nullptr) {
  bake::BakeOptions& options = plan.options;
  options.progress = run.showProgress();
  options.cancel = &run.cancelFlag();
  if (plan.needsImageIo) preloadImageIo();

  // Inputs (never modified: loaded into memory, prepared there).
  // The high poly (the big file) is parsed here while a second thread reads the rest;
  // errors are reported in argument order: low, high, cage, detail.
  std::optional<ToolRun::Phase> loading(std::in_place, run, "load");
  // Named parts (bake groups, material ID, vertex colour) are read through Assimp; a low
  // file that does not even contain the low suffix is read as before, in parallel with the high.
  const bake::GroupNaming naming{a.lowSuffix, a.highSuffix};
  std::optional<MeshParts> lowParts;
  if (mentionsText(a.low, naming.lowSuffix)) {
    lowParts = loadMeshParts(a.low);
    bool grouped = false;
    for (const std::string& name : lowParts->partNames) grouped = grouped || !bake::groupName(name, naming.lowSuffix, false).empty();
    if (!grouped) lowParts.reset();
  }
  const bool highAsParts = lowParts || options.materialId || options.vertexColor;
  auto others = std::async(std::launch::async, [&] {
    Mesh low = lowParts ? lowParts->mesh : loadMesh(a.low);
    if (!a.cage.empty()) options.cage = loadMesh(a.cage);
    if (!a.detail.empty()) options.detail = bake::HeightDetail{loadImage(a.detail), a.detailScale};
    return low;
  });
  // Rays need no shared vertices: skipping Assimp's vertex joining halves the load.
  std::shared_ptr<const Mesh> high;
  std::shared_ptr<const MeshParts> highParts;
  std::exception_ptr highError;
  bool highReused = false;
  try {
    if (HighCache::Entry* e = cache ? cache->find(a.high, highAsParts) : nullptr) {
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
  bake::GroupMatch match;
  if (lowParts) {
    match = bake::matchGroups(*lowParts, *highParts, naming);
    // (unmatched parts are warned about by the bake, by name)
    log::info("bake: {} bake group{} matched by name", match.groups.size(), match.groups.size() == 1 ? "" : "s");
  }
  run.throwIfInterrupted();
  // Every map this bake writes: (kind for the report, the path as given).
  const std::pair<const char*, const std::string*> kinds[] = {
      {"normal", &a.output},         {"ao", &a.ao},          {"height", &a.height},     {"miss_mask", &a.missMask},
      {"bent_normal", &a.bentNormal}, {"thickness", &a.thickness}, {"curvature", &a.curvature},
      {"position", &a.position},     {"opacity", &a.opacity},     {"material_id", &a.materialId},
      {"vertex_color", &a.vertexColor}};

  // UDIM: UVs beyond the unit square, or outputs named with <UDIM>, bake one image per tile.
  bool named = false, unnamed = false;
  for (const auto& [kind, path] : kinds) {
    if (path->empty()) continue;
    (bake::hasUdimToken(*path) ? named : unnamed) = true;
  }
  std::vector<bake::UdimTile> tiles;
  if (named || bake::spansUdimTiles(low)) {
    if (unnamed) {
      fail(ErrorKind::Usage, "bake: the low poly's UVs span UDIM tiles (or an output names <UDIM>): name every map with "
           "<UDIM> where the tile number goes, e.g. -o normal.<UDIM>.png");
    }
    bake::UdimSplit split = bake::splitUdimTiles(low);
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
    for (bake::Distance* d : {&options.maxFront, &options.maxRear, &options.aoDistance, &options.thicknessDistance,
                              &options.curvatureRadius})
      *d = bake::Distance{d->resolve(diagonal), false};
  }
  if (!udim) tiles.push_back({.number = 0, .low = low, .triangles = low.triangleCount()});
  // A UDIM tile's cage is the cage's vertices of the tile's triangles (the cage has the low
  // poly's vertices and triangles), and its bake groups are those of its triangles' parts.
  const std::optional<Mesh> wholeCage = udim ? options.cage : std::nullopt;
  const auto tileCage = [&](const bake::UdimTile& tile) {
    Mesh cage = tile.low;
    for (std::size_t k = 0; k < tile.lowVertices.size(); ++k) cage.positions[k] = wholeCage->positions[tile.lowVertices[k]];
    return cage;
  };
  const auto tileParts = [&](const bake::UdimTile& tile) {
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
  report.update(bake::toJson(options));
  if (match.grouped()) report.update(bake::toJson(match));
  Json tileReports = Json::array();
  const std::string label = options.progressLabel;
  for (const bake::UdimTile& tile : tiles) {
    const auto file = [&](const std::string& path) { return udim ? bake::udimPath(path, tile.number) : path; };
    if (udim) options.progressLabel = fmt::format("{} tile {}", label, tile.number);
    if (udim && wholeCage) options.cage = tileCage(tile);
    bake::BakeResult result;
    if (udim && lowParts) {  // the tile's parts, matched as the whole low poly's were
      const MeshParts parts = tileParts(tile);
      result = bake::bake(parts, *highParts, bake::matchGroups(parts, *highParts, naming), options);
    } else if (highParts) {
      result = bake::bake(lowParts ? *lowParts : MeshParts{.mesh = tile.low}, *highParts, match, options);
    } else {
      result = bake::bake(tile.low, *high, options);
    }
    const bake::BakeStats& s = result.stats;
    run.addSeconds("prepare", s.prepareSeconds);
    run.addSeconds("trace", s.traceSeconds);
    run.addSeconds("dilate", s.dilateSeconds);
    if (s.bvhReused) log::info("bake: {}: BVH reused from an earlier job of the batch", a.high);

    std::optional<ToolRun::Phase> writing(std::in_place, run, "write");
    // Every map asked for, as (its option's path, the image converted for that file), the
    // files written in parallel: compressing them is most of the write phase (six 2048²
    // PNGs: 2.4 s one after another).
    std::vector<std::function<void()>> writes;
    const auto add = [&](const std::string& path, auto convert) {
      if (!path.empty()) writes.emplace_back([&path, convert, &file, &a] { saveImage(convert(bake::outputType(path, a.bits)), file(path)); });
    };
    writes.emplace_back([&] { saveImage(result.normal, file(a.output)); });
    const float heightRange = std::max(s.frontDistance, s.rearDistance);
    add(a.ao, [&](PixelType t) { return bake::forOutput(result.ao, t); });
    add(a.height, [&](PixelType t) { return bake::heightForOutput(result.height, t, heightRange); });
    add(a.missMask, [&](PixelType t) { return bake::forOutput(result.missMask, t); });
    add(a.bentNormal, [&](PixelType t) { return bake::forOutput(result.bentNormal, t); });
    add(a.thickness, [&](PixelType t) { return bake::forOutput(result.thickness, t); });
    add(a.curvature, [&](PixelType t) { return bake::curvatureForOutput(result.curvature, t, s.curvatureRadius); });
    add(a.position, [&](PixelType t) { return bake::positionForOutput(result.position, t, *s.positionBounds); });
    add(a.opacity, [&](PixelType t) { return bake::forOutput(result.opacity, t); });
    add(a.materialId, [&](PixelType t) { return bake::forOutput(result.materialId, t); });
    add(a.vertexColor, [&](PixelType t) { return bake::forOutput(result.vertexColor, t); });
    tbb::parallel_for_each(writes.begin(), writes.end(), [](const std::function<void()>& write) { write(); });
    writing.reset();
    log::info("bake: {} ({} triangles) → {} ({}x{}, {} per texel): {} texels baked, {} padded; {} rays, hit ratio "
              "{:.4f}; {:.2f} s", a.high, highMesh.triangleCount(), file(a.output), options.width, options.height,
              options.samples, s.coveredTexels, s.paddedTexels, s.rays, s.hitRatio(), run.elapsed());
    for (const auto& w : result.warnings) run.recordWarning(w);
    if (!udim) {
      report.update(bake::toJson(s));
    } else {
      Json entry = {{"tile", tile.number}, {"low_triangles_in_tile", tile.triangles}, {"output", file(a.output)}};
      entry.update(bake::toJson(s));
      tileReports.push_back(std::move(entry));
    }
    run.throwIfInterrupted();
  }
  if (udim) report["udim_tiles"] = std::move(tileReports);
}

// ---------------------------------------------------------------------------- batches

/// Inside a catch block: the same Error, its message prefixed with `where` ("bake: jobs.json job 2 (crate_low.obj)").
[[noreturn]] void rethrowIn(const std::string& where) {
  try {
    throw;
  } catch (const Error& e) {
    throw Error(e.kind(), fmt::format("{}: {}", where, e.what()));
  }
}

/// A batch file: the defaults and one object per job, in order.
struct BatchFile {
  Json defaults = Json::object();
  std::vector<Json> jobs;
};

BatchFile loadBatch(const std::string& path) {
  const std::string text = readTextFile(path);  // Error(Input): exit 3, like every unreadable input
  Json doc;
  try {
    doc = Json::parse(text);
  } catch (const Json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..."
    std::string what = e.what();
    if (const auto end = what.find("] "); what.starts_with("[json.exception") && end != std::string::npos)
      what.erase(0, end + 2);
    fail(ErrorKind::Usage, "bake: {}: not valid JSON: {}", path, printable(what));
  }
  if (!doc.is_object())
    fail(ErrorKind::Usage, "bake: {}: a batch file is an object {{\"defaults\": {{...}}, \"bakes\": [...]}}, got {}", path,
         doc.type_name());
  BatchFile batch;
  for (const auto& [key, value] : doc.items()) {
    if (key == "defaults") {
      if (!value.is_object()) fail(ErrorKind::Usage, "bake: {}: \"defaults\" must be an object of options, got {}", path, value.type_name());
      batch.defaults = value;
    } else if (key == "bakes") {
      if (!value.is_array()) fail(ErrorKind::Usage, "bake: {}: \"bakes\" must be a list of jobs, got {}", path, value.type_name());
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (!value[i].is_object())
          fail(ErrorKind::Usage, "bake: {} job {}: a job must be an object of options, got {}", path, i, value[i].type_name());
        batch.jobs.push_back(value[i]);
      }
    } else {
      fail(ErrorKind::Usage, "bake: {}: unknown key '{}' (a batch file has \"defaults\" and \"bakes\")", path, printable(key));
    }
  }
  if (batch.jobs.empty()) fail(ErrorKind::Usage, "bake: {}: no jobs: \"bakes\" is missing or empty", path);
  return batch;
}

/// The option a batch file's key stands for: its long name without the dashes ("size",
/// "output"), or a positional's name ("low"). Null when there is none (help included).
const CLI::Option* optionForKey(const CLI::App& app, const std::string& key) {
  for (const CLI::Option* option : app.get_options()) {
    if (option == app.get_help_ptr()) continue;
    const auto& names = option->get_lnames();
    if (std::find(names.begin(), names.end(), key) != names.end()) return option;
    if (option->get_positional() && names.empty() && option->get_single_name() == key) return option;
  }
  return nullptr;
}

/// `settings` with each key replaced by its option's first name; Error(Usage) naming a key
/// that is no option.
Json canonicalKeys(const CLI::App& app, const Json& settings) {
  Json out = Json::object();
  for (const auto& [key, value] : settings.items()) {
    const CLI::Option* option = optionForKey(app, key);
    if (!option) fail(ErrorKind::Usage, "unknown key '{}': not an option of glint bake (see glint bake --help)", printable(key));
    out[option->get_single_name()] = value;
  }
  return out;
}

/// The argument list `glint bake` gets for settings (canonical keys, later layers winning):
/// positionals first, then the options in the command's order; a flag appears when true;
/// a number is written as JSON writes it; a relative path (a FILE option) is made relative
/// to `base`, the batch file's folder.
std::vector<std::string> argumentsFor(const CLI::App& app, const std::vector<const Json*>& layers, const fs::path& base) {
  Json merged = Json::object();
  for (const Json* layer : layers)
    for (const auto& [key, value] : layer->items()) merged[key] = value;
  std::vector<std::string> positionals, named;
  for (const CLI::Option* option : app.get_options()) {
    const std::string& key = option->get_single_name();
    if (option == app.get_help_ptr() || !merged.contains(key)) continue;
    const Json& value = merged[key];
    const std::string spelling = option->get_snames().empty() ? "--" + key : "-" + option->get_snames().front();
    if (option->get_expected_max() == 0) {  // a flag
      if (!value.is_boolean()) fail(ErrorKind::Usage, "'{}' is a flag: true or false, got {}", key, printable(value.dump()));
      if (value.get<bool>()) named.push_back(spelling);
      continue;
    }
    std::string text;
    if (value.is_string()) text = value.get<std::string>();
    else if (value.is_number()) text = value.dump();
    else fail(ErrorKind::Usage, "'{}' takes a value (a string or a number), got {}", key, printable(value.dump()));
    if (option->get_type_name() == kFile && !text.empty() && text != "-") {
      fs::path path(text);
      if (path.is_relative() && !base.empty()) path = base / path;
      text = path.string();
      if (text.starts_with('-')) text = "./" + text;  // a file, not an option
    }
    if (option->get_positional()) {
      positionals.push_back(text);
    } else if (text.starts_with('-')) {  // a negative number: one word, not taken for an option
      named.push_back("--" + key + "=" + text);
    } else {
      named.push_back(spelling);
      named.push_back(text);
    }
  }
  const bool dashed = std::any_of(positionals.begin(), positionals.end(), [](const std::string& p) { return p.starts_with('-'); });
  if (dashed) {  // after "--", where nothing is an option
    named.push_back("--");
    named.insert(named.end(), positionals.begin(), positionals.end());
    return named;
  }
  positionals.insert(positionals.end(), named.begin(), named.end());
  return positionals;
}

/// Parses a job's argument list exactly as the command line is parsed: a fresh CLI::App with
/// the bake command's options. Error(Usage) with CLI11's message.
BakeArgs parseJob(const std::vector<std::string>& arguments) {
  CLI::App app{"glint bake", "bake"};
  BakeArgs args;
  addBakeOptions(app, args, true);
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    fail(ErrorKind::Usage, "{}", e.what());
  }
  return args;
}

struct BatchRequest {
  std::string file;  ///< --batch, as typed
  int job = -1;      ///< --job; -1: every job
  bool list = false; ///< --list
};

struct BatchJob {
  std::string where;  ///< "bake: jobs.json job 2 (barrel_low.obj)", for messages
  std::vector<std::string> arguments;
  BakeArgs args;
};

/// Every job of a batch through the command line's option parsing: its argument list
/// (defaults, then the job, then `commandLine`, later layers winning) and its parsed options.
std::vector<BatchJob> parseBatchJobs(const BatchFile& batch, const std::string& file, const Json& commandLine) {
  const int count = int(batch.jobs.size());
  CLI::App prototype{"glint bake", "bake"};
  BakeArgs unused;
  addBakeOptions(prototype, unused, true);
  const fs::path base = fs::path(file).parent_path();
  Json defaults;
  try {
    defaults = canonicalKeys(prototype, batch.defaults);
  } catch (const Error&) {
    rethrowIn(fmt::format("bake: {} defaults", file));
  }
  std::vector<BatchJob> jobs(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    BatchJob& job = jobs[std::size_t(i)];
    const Json& raw = batch.jobs[std::size_t(i)];
    const Json* low = raw.contains("low") ? &raw["low"] : batch.defaults.contains("low") ? &batch.defaults["low"] : nullptr;
    job.where = fmt::format("bake: {} job {}", file, i);
    if (low && low->is_string()) job.where += fmt::format(" ({})", printable(low->get<std::string>()));
    try {
      const Json settings = canonicalKeys(prototype, raw);
      job.arguments = argumentsFor(prototype, {&defaults, &settings, &commandLine}, base);
      job.args = parseJob(job.arguments);
    } catch (const Error&) {
      rethrowIn(job.where);
    }
  }
  return jobs;
}

/// glint bake --batch. `cmd` is the parsed bake command: the options given with --batch
/// (except --json, the batch's own report) apply to every job.
int runBatch(const CLI::App& cmd, const BakeArgs& given, const BatchRequest& request,
             const std::vector<const CLI::Option*>& batchOptions) {
  const BatchFile batch = loadBatch(request.file);
  const int count = int(batch.jobs.size());
  if (request.job >= count || request.job < -1 || (request.job == -1 && cmd.get_option("--job")->count() > 0))
    fail(ErrorKind::Usage, "bake: --job {} is out of range: {} has {} job{} (0 to {})", request.job, request.file, count,
         count == 1 ? "" : "s", count - 1);

  // Options given on the command line, for every job (the batch's --json excepted).
  Json commandLine = Json::object();
  for (const CLI::Option* option : cmd.get_options()) {
    if (option == cmd.get_help_ptr() || option->count() == 0 || option->get_positional() ||
        option == cmd.get_option("--json") ||
        std::find(batchOptions.begin(), batchOptions.end(), option) != batchOptions.end())
      continue;
    if (option->get_expected_max() == 0) commandLine[option->get_single_name()] = true;
    else commandLine[option->get_single_name()] = option->results().back();
  }

  // Every job through the command line's option parsing, before anything runs.
  std::vector<BatchJob> jobs = parseBatchJobs(batch, request.file, commandLine);
  std::vector<int> selected;
  for (int i = 0; i < count; ++i)
    if (request.job < 0 || request.job == i) selected.push_back(i);

  if (request.list) {
    for (int i : selected) {
      std::string line = "glint bake";
      for (const std::string& word : jobs[std::size_t(i)].arguments) line += " " + shellWord(word);
      std::printf("%s\n", line.c_str());
    }
    std::fflush(stdout);
    return 0;
  }

  // The whole batch's files: no output is an input or another output of any job (also with
  // --job, so that every farm task agrees on whether the file is valid).
  std::vector<FileUse> inputs{{request.file, "the batch file"}}, outputs;
  for (int i = 0; i < count; ++i) {
    const BakeFiles files = bakeFiles(jobs[std::size_t(i)].args);
    const auto named = [i](const FileUse& f) {
      return FileUse{f.path, f.role.starts_with("the ") ? fmt::format("job {}'s {}", i, f.role.substr(4))
                                                        : fmt::format("job {} {}", i, f.role)};
    };
    for (const FileUse& f : files.inputs) inputs.push_back(named(f));
    for (const FileUse& f : files.outputs) outputs.push_back(named(f));
  }
  outputs.push_back({given.tool.json, "--json"});
  try {
    checkDistinctFiles(inputs, outputs);
    if (!given.tool.json.empty() && given.tool.json != "-") checkWritable(given.tool.json);
  } catch (const Error&) {
    rethrowIn(fmt::format("bake: {}", request.file));
  }
  // Every job's own checks (options, folders, memory), each as its bake will make them.
  for (const BatchJob& job : jobs) {
    try {
      ToolRun check("bake", job.args.tool);
      checkBake(job.args, check);
    } catch (const Error&) {
      rethrowIn(job.where);
    }
  }

  // One job after another: each bake already uses every core.
  const auto start = std::chrono::steady_clock::now();
  const log::Level level = log::level();
  if (given.tool.quiet && level < log::Level::Warn) log::setLevel(log::Level::Warn);
  struct Outcome {
    int job = 0;
    double seconds = 0.0;
    int status = 0;
    std::string error;
  };
  std::vector<Outcome> outcomes;
  Json reports = Json::array();
  HighCache highCache;  // jobs sharing a high poly read it and build its BVH once
  for (int i : selected) ++highCache.usesLeft[jobs[std::size_t(i)].args.high];
  std::optional<ErrorKind> firstFailure;
  for (std::size_t k = 0; k < selected.size(); ++k) {
    const int i = selected[k];
    const BatchJob& job = jobs[std::size_t(i)];
    const std::string step = fmt::format("{}/{}", k + 1, selected.size());
    log::info("bake {}: job {}: {} → {}", step, i, job.args.low, job.args.output);
    Outcome outcome{.job = i};
    Json entry = Json::object();
    entry["job"] = i;
    ToolRun run("bake", job.args.tool);
    try {
      BakePlan plan = checkBake(job.args, run);
      plan.options.progressLabel = "bake " + step;
      runBake(job.args, std::move(plan), run, &highCache);
      entry["status"] = "ok";
      entry.update(run.finish());
    } catch (const Error& e) {
      if (e.kind() == ErrorKind::Interrupted) {
        log::setLevel(level);
        throw;  // Ctrl-C stops the batch: exit 130, no partial file
      }
      outcome.status = exitCode(e.kind());
      outcome.error = fmt::format("{}: {}", job.where, e.what());
      log::error("{}", outcome.error);
      if (!firstFailure) firstFailure = e.kind();
      entry["status"] = "failed";
      entry["exit_status"] = outcome.status;
      entry["error"] = outcome.error;
      entry.update(run.completedReport());
    }
    highCache.done(job.args.high);
    outcome.seconds = run.elapsed();
    outcomes.push_back(outcome);
    reports.push_back(std::move(entry));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::size_t failed = std::size_t(std::count_if(outcomes.begin(), outcomes.end(), [](const Outcome& o) { return o.status != 0; }));
  log::info("bake: {}: {} job{} in {:.2f} s, {} ok, {} failed", request.file, outcomes.size(),
            outcomes.size() == 1 ? "" : "s", seconds, outcomes.size() - failed, failed);
  for (const Outcome& o : outcomes) {
    log::info("  job {:<3} {:<40} {:7.2f} s  {}", o.job, jobs[std::size_t(o.job)].args.output, o.seconds,
              o.status == 0 ? std::string("ok") : fmt::format("failed (exit {})", o.status));
  }
  log::setLevel(level);

  if (!given.tool.json.empty()) {
    Json report;
    report["tool"] = "bake";
    report["version"] = GLINT_VERSION;
    report["batch"] = request.file;
    report["jobs"] = std::move(reports);
    report["failed"] = failed;
    report["seconds"] = {{"total", seconds}};
    report["peak_memory_mib"] = ToolRun::peakMemoryMiB();
    const std::string text = report.dump(2) + "\n";
    if (given.tool.json == "-") {
      std::fputs(text.c_str(), stdout);
      std::fflush(stdout);
    } else {
      writeTextAtomically(given.tool.json, text);
    }
  }
  if (firstFailure) {  // each failure was printed when it happened; the exit status is the first one's
    std::string which;
    std::size_t named = 0;
    for (const Outcome& o : outcomes) {
      if (o.status == 0) continue;
      if (++named > 10) {
        which += ", ...";
        break;
      }
      which += fmt::format("{}{}", named == 1 ? "" : ", ", o.job);
    }
    fail(*firstFailure, "bake: {}: {} of {} job{} failed (job{} {})", request.file, failed, outcomes.size(),
         outcomes.size() == 1 ? "" : "s", failed == 1 ? "" : "s", which);
  }
  return 0;
}

}  // namespace

std::vector<BatchBake> batchBakes(const std::string& file) {
  const BatchFile batch = loadBatch(file);
  std::vector<BatchBake> bakes;
  for (const BatchJob& job : parseBatchJobs(batch, file, Json::object())) {
    const BakeFiles files = bakeFiles(job.args);
    BatchBake b{.where = job.where};
    for (const FileUse& f : files.inputs)
      if (!f.path.empty()) b.inputs.push_back(f.path);
    for (const FileUse& f : files.outputs)
      if (!f.path.empty() && f.path != "-") b.outputs.push_back(f.path);
    bake::BakeOptions options;
    const ivec2 size = parseSize(job.args.size);
    options.width = size.x;
    options.height = size.y;
    options.samples = job.args.samples;
    options.ambientOcclusion = !job.args.ao.empty();
    options.aoSamples = job.args.aoSamples;
    options.heightMap = !job.args.height.empty();
    options.missMask = !job.args.missMask.empty();
    options.bentNormals = !job.args.bentNormal.empty();
    options.thickness = !job.args.thickness.empty();
    options.curvature = !job.args.curvature.empty();
    options.positionMap = !job.args.position.empty();
    options.opacity = !job.args.opacity.empty();
    options.materialId = !job.args.materialId.empty();
    options.vertexColor = !job.args.vertexColor.empty();
    b.memoryMiB = bake::estimatePeakMemoryMiB(options, {job.args.low, job.args.high, job.args.cage});
    bakes.push_back(std::move(b));
  }
  return bakes;
}

Command bakeCommand(CLI::App& app, const GlobalOptions& global) {
  auto a = std::make_shared<BakeArgs>();
  auto request = std::make_shared<BatchRequest>();
  auto* cmd = app.add_subcommand("bake", "Bake a high-poly mesh's detail into a normal map for a low-poly mesh");
  cmd->footer(kFooter);
  addBakeOptions(*cmd, *a, false);  // LOW HIGH -o are checked in run: --batch replaces them
  CLI::Option* batch = cmd->add_option("--batch", request->file, "Run the bakes a JSON file lists (instead of LOW "
                                       "HIGH -o; see the footer)")->type_name(kFile);
  CLI::Option* job = cmd->add_option("--job", request->job, "With --batch: run only this job (0-based)")
                         ->type_name("I")->needs(batch);
  CLI::Option* list = cmd->add_flag("--list", request->list, "With --batch: print the jobs as glint bake command "
                                    "lines, run nothing")->needs(batch);
  const std::vector<const CLI::Option*> batchOptions{batch, job, list};

  return Command{.run = [a, request, cmd, batchOptions, &global] {
    (void)global;
    CLI::Option* low = cmd->get_option("low");
    CLI::Option* high = cmd->get_option("high");
    if (!request->file.empty() || cmd->get_option("--batch")->count() > 0) {
      if (low->count() > 0 || high->count() > 0)
        fail(ErrorKind::Usage, "bake: --batch takes the meshes from {}: give no LOW HIGH with it", request->file);
      return runBatch(*cmd, *a, *request, batchOptions);
    }
    for (const char* name : {"low", "high", "--output"})
      if (cmd->get_option(name)->count() == 0) fail(ErrorKind::Usage, "{} is required (see --help)", name);
    ToolRun run("bake", a->tool);
    BakePlan plan = checkBake(*a, run);
    runBake(*a, std::move(plan), run);
    run.finish();
    return 0;
  },
  // The OpenImageIO module is started by the command itself, only when it reads an image
  // or writes another format than PNG (libspng): its 0.3 s of dynamic linking would take
  // the second core from the mesh parser.
  .readsImages = false};
}

}  // namespace glint::app
