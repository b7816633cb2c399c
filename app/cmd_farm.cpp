// glint farm TOOL ... — a tool job split over a Slurm cluster: the pieces as a job array, the
// join as a job that depends on it (farm/farm.h). Each `glint farm TOOL` subcommand takes
// every option of `glint TOOL` itself (the tool's own command registers them, with its own
// checks, so an option error stops before anything is submitted) plus the farm's options;
// the options given are passed on to the pieces and the join as typed.
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"
#include "glint/core/text.h"
#include "glint/farm/farm.h"
#include "glint/render/post/job.h"
#include "glint/video/source.h"
#if GLINT_HAS_CUT
#include "glint/cut/cutter.h"
#include "glint/cut/output.h"
#endif

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <set>

namespace glint::app {

Command cutCommand(CLI::App& app, const GlobalOptions& global);
Command postCommand(CLI::App& app, const GlobalOptions& global);
Command renderCommand(CLI::App& app, const GlobalOptions& global);
Command bakeCommand(CLI::App& app, const GlobalOptions& global);

namespace {

namespace fs = std::filesystem;

struct FarmArgs {
  std::string partition, time, mem, workDir, scheduler = "slurm";
  int cpusPerTask = 0, pieces = 0;
  bool dryRun = false, wait = false;
};

/// Set by Ctrl-C while `--wait` follows the jobs: stop following, say that they go on.
std::atomic<bool> stopFollowing{false};
void onFarmInterrupt(int) { stopFollowing.store(true); }

/// An option of the tool as given on the command line: its name (empty for a positional)
/// and values; flags have no values.
struct Given {
  std::string name;
  std::vector<std::string> values;
  bool flag = false;
};

/// The tool options given, in the order the tool declares them, without the farm's own.
std::vector<Given> givenOptions(CLI::App& cmd, const std::set<const CLI::Option*>& farmOptions) {
  std::vector<Given> given;
  for (const CLI::Option* opt : cmd.get_options()) {
    if (farmOptions.count(opt) || opt->count() == 0) continue;
    if (opt == cmd.get_help_ptr()) continue;
    Given g;
    if (opt->nonpositional()) g.name = opt->get_name();
    g.flag = opt->nonpositional() && opt->get_type_size() == 0;
    if (!g.flag) g.values = opt->results();
    given.push_back(std::move(g));
  }
  return given;
}

const Given* find(const std::vector<Given>& given, const std::string& name) {
  for (const auto& g : given)
    if (g.name == name) return &g;
  return nullptr;
}

std::vector<std::string> positionals(const std::vector<Given>& given) {
  std::vector<std::string> values;
  for (const auto& g : given)
    if (g.name.empty()) values.insert(values.end(), g.values.begin(), g.values.end());
  return values;
}

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

/// The given options as arguments, except `skip`; positionals first (made absolute: tasks
/// run wherever Slurm puts them), then options. `pathOptions` are made absolute too.
std::vector<std::string> arguments(const std::vector<Given>& given, const std::set<std::string>& skip,
                                   const std::set<std::string>& pathOptions = {}) {
  std::vector<std::string> argv;
  for (const auto& g : given)
    if (g.name.empty())
      for (const auto& v : g.values) argv.push_back(absolute(v));
  for (const auto& g : given) {
    if (g.name.empty() || skip.count(g.name)) continue;
    if (g.flag) {
      argv.push_back(g.name);
      continue;
    }
    for (const auto& v : g.values) {
      argv.push_back(g.name);
      argv.push_back(pathOptions.count(g.name) && v != "-" ? absolute(v) : v);
    }
  }
  return argv;
}

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

Pieces are named by a hash of their command line and of each input's path, size and time:
running the same command again submits only the pieces that are missing or failed (a
piece still queued or running is waited for), then the join. A piece that fails or is
cancelled stops the join; --wait names it, its exit code and its log, and exits non-zero
(the task's exit code). Intermediates are removed only after a successful join.
Slurm is reached through sbatch, squeue, scontrol and scancel (Debian: slurm-client);
SLURM_CONF says which cluster. docs/farm.md has a studio set-up.)";

/// The farm's options, added to a tool's own subcommand.
std::set<const CLI::Option*> addFarmOptions(CLI::App& cmd, FarmArgs& a, const char* piecesName, const char* piecesHelp) {
  // A tool option of the same name gives way (render's --time, a scene time, means nothing
  // for a video, which --frames and --fps time).
  for (const char* name : {"--partition", "--time", "--mem", "--cpus-per-task", "--work-dir", "--dry-run", "--wait",
                           "--scheduler"})
    if (CLI::Option* clash = cmd.get_option_no_throw(name)) cmd.remove_option(clash);
  std::set<const CLI::Option*> options;
  if (piecesName)
    options.insert(cmd.add_option(piecesName, a.pieces, piecesHelp)->required()->check(CLI::Range(1, 100000)));
  options.insert(cmd.add_option("--partition", a.partition, "Slurm partition for every task (default: the cluster's)"));
  options.insert(cmd.add_option("--time", a.time, "Slurm time limit per task, e.g. 2:00:00 (default: the partition's)"));
  options.insert(cmd.add_option("--mem", a.mem, "Memory per task: MiB, or 512M, 4G (default: the tool's own estimate "
                                                 "for the job, which each piece also gets as --max-memory)"));
  options.insert(cmd.add_option("--cpus-per-task", a.cpusPerTask, "CPUs per task (also the pieces' --threads; "
                                                                  "default: Slurm's, one)")
                     ->check(CLI::Range(1, 4096)));
  options.insert(cmd.add_option("--work-dir", a.workDir, "Directory for intermediates, scripts and logs, seen by every "
                                                         "node (default: the output's directory)"));
  options.insert(cmd.add_option("--scheduler", a.scheduler, "slurm, or local: run the tasks on this machine as child "
                                                            "processes (same scripts and rules)")
                     ->check(CLI::IsMember({"slurm", "local"}))
                     ->capture_default_str());
  options.insert(cmd.add_flag("--dry-run", a.dryRun, "Print the batch scripts and submit nothing"));
  options.insert(cmd.add_flag("--wait", a.wait, "Follow the tasks to the end; exit 0 only when the joined output exists"));
  return options;
}

/// Memory per task in MiB: --mem as typed, or the estimate with a quarter more, rounded up
/// to 64 MiB.
std::int64_t memoryMiB(const FarmArgs& a, double estimateMiB) {
  if (!a.mem.empty()) return std::int64_t(std::ceil(parseMemorySize(a.mem, "--mem")));
  return (std::int64_t(std::ceil(estimateMiB * 1.25)) + 63) / 64 * 64;
}

/// Adds --max-memory and --threads to a tool command when the tool takes them and the
/// user did not give them.
void addLimits(std::vector<std::string>& argv, CLI::App& cmd, const std::vector<Given>& given, std::int64_t mib,
               int threads) {
  if (cmd.get_option_no_throw("--max-memory") && !find(given, "--max-memory") && mib > 0) {
    argv.push_back("--max-memory");
    argv.push_back(std::to_string(mib));
  }
  if (threads > 0 && cmd.get_option_no_throw("--threads") && !find(given, "--threads")) {
    argv.push_back("--threads");
    argv.push_back(std::to_string(threads));
  }
}

/// Error(Input) when the scheduler cannot be used here (sbatch missing): before any work.
void checkScheduler(const FarmArgs& a) {
  if (a.dryRun) return;
  const auto scheduler = a.scheduler == "local" ? farm::localScheduler("/") : farm::slurmScheduler();
  if (auto missing = scheduler->unavailable()) throw Error(ErrorKind::Input, *missing);
}

/// Submits (or prints) the plan and reports; the exit status.
int runFarm(farm::Plan plan, const FarmArgs& a, std::int64_t mib) {
  farm::Resources resources{.partition = a.partition, .time = a.time, .memoryMiB = mib, .cpusPerTask = a.cpusPerTask};
  if (plan.workDir.empty()) plan.workDir = a.workDir.empty() ? fs::path(absolute(plan.outputs.front().string())).parent_path()
                                                             : fs::path(a.workDir);
  // The outputs' folders must exist and be writable: found now, not after the cluster's work.
  for (const auto& output : plan.outputs) checkWritable(output);
  const fs::path localSpool = fs::path(plan.workDir) / "local-jobs";
  std::shared_ptr<farm::Scheduler> scheduler =
      a.scheduler == "local" ? std::shared_ptr<farm::Scheduler>(farm::localScheduler(localSpool)) : farm::slurmScheduler();
  farm::Farm job(std::move(plan), resources, scheduler);
  if (a.dryRun) {
    fmt::print("{}", job.scripts());
    return 0;
  }
  const farm::Submission s = job.submit();
  const std::string outputs = [&] {
    std::string text;
    for (const auto& o : job.plan().outputs) text += (text.empty() ? "" : ", ") + o.string();
    return text;
  }();
  if (s.alreadyJoined) {
    log::info("farm {}: {} already made by this very job (same inputs and options): nothing to submit",
              job.plan().tool, outputs);
    return 0;
  }
  std::string pieces = fmt::format("{} piece{}", s.submitted.size(), s.submitted.size() == 1 ? "" : "s");
  if (!s.reused.empty())
    pieces += fmt::format(" ({} of {} already done or still running: not resubmitted)", s.reused.size(),
                          job.plan().pieces.size());
  log::info("farm {}: {} → {}: submitted {}{}{}; work directory {}", job.plan().tool, job.plan().title, outputs, pieces,
            s.arrayJob.empty() ? "" : fmt::format(" as job array {}", s.arrayJob),
            s.joinJob.empty() ? "" : fmt::format(", join job {}", s.joinJob), job.directory().string());
  if (!a.wait) {
    std::string ids = s.arrayJob;
    if (!s.joinJob.empty()) ids += (ids.empty() ? "" : ",") + s.joinJob;
    fmt::print("{}\n", ids);
    log::info("follow it: squeue -j {}   (or run the same command with --wait)", ids);
    return 0;
  }
  Progress progress("farm " + job.plan().tool, job.plan().pieces.size());
  std::string last;
  stopFollowing.store(false);
  struct sigaction action {}, oldInt {}, oldTerm {};
  action.sa_handler = onFarmInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &oldInt);
  sigaction(SIGTERM, &action, &oldTerm);
  const farm::WaitResult result = job.wait(
      [&](int done, int, const std::string& line) {
        if (std::uint64_t(done) > progress.done()) progress.advance(std::uint64_t(done) - progress.done());
        progress.setDetail(line);
        if (!progress.enabled() && line != last) log::info("farm {}: {}", job.plan().tool, line);
        last = line;
      },
      &stopFollowing);
  sigaction(SIGINT, &oldInt, nullptr);
  sigaction(SIGTERM, &oldTerm, nullptr);
  progress.finish();
  if (result.stopped) {
    std::string ids = job.arrayJob();
    if (!job.joinJob().empty()) ids += (ids.empty() ? "" : " ") + job.joinJob();
    log::warn("farm {}: stopped following; the jobs keep running ({}{}): the same command with --wait follows them "
              "again{}", job.plan().tool, a.scheduler == "local" ? "on this machine, local jobs " : "", ids,
              a.scheduler == "local" ? "" : fmt::format("; scancel {} cancels them", ids));
    return exitCode(ErrorKind::Interrupted);
  }
  if (result.joined) {
    log::info("farm {}: done: {}", job.plan().tool, outputs);
    return 0;
  }
  for (const auto& failure : result.failures) log::error("farm {}: {}", job.plan().tool, failure);
  log::error("farm {}: not joined; run the same command again to redo only the failed pieces", job.plan().tool);
  return result.exitCode;
}

// ------------------------------------------------------------------ the tools

farm::Plan cutPlan(CLI::App& cmd, const std::vector<Given>& given, int shards, std::int64_t& mib, const FarmArgs& a) {
#if GLINT_HAS_CUT
  if (find(given, "--shard") || find(given, "--merge"))
    fail(ErrorKind::Usage, "farm cut: --shard and --merge are what the farm runs; give --shards N");
  const Given* outputs = find(given, "--output");
  const auto inputs = positionals(given);
  farm::Plan plan{.tool = "cut"};
  plan.title = fmt::format("{} → {}", fs::path(inputs.front()).filename().string(),
                           fs::path(outputs->values.front()).filename().string());
  for (const auto& o : outputs->values) plan.outputs.push_back(absolute(o));
  // The estimate of the whole job (every shard loads the whole scene).
  std::vector<cut::Light> gltfLights;
  const Mesh scene = cut::loadScene(std::vector<fs::path>(inputs.begin(), inputs.end()), &gltfLights);
  const Given* lights = find(given, "--light");
  const std::size_t lightCount = lights ? lights->values.size() : gltfLights.size();
  mib = memoryMiB(a, cut::estimatePeakMemoryMiB(scene.triangleCount(), std::max<std::size_t>(lightCount, 1),
                                                a.cpusPerTask));
  const auto common = arguments(given, {"--output", "--json"});
  for (int i = 1; i <= shards; ++i) {
    farm::Piece piece{.label = fmt::format("shard {}/{}", i, shards), .command = {"cut"}, .extension = ".shard"};
    piece.command.insert(piece.command.end(), common.begin(), common.end());
    piece.command.insert(piece.command.end(), {"--shard", fmt::format("{}/{}", i, shards), "-o", farm::kPieceOutput});
    addLimits(piece.command, cmd, given, mib, a.cpusPerTask);
    piece.inputs.assign(inputs.begin(), inputs.end());
    plan.pieces.push_back(std::move(piece));
  }
  plan.join = {"cut"};
  plan.join.insert(plan.join.end(), common.begin(), common.end());
  plan.join.insert(plan.join.end(), {"--merge", farm::kAllPieceOutputs});
  for (const auto& o : outputs->values) plan.join.insert(plan.join.end(), {"-o", absolute(o)});
  if (const Given* json = find(given, "--json")) plan.join.insert(plan.join.end(), {"--json", absolute(json->values.front())});
  addLimits(plan.join, cmd, given, mib, a.cpusPerTask);
  return plan;
#else
  (void)cmd, (void)given, (void)shards, (void)mib, (void)a;
  fail(ErrorKind::Usage, "farm cut: this glint was built without the shadow cutter (GLINT_BUILD_CUT=OFF)");
#endif
}

/// --frames as given (every frame when absent).
FrameRange frameRange(const Given* frames) {
  return frames ? parseFrameRange(frames->values.front(), "--frames") : FrameRange{};
}

farm::Plan postPlan(CLI::App& cmd, const std::vector<Given>& given, int chunks, std::int64_t& mib, const FarmArgs& a) {
  for (const char* refused : {"--camera", "--input", "--concat", "--realtime"})
    if (find(given, refused))
      fail(ErrorKind::Usage, "farm post: {} cannot be split over machines; farm a video file", refused);
  const auto inputs = positionals(given);
  if (inputs.empty() || inputs.front() == "-") fail(ErrorKind::Usage, "farm post: give a video file every node can read");
  const Given* output = find(given, "--output");
  if (!output || output->values.front() == "-") fail(ErrorKind::Usage, "farm post: give -o, a video file");
  const std::string input = absolute(inputs.front()), out = absolute(output->values.front());
  if (video::isImagePath(input)) fail(ErrorKind::Usage, "farm post: '{}' is an image; farm a video", inputs.front());
  const video::FrameIndex index = video::indexFrames(input);
  auto [first, end] = frameRange(find(given, "--frames"));
  if (end < 0 || end > index.frameCount) end = index.frameCount;
  if (first >= end) fail(ErrorKind::Usage, "farm post: frames {}:{} of '{}' ({} frames) select none", first, end,
                         inputs.front(), index.frameCount);
  const auto ranges = farm::splitAtKeyframes(index.keyframes, first, end, chunks);
  if (int(ranges.size()) < chunks)
    log::warn("farm post: '{}' has keyframes for only {} chunk{} of frames {}:{} (asked for {})", inputs.front(),
              ranges.size(), ranges.size() == 1 ? "" : "s", first, end, chunks);
  {
    const video::Source source = video::Source::open(input);
    mib = memoryMiB(a, render::post::estimatePeakMemoryMiB(source.info().size, false));
  }
  farm::Plan plan{.tool = "post"};
  plan.title = fmt::format("{} → {}", fs::path(input).filename().string(), fs::path(out).filename().string());
  plan.outputs = {out};
  const auto common = arguments(given, {"--output", "--json", "--frames"}, {"--camera"});
  const std::string extension = fs::path(out).extension().string();
  for (const auto& [a0, b0] : ranges) {
    farm::Piece piece{.label = fmt::format("frames {}:{}", a0, b0), .command = {"post"}, .extension = extension};
    piece.command.insert(piece.command.end(), common.begin(), common.end());
    piece.command.insert(piece.command.end(), {"--frames", fmt::format("{}:{}", a0, b0), "-o", farm::kPieceOutput});
    addLimits(piece.command, cmd, given, mib, a.cpusPerTask);
    piece.inputs = {input};
    plan.pieces.push_back(std::move(piece));
  }
  plan.join = {"post", "--concat", farm::kAllPieceOutputs, "-o", out};
  if (const Given* json = find(given, "--json")) plan.join.insert(plan.join.end(), {"--json", absolute(json->values.front())});
  return plan;
}

farm::Plan renderPlan(CLI::App& cmd, const std::vector<Given>& given, int chunks, std::int64_t& mib, const FarmArgs& a) {
  const Given* output = find(given, "--output");
  const Given* frames = find(given, "--frames");
  if (!output || !frames) fail(ErrorKind::Usage, "farm render: give -o OUT (a video) and --frames A:B");
  const std::string out = absolute(output->values.front());
  if (video::isImagePath(out)) fail(ErrorKind::Usage, "farm render: -o must be a video (.mp4, .mkv, ...), got '{}'", out);
  const auto [first, end] = frameRange(frames);
  if (end < 0 || end <= first) fail(ErrorKind::Usage, "farm render: --frames {} must be FIRST:END with END > FIRST",
                                    frames->values.front());
  // Rendering is GPU (or llvmpipe) work whose memory the scene decides; 2 GiB holds the
  // Pipe Dream at 1080p on llvmpipe with room to spare.
  mib = memoryMiB(a, 1640.0);
  const auto scene = positionals(given);
  farm::Plan plan{.tool = "render"};
  plan.title = fmt::format("{} frames {}:{} → {}", scene.front(), first, end, fs::path(out).filename().string());
  plan.outputs = {out};
  std::vector<std::string> common{"render", scene.front()};
  const auto options = arguments(given, {"--output", "--frames"});
  common.insert(common.end(), options.begin() + std::ptrdiff_t(scene.size()), options.end());  // the scene is not a path
  const std::string extension = fs::path(out).extension().string();
  for (const auto& [a0, b0] : farm::splitEvenly(first, end, chunks)) {
    farm::Piece piece{.label = fmt::format("frames {}:{}", a0, b0), .command = common, .extension = extension};
    piece.command.insert(piece.command.end(), {"--frames", fmt::format("{}:{}", a0, b0), "-o", farm::kPieceOutput});
    addLimits(piece.command, cmd, given, mib, a.cpusPerTask);
    plan.pieces.push_back(std::move(piece));
  }
  plan.join = {"post", "--concat", farm::kAllPieceOutputs, "-o", out};
  return plan;
}

farm::Plan bakePlan(const std::string& file, std::int64_t& mib, const FarmArgs& a) {
  const std::vector<BatchBake> bakes = batchBakes(file);
  double most = 0.0;
  for (const auto& b : bakes) most = std::max(most, b.memoryMiB);
  mib = memoryMiB(a, most);
  farm::Plan plan{.tool = "bake"};
  plan.title = fmt::format("{} ({} bake{})", fs::path(file).filename().string(), bakes.size(), bakes.size() == 1 ? "" : "s");
  plan.workDir = a.workDir.empty() ? fs::path(absolute(file)).parent_path() : fs::path(a.workDir);
  for (std::size_t i = 0; i < bakes.size(); ++i) {
    const BatchBake& b = bakes[i];
    farm::Piece piece{.label = b.where.substr(b.where.find(" job ") + 1), .command = {"bake", "--batch", absolute(file),
                                                                                      "--job", std::to_string(i)}};
    piece.command.insert(piece.command.end(), {"--max-memory", std::to_string(mib)});
    if (a.cpusPerTask > 0) piece.command.insert(piece.command.end(), {"--threads", std::to_string(a.cpusPerTask)});
    piece.inputs.push_back(absolute(file));
    for (const auto& in : b.inputs) piece.inputs.push_back(absolute(in));
    for (const auto& out : b.outputs) {
      piece.outputs.push_back(absolute(out));
      plan.outputs.push_back(absolute(out));
    }
    plan.pieces.push_back(std::move(piece));
  }
  return plan;
}

}  // namespace

Command farmCommand(CLI::App& app, const GlobalOptions& global) {
  auto* farmCmd = app.add_subcommand("farm", "Split a cut, post, render or bake job over a Slurm cluster: the pieces as a "
                                             "job array, then the join");
  farmCmd->require_subcommand(1);
  farmCmd->fallthrough();
  farmCmd->footer(std::string(R"(Examples:
  glint farm cut city.glb -o city_cut.glb --light 0,40,10 --shards 16 --wait
  glint farm post film.mp4 -o film_sepia.mp4 -e sepia --chunks 8 --wait
  glint farm render pipedream -o pipedream.mp4 --frames 0:600 --fps 30 --size 1920x1080 --chunks 8
  glint farm bake assets.json --wait
  glint farm post film.mp4 -o graded.mkv --codec ffv1 -e sepia --chunks 4 --dry-run
)") + kCommonHelp);

  struct Tool {
    const char* name;
    Command (*add)(CLI::App&, const GlobalOptions&);
    const char* piecesName;
    const char* piecesHelp;
  };
  const Tool tools[] = {
      {"cut", &cutCommand, "--shards", "Shards: `glint cut --shard i/N` tasks, then `--merge` (byte-identical to one run)"},
      {"post", &postCommand, "--chunks", "Chunks: `glint post --frames a:b` tasks starting on keyframes, then `--concat`"},
      {"render", &renderCommand, "--chunks", "Chunks: `glint render --frames a:b` tasks, then `glint post --concat`"},
  };
  struct Parsed {
    CLI::App* cmd;
    std::string tool;
    std::shared_ptr<FarmArgs> args;
    std::set<const CLI::Option*> farmOptions;
    Command command;  ///< kept: its run is not used, but it owns the storage the tool's options write to
  };
  auto parsed = std::make_shared<std::vector<Parsed>>();
  for (const Tool& tool : tools) {
    const auto before = farmCmd->get_subcommands({});
    Command toolCommand = tool.add(*farmCmd, global);  // the tool's own options and checks
    CLI::App* cmd = nullptr;
    for (CLI::App* sub : farmCmd->get_subcommands({}))
      if (std::find(before.begin(), before.end(), sub) == before.end()) cmd = sub;
    auto args = std::make_shared<FarmArgs>();
    cmd->description(fmt::format("`glint {}` over a Slurm cluster (every option of glint {}, plus the farm's)", tool.name,
                                 tool.name));
    cmd->footer(std::string("See `glint farm --help` and `glint ") + tool.name + " --help`." + kCommonHelp);
    auto options = addFarmOptions(*cmd, *args, tool.piecesName, tool.piecesHelp);
    parsed->push_back({cmd, tool.name, args, std::move(options), std::move(toolCommand)});
  }

  // bake: one task per bake of a batch file, each `glint bake --batch F --job i`; no join.
  auto bakeArgs = std::make_shared<FarmArgs>();
  auto bakeFile = std::make_shared<std::string>();
  auto* bakeCmd = farmCmd->add_subcommand("bake", "`glint bake --batch JOBS.json` over a Slurm cluster: one task per "
                                                  "bake (`--job i`), no join");
  bakeCmd->add_option("jobs", *bakeFile, "Batch file: {\"defaults\": {...}, \"bakes\": [...]} (see glint bake --help)")
      ->required();
  addFarmOptions(*bakeCmd, *bakeArgs, nullptr, nullptr);
  bakeCmd->footer(std::string("Example:\n  glint farm bake assets.json --mem 8G --cpus-per-task 16 --wait\n") + kCommonHelp);

  return Command{.run = [parsed, bakeCmd, bakeArgs, bakeFile] {
                   if (bakeCmd->parsed()) {
                     checkScheduler(*bakeArgs);
                     std::int64_t mib = 0;
                     farm::Plan plan = bakePlan(*bakeFile, mib, *bakeArgs);
                     return runFarm(std::move(plan), *bakeArgs, mib);
                   }
                   for (Parsed& p : *parsed) {
                     if (!p.cmd->parsed()) continue;
                     const FarmArgs& a = *p.args;
                     checkScheduler(a);
                     const auto given = givenOptions(*p.cmd, p.farmOptions);
                     std::int64_t mib = 0;
                     farm::Plan plan = p.tool == "cut"    ? cutPlan(*p.cmd, given, a.pieces, mib, a)
                                       : p.tool == "post" ? postPlan(*p.cmd, given, a.pieces, mib, a)
                                                          : renderPlan(*p.cmd, given, a.pieces, mib, a);
                     return runFarm(std::move(plan), a, mib);
                   }
                   fail(ErrorKind::Usage, "farm: give a subcommand: cut, post, render or bake");
                 },
                 .readsImages = false};
}

}  // namespace glint::app
