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
  if (options.device == Device::Auto && !job.gpuPossible) options.device = Device::Cpu;  // auto will take the CPU
  return estimatePeakMemoryMiB(options, {job.low, job.high, job.cage});
}

bool gpuPossible(const std::string& device, GpuBackend* gpu) {
  return device != "auto" || (gpu && !gpu->onlySoftwareDevices());
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

namespace {

/// A bake's meshes as loaded: the low poly (as parts when its file names bake groups), the
/// high poly (as parts when groups or material IDs need its part names).
struct LoadedMeshes {
  Mesh low;
  std::optional<MeshParts> lowParts;
  std::shared_ptr<const Mesh> high;
  std::shared_ptr<const MeshParts> highParts;
  bool highReused = false;  ///< from the batch's cache: read by an earlier job

  const Mesh& highMesh() const { return highParts ? highParts->mesh : *high; }
};

/// Loads the inputs (never modified: loaded into memory, prepared there). The high poly (the
/// big file) is parsed here while a second thread reads the rest (the low poly, the cage,
/// the detail map into `options`); errors are reported in argument order: low, high, cage,
/// detail.
LoadedMeshes loadMeshes(const BakeJob& a, BakeOptions& options, const GroupNaming& naming, HighMeshCache* cache,
                        ToolRun& run) {
  ToolRun::Phase loading(run, "load");
  LoadedMeshes m;
  // Named parts (bake groups, material ID, vertex colour) are read through Assimp; a low
  // file that does not even contain the low suffix is read as before, in parallel with the high.
  if (!a.noGroups && !a.lowMesh && mentionsText(a.low, naming.lowSuffix)) {
    m.lowParts = loadMeshParts(a.low);
    bool grouped = false;
    for (const std::string& name : m.lowParts->partNames) grouped = grouped || !groupName(name, naming.lowSuffix, false).empty();
    if (!grouped) m.lowParts.reset();
  }
  const bool highAsParts = m.lowParts || options.maps.needs(kHitTriangle);
  auto others = std::async(std::launch::async, [&] {
    Mesh low = m.lowParts ? m.lowParts->mesh : a.lowMesh ? *a.lowMesh : loadMesh(a.low);
    if (!a.cage.empty()) options.cage = loadMesh(a.cage);
    if (!a.detail.empty()) options.detail = HeightDetail{loadImage(a.detail), a.detailScale};
    return low;
  });
  // Rays need no shared vertices: skipping Assimp's vertex joining halves the load.
  std::exception_ptr highError;
  try {
    if (a.highMesh) {
      if (highAsParts) m.highParts = std::make_shared<const MeshParts>(MeshParts{.mesh = *a.highMesh});
      else m.high = a.highMesh;
    } else if (HighMeshCache::Entry* e = cache ? cache->find(a.high, highAsParts) : nullptr) {
      m.high = e->mesh;
      m.highParts = e->parts;
      m.highReused = true;
    } else {
      if (highAsParts) m.highParts = std::make_shared<const MeshParts>(loadMeshParts(a.high, {.joinVertices = false}));
      else m.high = std::make_shared<const Mesh>(loadMesh(a.high, {.joinVertices = false}));
      if (cache && cache->usesLeft[a.high] > 1) cache->add(a.high, m.high, m.highParts);
    }
  } catch (...) {
    highError = std::current_exception();
  }
  m.low = others.get();
  if (highError) std::rethrow_exception(highError);
  return m;
}

/// The bake groups of the low poly's parts matched with the high poly's by name; none when
/// the low poly has no groups. A high file that names no part with the high suffix (a PLY
/// has no part names) is baked against as one, said once, rather than a bake that stops.
GroupMatch matchBakeGroups(const BakeJob& a, LoadedMeshes& m, const GroupNaming& naming, ToolRun& run) {
  if (m.lowParts) {
    bool highNamed = false;
    for (const std::string& name : m.highParts->partNames) highNamed = highNamed || !groupName(name, naming.highSuffix, true).empty();
    if (!highNamed) {
      run.warn(fmt::format("bake groups: the low poly names its parts with '{}' but '{}' names no part with '{}' (no "
                           "part names): baked against the whole high poly, without groups (--no-groups says so "
                           "up front)", naming.lowSuffix, a.high, naming.highSuffix));
      m.lowParts.reset();
    }
  }
  if (!m.lowParts) return {};
  GroupMatch match = matchGroups(*m.lowParts, *m.highParts, naming);
  // (unmatched parts are warned about by the bake, by name)
  log::info("bake: {} bake group{} matched by name", match.groups.size(), match.groups.size() == 1 ? "" : "s");
  return match;
}

/// The UDIM tiles to bake: UVs beyond the unit square, or outputs named with <UDIM>, bake one
/// image per tile; none for a plain bake. Distances given as a share of the model become the
/// whole low poly's, in every tile.
std::vector<UdimTile> udimTiles(const BakeJob& a, const Mesh& low, BakeOptions& options, ToolRun& run) {
  bool named = false, unnamed = false;
  for (const MapInfo& m : mapTable()) {
    const std::string& path = a.path(m.map);
    if (path.empty()) continue;
    (hasUdimToken(path) ? named : unnamed) = true;
  }
  if (!named && !spansUdimTiles(low)) return {};
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
  const float diagonal = low.bounds().diagonal();
  for (Distance* d : {&options.maxFront, &options.maxRear, &options.aoDistance, &options.thicknessDistance,
                      &options.curvatureRadius})
    *d = Distance{d->resolve(diagonal), false};
  return std::move(split.tiles);
}

/// The report's fields known before the bake: inputs, outputs, every map by kind, options.
void startReport(const BakeJob& a, const BakeOptions& options, const GroupMatch& match, bool cached, bool highReused,
                 ToolRun& run) {
  auto& report = run.report();
  report["low"] = a.low;
  report["high"] = a.high;
  if (cached) report["high_mesh_reused"] = highReused;
  report["output"] = a.output;
  Json maps = Json::object();  // every map written, by kind, in the table's order
  for (const MapInfo& m : mapTable())
    if (!a.path(m.map).empty()) maps[m.reportKey] = a.path(m.map);
  report["maps"] = std::move(maps);
  report.update(toJson(options));
  if (match.grouped()) report.update(toJson(match));
}

/// Every map of one tile (tile 0: a plain bake) to its file, or to the job's sink. The files
/// are written in parallel: compressing them is most of the write phase (six 2048² PNGs:
/// 2.4 s one after another).
void writeMaps(const BakeJob& a, BakeResult& result, int tile, const std::function<std::string(const std::string&)>& file,
               ToolRun& run) {
  ToolRun::Phase writing(run, "write");
  const BakeStats& s = result.stats;
  if (a.sink) {  // in memory: each map as its file would hold it
    a.sink(Map::Normal, tile, std::move(result.normal));
    for (const MapInfo& m : mapTable())
      if (m.map != Map::Normal && !a.path(m.map).empty())
        a.sink(m.map, tile, m.forOutput(result.map(m.map), outputType(a.path(m.map), a.bits), s));
    return;
  }
  std::vector<std::function<void()>> writes;
  writes.emplace_back([&] { saveImage(result.normal, file(a.output)); });  // quantized as it was baked
  for (const MapInfo& m : mapTable()) {
    const std::string& path = a.path(m.map);
    if (m.map == Map::Normal || path.empty()) continue;
    writes.emplace_back([&m, &path, &result, &s, &file, &a] {
      saveImage(m.forOutput(result.map(m.map), outputType(path, a.bits), s), file(path));
    });
  }
  tbb::parallel_for_each(writes.begin(), writes.end(), [](const std::function<void()>& write) { write(); });
}

/// A UDIM tile's low poly with its cage (the cage's vertices of the tile's triangles: the
/// cage has the low poly's vertices and triangles) and its parts (those of its triangles).
Mesh tileCage(const UdimTile& tile, const Mesh& wholeCage) {
  Mesh cage = tile.low;
  for (std::size_t k = 0; k < tile.lowVertices.size(); ++k) cage.positions[k] = wholeCage.positions[tile.lowVertices[k]];
  return cage;
}

MeshParts tileParts(const UdimTile& tile, const MeshParts& lowParts) {
  MeshParts parts{.mesh = tile.low, .partNames = lowParts.partNames};
  parts.trianglePart.reserve(tile.lowTriangles.size());
  for (const std::uint32_t t : tile.lowTriangles) parts.trianglePart.push_back(lowParts.trianglePart[t]);
  return parts;
}

/// One tile's bake: its parts matched as the whole low poly's were, against the high poly's
/// parts or the high poly as one. `tileMatch` gets the tile's own match (UDIM with groups).
BakeResult bakeTile(const UdimTile& tile, bool udim, const LoadedMeshes& m, const GroupMatch& match,
                    const GroupNaming& naming, const BakeOptions& options, GroupMatch& tileMatch) {
  if (udim && m.lowParts) {
    const MeshParts parts = tileParts(tile, *m.lowParts);
    tileMatch = matchGroups(parts, *m.highParts, naming);
    return bake(parts, *m.highParts, tileMatch, options);
  }
  if (m.highParts) return bake(m.lowParts ? *m.lowParts : MeshParts{.mesh = tile.low}, *m.highParts, match, options);
  return bake(tile.low, *m.high, options);
}

}  // namespace

void runJob(const BakeJob& job, ToolRun& run, HighMeshCache* cache, GpuBackend* gpu) {
  BakeJob a = job;
  a.gpuPossible = a.gpuPossible && gpuPossible(a.device, gpu);
  BakePlan plan = prepare(a, run);
  BakeOptions& options = plan.options;
  options.gpu = gpu;
  if (cache) options.progressLabel = cache->progressLabel;
  options.progress = run.showProgress();
  options.cancel = &run.cancelFlag();
  if (plan.needsImageIo) preloadImageIo();

  const GroupNaming naming{a.lowSuffix, a.highSuffix};
  LoadedMeshes meshes = loadMeshes(a, options, naming, cache, run);
  if (meshes.highReused) log::info("bake: {}: high mesh reused from an earlier job of the batch (read once)", a.high);
  if (cache && (meshes.highReused || cache->usesLeft[a.high] > 1)) options.sceneCache = &cache->scenes;
  const GroupMatch match = matchBakeGroups(a, meshes, naming, run);
  run.throwIfInterrupted();

  std::vector<UdimTile> tiles = udimTiles(a, meshes.low, options, run);
  const bool udim = !tiles.empty();
  if (!udim) tiles.push_back({.number = 0, .low = meshes.low, .triangles = meshes.low.triangleCount()});
  const std::optional<Mesh> wholeCage = udim ? options.cage : std::nullopt;

  startReport(a, options, match, cache != nullptr, meshes.highReused, run);
  Json tileReports = Json::array();
  const std::string label = options.progressLabel;
  const bool wantsAsset = !a.asset.empty() || !a.preview.empty();
  Asset asset;
  asset.name = fs::path(a.low).stem().string();
  for (const UdimTile& tile : tiles) {
    const std::function<std::string(const std::string&)> file = [&](const std::string& path) {
      return udim ? udimPath(path, tile.number) : path;
    };
    if (udim) options.progressLabel = fmt::format("{} tile {}", label, tile.number);
    if (udim && wholeCage) options.cage = tileCage(tile, *wholeCage);
    GroupMatch tileMatch;
    BakeResult result = bakeTile(tile, udim, meshes, match, naming, options, tileMatch);
    if (wantsAsset) {  // the tile as baked, its groups apart
      const GroupMatch& g = udim ? tileMatch : match;
      const auto groupOf = [&g](std::size_t t) {
        const std::uint32_t group = g.grouped() ? g.lowTriangleGroup[t] : GroupMatch::kNone;
        return group == GroupMatch::kNone ? std::string() : g.groups[group].name;
      };
      addToAsset(asset, result.low, assetMaps(a, result), udim ? std::to_string(tile.number) : std::string(), groupOf);
    }
    const BakeStats s = result.stats;
    run.addSeconds("prepare", s.prepareSeconds);
    run.addSeconds("trace", s.traceSeconds);
    run.addSeconds("dilate", s.dilateSeconds);
    if (s.bvhReused) log::info("bake: {}: BVH reused from an earlier job of the batch", a.high);
    writeMaps(a, result, tile.number, file, run);
    log::info("bake: {} ({} triangles) → {} ({}x{}, {} per texel): {} texels baked, {} padded; {} rays, hit ratio "
              "{:.4f}; {:.2f} s", a.high, meshes.highMesh().triangleCount(), file(a.output), options.width,
              options.height, options.samples, s.coveredTexels, s.paddedTexels, s.rays, s.hitRatio(), run.elapsed());
    for (const auto& w : result.warnings) run.recordWarning(w);
    if (!udim) {
      run.report().update(toJson(s));
    } else {
      Json entry = {{"tile", tile.number}, {"low_triangles_in_tile", tile.triangles}, {"output", file(a.output)}};
      entry.update(toJson(s));
      tileReports.push_back(std::move(entry));
    }
    run.throwIfInterrupted();
  }
  if (udim) run.report()["udim_tiles"] = std::move(tileReports);
  if (wantsAsset) writeAsset(a, asset, run);
}

}  // namespace glint::bake
