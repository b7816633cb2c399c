#pragma once
// glint/bake/job.h — `glint bake` as a library call: one bake (every map, UDIM tiles, bake
// groups) or a batch file of bakes, with the command's options, checks, memory estimate,
// warnings, report and atomic writes (all of a bake's maps or none: core/file.h), and how a
// farm runs a batch (one task per bake).
//
/// ```cpp
/// glint::bake::BakeJob job;
/// job.low = "crate_low.obj";
/// job.high = "crate_high.ply";
/// job.output = "crate_n.png";
/// job.maps[std::size_t(glint::bake::Map::Ao)] = "crate_ao.png";  // --ao
/// job.size = "512x512";
/// glint::ToolRun run("bake", job.tool);
/// glint::bake::runJob(job, run);  // checks, bakes, stages both maps
/// run.finish();                   // both maps renamed into place together
///
/// // A batch file's bakes, one after another, each with the options above as defaults:
/// glint::bake::BatchRequest batch;
/// batch.file = "assets.json";
/// // const int status = glint::bake::runBatch(batch);  // 0, or the first failed job's exit status
/// ```
//
// The command (`glint bake`), batch files, `glint farm bake` and the Python module parse
// options with addOptions: a batch file's key is an option's long name, so the four take the
// same options with the same checks and defaults.
#include "glint/bake/gpu_backend.h"
#include "glint/bake/maps.h"
#include "glint/core/tool.h"
#include "glint/farm/farm.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace glint::bake {

/// A bake as typed: every option of `glint bake` as text, parsed and checked by checkJob.
struct BakeJob {
  std::string low, high, output, size = "1024x1024", space = "tangent", worldMatrix;
  std::string maxFront = "5%", maxRear = "5%", aoDistance = "10%", thicknessDistance = "10%", curvatureRadius = "1%";
  /// `--device`: auto, cpu or gpu (bake/gpu_backend.h's Device); the GPU needs runJob's backend.
  std::string device = "auto";
  std::string cage, detail;
  /// `--asset`: the low poly with its maps as a glTF asset (.glb, or .gltf with the buffer
  /// embedded; bake/asset.h); `--preview`: a folder for the web page that shows it.
  std::string asset, preview;
  /// Each extra map's file, by bake/maps.h's Map (`--ao`, `--curvature`, ...); empty: not
  /// baked. maps[Map::Normal] is unused: the normal map is `output`.
  std::array<std::string, kMapCount> maps;
  /// The file of any map: `output` for the normal map.
  const std::string& path(Map m) const { return m == Map::Normal ? output : maps[std::size_t(m)]; }
  std::string lowSuffix = "_low", highSuffix = "_high";
  int samples = 1, padding = 16, bits = 0, aoSamples = 16;
  float detailScale = 8.0f;
  bool directX = false, frontFirst = false, fillAll = false, noGroups = false;
  ToolSettings tool;  ///< --threads, -q, --max-memory, --json
  bool glDebug = false;  ///< the GPU's context with GL debug output (`glint --gl-debug`)
  /// Whether --device auto may take a GPU in this program: runJob and runBatch set it from
  /// their backend (none, or EGL lists only software renderers: false). The memory estimate
  /// counts a GPU bake's host memory for auto only when it is true.
  bool gpuPossible = true;

  // In memory rather than files (the Python module, glint.bake on arrays):
  /// Meshes that replace the files `low` and `high` (which then only name them in messages;
  /// bake groups need named parts, so a mesh given here bakes as one part).
  std::shared_ptr<const Mesh> lowMesh, highMesh;
  /// Takes every map instead of its file, as the file would hold it (the path's format and
  /// --bits decide the pixel type: "ao.png" U8, "ao.exr" F32), with its UDIM tile (0
  /// without UDIM); `output` and `maps` then only name formats, and no map file is written
  /// or checked (the report, --asset and --preview still are). Called on the job's thread.
  std::function<void(Map map, int tile, Image image)> sink;
};

/// A bake from option settings keyed by long option names, as a batch file's job is read
/// (the same parsing, defaults and checks as the command line): {"low": "a_low.obj",
/// "high": "a_high.ply", "output": "n.png", "samples": 4, "directx": true}. A key may be
/// spelled with underscores for dashes ("max_front"). Relative file paths stay as given.
/// Error(Usage) naming an unknown key or a bad value.
BakeJob jobFromSettings(const nlohmann::ordered_json& settings);

/// Which of LOW, HIGH and -o addOptions declares.
enum class Meshes {
  Required,  ///< a bake's own command line (and each job of a batch file)
  Optional,  ///< `glint bake`, where --batch may replace them
  None       ///< `glint farm bake JOBS.json`: options for every job of the file
};

/// Every option of `glint bake` but the batch ones (--batch, --job, --list), bound to `job`,
/// the tool options (--threads, -q, --max-memory, --json) included.
void addOptions(CLI::App& command, BakeJob& job, Meshes meshes);
/// `glint bake --help`'s footer: UDIM, examples, batch files, the maps (from bake/maps.h's
/// table), bake groups, notes.
std::string helpFooter();

/// The bake's options and maps as data, for a front end that builds its own controls from
/// them rather than copying them (the Blender add-on: glint.bake_options() in Python,
/// `glint bake --describe` for the command): {"maps": [{"name", "option", "label", "help",
/// "summary", "channels", "colour", "parts": it needs the high poly's parts, which a
/// glint.Mesh has not}, ...] in the table's order, "options": {long name:
/// {"help", "default", "kind": "flag"|"file"|"value"}}, "samples": the values --samples takes,
/// "size": {"min", "max"}, "ao_samples": {"min", "max"}, "version"}.
nlohmann::ordered_json describe();

/// The files a bake reads and writes, as its messages name them ("the low poly", "--ao").
std::vector<FileUse> inputFiles(const BakeJob& job);
std::vector<FileUse> outputFiles(const BakeJob& job);

/// Everything a bake checks before it reads an input: its options, its files (no output is
/// an input or another output, by file identity), writable folders, and its memory estimate
/// against --max-memory or, without it, the machine's physical memory. Fails in a
/// millisecond, not after the bake: Error(Usage) or Error(Output), one line.
void checkJob(const BakeJob& job, ToolRun& run);

/// Jobs of one batch that share their high meshes: each high mesh (and its BVH) is read
/// once and kept while a later job still reads it. Opaque; runBatch makes one.
class HighMeshCache;

/// checkJob, then loads the meshes, bakes (every UDIM tile; bake groups when the low and
/// high files name their parts), writes every map through the run (staged until
/// run.finish()) and fills the run's report. `cache`: a batch's shared high meshes. `gpu`:
/// where --device auto|gpu traces (scenes/bake_gpu.h's bakeGpuBackend()); null: the CPU
/// (auto) or Error(NoGpu) (gpu).
void runJob(const BakeJob& job, ToolRun& run, HighMeshCache* cache = nullptr, GpuBackend* gpu = nullptr);

/// The memory a bake is estimated to need (MiB), from its options and input files' sizes.
double estimateMemoryMiB(const BakeJob& job);

// ------------------------------------------------------------------ batches

/// `glint bake --batch FILE [--job I | --list]`, with the options given on the command line.
struct BatchRequest {
  std::string file;               ///< the batch file (JSON)
  int job = -1;                   ///< one job (0-based); -1: every job
  bool list = false;              ///< print the jobs as `glint bake` command lines, run nothing
  /// Options for every job, over the file's defaults and jobs: {"samples": 4, "directx": true}
  /// (keys are long option names; givenOptions reads them off a parsed command line).
  nlohmann::ordered_json overrides = nlohmann::ordered_json::object();
  ToolSettings tool;              ///< the batch's own: --json is the batch report, -q quiets every job
  GpuBackend* gpu = nullptr;      ///< every job's GPU (runJob); null: the CPU only
  bool glDebug = false;           ///< every job's glDebug
};

/// One bake of a batch, parsed and checked as `glint bake --batch` does.
struct BatchJob {
  std::string where;                   ///< "bake: jobs.json job 2 (crate_low.obj)", for messages
  std::vector<std::string> arguments;  ///< its `glint bake` arguments (paths resolved against the file's folder)
  BakeJob job;
};

/// The options given on a parsed command line (those with a value or a flag set), as a
/// batch layer; `except` (the batch options, --json) left out.
nlohmann::ordered_json givenOptions(const CLI::App& command, const std::vector<const CLI::Option*>& except);

/// Every job of a batch file through the command line's option parsing (defaults, then the
/// job, then `overrides`, later layers winning), and every check a bake makes before it runs,
/// for every job (also when one job is asked for: every farm task agrees on the file):
/// distinct files across the whole batch, each job's options, folders and memory.
/// Error(Usage) naming the job and key; Error(Input) for an unreadable file.
std::vector<BatchJob> loadBatch(const std::string& file, const nlohmann::ordered_json& overrides = {});

/// Runs the batch (or lists it): one job after another, each its own report and its own
/// outputs (all of a job's maps or none); a failed job does not stop the others. Returns 0,
/// or throws the first failure's kind naming every failed job; Ctrl-C stops the batch.
int runBatch(const BatchRequest& request);

/// One task per bake of the batch (`glint bake --batch FILE --job i` with the overrides),
/// no join, after loadBatch's checks; each task asks for the largest bake's memory.
farm::Plan farmPlan(const BatchRequest& request, const farm::Split& split);

}  // namespace glint::bake
