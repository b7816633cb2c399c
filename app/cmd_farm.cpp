// glint farm TOOL ... — a tool job split over a Slurm cluster (or this machine): the pieces
// as a job array, the join as a job that depends on it (farm/farm.h). Each `glint farm TOOL`
// takes every option of `glint TOOL` — the tool's library defines them (cut/job.h,
// post/job.h, scenes/render_job.h, bake/job.h) and plans the job with the command's
// own checks — plus the farm's options. Thin: parse, plan, submit, follow.
#include "common.h"

#include "glint/bake/job.h"
#include "glint/core/error.h"
#include "glint/core/text.h"
#include "glint/farm/farm.h"
#include "glint/farm/run.h"
#include "glint/post/job.h"
#include "glint/scenes/render_job.h"
#if GLINT_HAS_CUT
#include "glint/cut/job.h"
#endif

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace glint::app {

namespace {

namespace fs = std::filesystem;

/// The farm's options: what `glint farm` asks besides the tool's own (farm::RunOptions) and
/// the pieces and memory (farm::Split).
struct FarmArgs {
  farm::RunOptions run;
  std::string mem;
  int pieces = 0;
};

constexpr const char* kCommonHelp = R"(
Farm options (every `glint farm` subcommand):
  --partition P, --time T, --mem SIZE, --cpus-per-task N   what each task asks Slurm for
  --work-dir DIR   intermediates, scripts and logs, on a filesystem every node sees
                   (default: the output's directory); the job's directory is
                   DIR/<tool>-<key>, named by a hash of the inputs and options
  --scheduler S    slurm (the default) or local: this machine runs the tasks as child
                   processes, with the same scripts, dependencies and resubmit rules
  --dry-run        print the batch scripts (plain glint calls) and submit nothing
  --wait           follow the tasks with a progress bar; exit 0 only when the output exists;
                   Ctrl-C stops following (the jobs go on)

Before anything is submitted, the job is checked as the tool checks it (an output that is
an input, a bad option, an unwritable folder: the tool's own message and exit code).
Pieces are named by a hash of their command line and of each input's path, size and time:
running the same command again submits only the pieces that are missing or failed (a
piece still queued or running is waited for), then the join; a second identical command
at the same time follows the first. A piece that fails or is cancelled stops the join;
--wait names it, its exit code and its log, and exits non-zero (the task's exit code); a
task Slurm can never start (more CPUs than a node has) is named and cancelled (exit 2).
Intermediates are removed only after a successful join. Slurm is reached through sbatch,
squeue, scontrol, scancel and sinfo (Debian: slurm-client); SLURM_CONF says which cluster.
File names and options reach the batch scripts quoted; a line break in the work
directory's name is refused. docs/farm.md has a studio set-up.)";

constexpr const char* kFarmOptions[] = {"--partition", "--time", "--mem", "--cpus-per-task", "--work-dir",
                                       "--dry-run", "--wait", "--scheduler"};

/// The farm's options, added to a tool's subcommand.
void addFarmOptions(CLI::App& cmd, FarmArgs& a, const char* piecesName, const char* piecesHelp) {
  // A tool option of the same name gives way (render's --time, a scene time, means nothing
  // for a video, which --frames and --fps time).
  for (const char* name : kFarmOptions)
    if (CLI::Option* clash = cmd.get_option_no_throw(name)) cmd.remove_option(clash);
  if (piecesName) cmd.add_option(piecesName, a.pieces, piecesHelp)->required()->check(CLI::Range(1, 100000));
  cmd.add_option("--partition", a.run.partition, "Slurm partition for every task (default: the cluster's)");
  cmd.add_option("--time", a.run.time, "Slurm time limit per task, e.g. 2:00:00 (default: the partition's)");
  cmd.add_option("--mem", a.mem, "Memory per task: MiB, or 512M, 4G (default: the tool's own estimate for the job, "
                                 "which each piece also gets as --max-memory)");
  cmd.add_option("--cpus-per-task", a.run.cpusPerTask, "CPUs per task (also the pieces' --threads; default: Slurm's, one)")
      ->check(CLI::Range(1, 4096));
  cmd.add_option("--work-dir", a.run.workDir, "Directory for intermediates, scripts and logs, seen by every node (default: "
                                          "the output's directory)");
  cmd.add_option("--scheduler", a.run.scheduler, "slurm, or local: run the tasks on this machine as child processes (same "
                                             "scripts and rules)")
      ->check(CLI::IsMember({"slurm", "local"}))
      ->capture_default_str();
  cmd.add_flag("--dry-run", a.run.dryRun, "Print the batch scripts and submit nothing");
  cmd.add_flag("--wait", a.run.wait, "Follow the tasks to the end; exit 0 only when the joined output exists");
}

farm::Split splitOf(const FarmArgs& a) {
  farm::Split split{.pieces = std::max(1, a.pieces), .cpusPerTask = a.run.cpusPerTask, .workDir = a.run.workDir};
  if (!a.mem.empty()) split.memoryMiB = std::int64_t(std::ceil(parseMemorySize(a.mem, "--mem")));
  return split;
}

/// One tool `glint farm` splits: its subcommand, its options (the library's), its plan.
struct FarmTool {
  const char* name;
  const char* description;
  const char* piecesName;  ///< --shards or --chunks; null: a piece per job of a batch file
  const char* piecesHelp;
  /// Adds the tool's options to `cmd` and returns what plans the parsed job.
  std::function<std::function<farm::Plan(const farm::Split&)>(CLI::App& cmd)> add;
};

std::vector<FarmTool> farmTools() {
  std::vector<FarmTool> tools;
#if GLINT_HAS_CUT
  tools.push_back({"cut", "`glint cut` over a Slurm cluster: `--shard i/N` tasks, then `--merge`", "--shards",
                   "Shards: `glint cut --shard i/N` tasks, then `--merge` (byte-identical to one run)", [](CLI::App& cmd) {
                     auto job = std::make_shared<cut::CutJob>();
                     auto settings = std::make_shared<ToolSettings>();
                     cut::addOptions(cmd, *job);
                     addToolOptions(cmd, *settings, "the merge's report");
                     return std::function<farm::Plan(const farm::Split&)>(
                         [job, settings](const farm::Split& split) { return cut::farmPlan(*job, *settings, split); });
                   }});
#endif
  tools.push_back({"post", "`glint post` over a Slurm cluster: `--frames a:b` tasks starting on keyframes, then "
                   "`--concat`", "--chunks",
                   "Chunks: `glint post --frames a:b` tasks starting on keyframes, then `--concat`", [](CLI::App& cmd) {
                     auto args = std::make_shared<post::PostArgs>();
                     auto settings = std::make_shared<ToolSettings>();
                     post::addOptions(cmd, *args);
                     addToolOptions(cmd, *settings, "the join's report");
                     return std::function<farm::Plan(const farm::Split&)>([args, settings](const farm::Split& split) {
                       return post::farmPlan(post::makeJob(*args), *settings, split);
                     });
                   }});
  tools.push_back({"render", "`glint render` over a Slurm cluster: `--frames a:b` tasks, then `glint post --concat`",
                   "--chunks", "Chunks: `glint render --frames a:b` tasks, then `glint post --concat`", [](CLI::App& cmd) {
                     auto args = std::make_shared<scenes::RenderArgs>();
                     scenes::addOptions(cmd, *args);
                     return std::function<farm::Plan(const farm::Split&)>(
                         [args](const farm::Split& split) { return scenes::farmPlan(*args, split); });
                   }});
  tools.push_back({"bake", "`glint bake --batch JOBS.json` over a Slurm cluster: one task per bake (`--job i`), no "
                   "join; every option of glint bake applies to every job", nullptr, nullptr, [](CLI::App& cmd) {
                     auto request = std::make_shared<bake::BatchRequest>();
                     auto job = std::make_shared<bake::BakeJob>();
                     cmd.add_option("jobs", request->file, "Batch file: {\"defaults\": {...}, \"bakes\": [...]} (see "
                                                           "glint bake --help)")
                         ->required();
                     bake::addOptions(cmd, *job, bake::Meshes::None);
                     CLI::App* app = &cmd;
                     return std::function<farm::Plan(const farm::Split&)>([request, job, app](const farm::Split& split) {
                       std::vector<const CLI::Option*> farmOwn{app->get_option("--json")};  // the batch's report
                       for (const char* name : kFarmOptions) farmOwn.push_back(app->get_option_no_throw(name));
                       request->overrides = bake::givenOptions(*app, farmOwn);
                       request->tool = job->tool;
                       return bake::farmPlan(*request, split);
                     });
                   }});
  return tools;
}

}  // namespace

Command farmCommand(CLI::App& app, const GlobalOptions&) {
  auto* farmCmd = app.add_subcommand("farm", "Split a cut, post, render or bake job over a Slurm cluster: the pieces as a "
                                             "job array, then the join");
  farmCmd->require_subcommand(1);
  farmCmd->fallthrough();
  farmCmd->footer(std::string(R"(Examples:
  glint farm cut city.glb -o city_cut.glb --light 0,40,10 --shards 16 --wait
  glint farm post film.mp4 -o film_sepia.mp4 -e sepia --chunks 8 --wait
  glint farm render pipedream -o pipedream.mp4 --frames 0:600 --fps 30 --size 1920x1080 --chunks 8
  glint farm bake assets.json --samples 16 --wait
  glint farm post film.mp4 -o graded.mkv --codec ffv1 -e sepia --chunks 4 --dry-run
  glint farm post film.mp4 -o graded.mkv --codec ffv1 -e sepia --chunks 2 --scheduler local --wait
)") + kCommonHelp);

  struct Parsed {
    CLI::App* cmd;
    std::shared_ptr<FarmArgs> args;
    std::function<farm::Plan(const farm::Split&)> plan;
  };
  auto parsed = std::make_shared<std::vector<Parsed>>();
  for (const FarmTool& tool : farmTools()) {
    CLI::App* cmd = farmCmd->add_subcommand(tool.name, tool.description);
    auto args = std::make_shared<FarmArgs>();
    auto plan = tool.add(*cmd);
    cmd->footer(fmt::format("Every option of `glint {}` (see glint {} --help), plus the farm's.", tool.name, tool.name) +
                kCommonHelp);
    addFarmOptions(*cmd, *args, tool.piecesName, tool.piecesHelp);
    parsed->push_back({cmd, args, std::move(plan)});
  }
  return Command{.run = [parsed] {
                   for (const Parsed& p : *parsed) {
                     if (!p.cmd->parsed()) continue;
                     farm::checkScheduler(p.args->run);
                     return farm::run(p.plan(splitOf(*p.args)), p.args->run);
                   }
                   fail(ErrorKind::Usage, "farm: give a subcommand: cut, post, render or bake");
                 },
                 .readsImages = false};
}

}  // namespace glint::app
