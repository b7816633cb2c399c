#pragma once
// glint/cut/job.h — `glint cut` as a library call: a job from scene files to written outputs,
// with the command's options, checks, memory estimate, warnings, report and atomic writes
// (all of a run's outputs or none: core/file.h), and how a farm splits and joins it.
//
/// ```cpp
/// glint::cut::CutJob job;
/// job.inputs = {"room.glb"};
/// job.outputs = {"room_cut.glb", "room_cut.ply"};
/// job.lights = {"0,4,0,lamp"};
/// glint::ToolSettings settings;
/// settings.json = "report.json";
/// glint::ToolRun run("cut", settings);
/// glint::cut::runJob(job, run);  // the checks, the cut, both outputs staged
/// run.finish();                  // report.json and both outputs renamed into place together
/// ```
//
// The command (`glint cut`), `glint farm cut` and the Python module parse their options with
// addOptions, so the three take the same options with the same checks.
#include "glint/core/tool.h"
#include "glint/farm/farm.h"

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace glint::cut {

/// A cut as typed: files and lights as text, parsed and checked by checkJob.
struct CutJob {
  std::vector<std::string> inputs;   ///< scene files (OBJ, PLY, glTF/GLB, FBX, ...), joined in order
  std::vector<std::string> outputs;  ///< .glb, .gltf or .ply, one or more; with `shard`, the one shard file
  std::vector<std::string> lights;   ///< "x,y,z[,name]"; empty: the glTF inputs' KHR_lights_punctual lights
  std::string shard;                 ///< "i/n": cut only shard i of n into outputs[0]
  std::vector<std::string> merge;    ///< shard files of one job to join into the outputs (instead of cutting)
};

/// The options of `glint cut` (inputs, -o, --light, --shard, --merge), bound to `job`; the
/// tool options (--threads, -q, --max-memory, --json) are addToolOptions'.
void addOptions(CLI::App& command, CutJob& job);
/// `glint cut --help`'s footer: how beams and tags work, the outputs, examples, exit codes.
const char* helpFooter();

/// Everything checked before a file is read: no output is an input or another output (by
/// file identity), --shard and --merge not together, one -o with --shard, output formats,
/// the lights' text, writable folders. Error(Usage) or Error(Output), one line.
void checkJob(const CutJob& job, const ToolSettings& settings);

/// checkJob, then the cut (or the shard, or the merge): the outputs are written through the
/// run (staged until run.finish()), its report filled (inputs, lights, outputs and toJson of
/// the stats or the shard), warnings recorded. Error(Input) for an unreadable scene,
/// Error(Usage) for no lights or a --max-memory the job exceeds, Error(Interrupted).
void runJob(const CutJob& job, ToolRun& run);

/// The job as `glint cut` arguments (inputs, then -o, --light, --shard, --merge as set).
std::vector<std::string> arguments(const CutJob& job);

/// The job split into `split.pieces` shards (`glint cut --shard i/n`) and their merge, each
/// with the files made absolute; checked first as checkJob does (and --shard or --merge
/// refused: the farm gives them). Reads the scene once for the memory estimate.
farm::Plan farmPlan(const CutJob& job, const ToolSettings& settings, const farm::Split& split);

}  // namespace glint::cut
