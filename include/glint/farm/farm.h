#pragma once
// glint/farm/farm.h — a tool job split into pieces and a join, run on a Slurm cluster
// (`glint farm`).
//
// glint's tools already split their own work: `glint cut --shard i/n` then `--merge`,
// `glint post --frames a:b` then `--concat`, `glint render --frames a:b` then
// `glint post --concat`, one `glint bake --batch F --job i` per bake. A Plan is such a job
// written down: the pieces (plain glint command lines, each writing its own files) and the
// join (one command line that reads every piece's output and writes the final output).
// A Farm submits a plan to a Scheduler (farm/scheduler.h: Slurm, or this machine) as one job
// array (task i = piece i) and one join job that depends on the whole array (`afterok`,
// cancelled when a dependency fails).
//
//   pieces named     every piece has a key: a hash of its command line (glint's own
//   by their inputs  options, the piece's index) and of each input file's absolute path, size
//                    and modification time. Its output is `<work dir>/<key>.<ext>`, and a
//                    piece counts as done when its marker (`<key>.done`, written by the task
//                    after glint exits 0) is there and its outputs are the ones the marker
//                    recorded (size and modification time): a file put there since does not
//                    count.
//   already made     the join records the final outputs' size and modification time; a plan
//                    counts as joined only while its outputs are those very files.
//   resubmit rule    running the same plan again submits only the pieces that are not done
//                    and not still queued or running (a live task from the last submission is
//                    waited for, not doubled), then the join; a plan whose join already
//                    succeeded submits nothing. Submissions hold a lock on the plan's
//                    directory, so a second identical command at the same time follows the
//                    first's jobs instead of submitting them again.
//   atomic outputs   each piece and the join write through glint's own atomic writes, so a
//                    cancelled task leaves no half file under the final name; the join job
//                    removes the intermediates only after the join command succeeded.
//   faults           wait() follows the tasks and reports every failed or cancelled one with
//                    its state, exit code and log file; the join does not run. A task that
//                    can never start (Slurm's PartitionConfig: more CPUs than a node has) is
//                    reported and cancelled instead of being waited for.
//   scripts          every string in a batch script is a quoted shell word, an escaped
//                    comment or a checked #SBATCH value (docs/farm.md, "What reaches a batch
//                    script"): no file name runs as a command or cuts the directives short.
//
/// ```cpp
/// glint::farm::Plan plan;
/// plan.tool = "post";
/// plan.title = "clip.mp4 → graded.mp4";
/// plan.workDir = "/shared/farm";
/// for (int i = 0; i < 2; ++i) {
///   glint::farm::Piece piece;
///   piece.label = "frames " + std::to_string(i * 100) + ":" + std::to_string(i * 100 + 100);
///   piece.command = {"post", "/shared/clip.mp4", "-o", glint::farm::kPieceOutput, "--codec", "ffv1",
///                    "--frames", std::to_string(i * 100) + ":" + std::to_string(i * 100 + 100), "-e", "sepia"};
///   piece.extension = ".mkv";
///   piece.inputs = {"/shared/clip.mp4"};
///   plan.pieces.push_back(piece);
/// }
/// plan.join = {"post", "--concat", glint::farm::kAllPieceOutputs, "-o", "/shared/graded.mkv"};
/// plan.outputs = {"/shared/graded.mkv"};
/// glint::farm::Resources resources;
/// resources.memoryMiB = 2048;
/// glint::farm::Farm farm(plan, resources);   // Slurm; keys the pieces, reads the work dir
/// std::string scripts = farm.scripts();      // what --dry-run prints: the two batch scripts
/// // farm.submit() submits what is missing; farm.wait() follows it (see below).
/// ```
//
// Errors are glint::Error with one line: Usage for a plan without pieces or a string no
// #SBATCH line can hold (a line break in the work directory's name), Input for a missing
// `sbatch` ("install slurm-client") or a submission Slurm refused (its own message), Output
// for a work directory that cannot be written.
#include "glint/core/tool.h"
#include "glint/farm/scheduler.h"

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint::farm {

/// In a piece's command: replaced by the piece's output path (`<work dir>/<key><extension>`).
inline constexpr const char* kPieceOutput = "{piece}";
/// In the join's command: replaced by every piece's output path, in piece order.
inline constexpr const char* kAllPieceOutputs = "{pieces}";

/// One task of the array: a glint command line (without the program itself).
struct Piece {
  std::string label;                 ///< for people: "shard 2/4", "frames 250:500", "bake 3 (crate_n.png)"
  std::vector<std::string> command;  ///< glint's arguments; kPieceOutput where the piece's output goes
  std::string extension;             ///< of the piece's output in the work directory (".glint-shard", ".mkv");
                                     ///< empty: the piece writes final outputs itself (a bake)
  std::vector<std::filesystem::path> inputs;   ///< files the piece reads (their size and time key it)
  std::vector<std::filesystem::path> outputs;  ///< final files it writes itself (with an empty extension)
};

/// A split job: the pieces, the join, and what the whole writes.
struct Plan {
  std::string tool;                    ///< "cut", "post", "render", "bake": names the job and its directory
  std::string title;                   ///< one line for reports: "city.glb → city-cut.glb"
  std::vector<Piece> pieces;
  std::vector<std::string> join;       ///< glint's arguments for the join (kAllPieceOutputs); empty: no join
  std::vector<std::filesystem::path> outputs;  ///< the final outputs (written by the join, or by the pieces)
  std::filesystem::path workDir;       ///< intermediates, scripts, logs (on a filesystem every node sees)
  std::int64_t memoryMiB = 0;          ///< what each task asks for (the tool's estimate or --mem); 0: the cluster's default
};

/// What `glint farm TOOL` gives a tool's plan function (cut::farmPlan, ...) besides the job.
struct Split {
  int pieces = 1;               ///< --shards or --chunks
  std::int64_t memoryMiB = 0;   ///< --mem in MiB; 0: the tool's estimate for the job
  int cpusPerTask = 0;          ///< --cpus-per-task, also each piece's --threads; 0: Slurm's default
  std::filesystem::path workDir;  ///< --work-dir; empty: the first output's folder
};

/// The memory each task asks for: `split.memoryMiB`, or `estimateMiB` with a quarter more,
/// rounded up to 64 MiB.
std::int64_t taskMemoryMiB(const Split& split, double estimateMiB);

/// The tool options of a plan's commands: the user's --threads, else --cpus-per-task; the
/// user's --max-memory, else the task's memory (`taskMiB`); -q as given. No --json: the join
/// (or a piece that writes final outputs) gets the report's path itself.
std::vector<std::string> pieceSettings(const ToolSettings& given, const Split& split, std::int64_t taskMiB);

/// `path` absolute and normalized: what a task on another node is given.
std::string absolutePath(const std::string& path);

/// What each task asks Slurm for.
struct Resources {
  std::string partition;     ///< --partition; empty: the cluster's default
  std::string time;          ///< --time (e.g. "1:00:00"); empty: the partition's default
  std::int64_t memoryMiB = 0;  ///< --mem in MiB (also the piece's --max-memory); 0: the cluster's default
  int cpusPerTask = 0;       ///< --cpus-per-task; 0: Slurm's default (1)
  std::string glint;         ///< the glint program the tasks run; empty: this process's executable
};

/// Where a piece stands.
enum class PieceState { Done, Queued, Running, Failed, Missing };

struct PieceStatus {
  PieceState state = PieceState::Missing;
  std::string slurmState;  ///< "COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", ... (empty when unknown)
  std::string exitCode;    ///< Slurm's "code:signal", e.g. "3:0", "0:15"; or the rc the task wrote
  std::string jobId;       ///< "1234_2" once submitted
  std::string reason;      ///< why it is queued or ended ("Resources", "PartitionConfig"); empty for none
};

/// The outcome of wait().
struct WaitResult {
  bool joined = false;           ///< the join succeeded: the outputs exist
  bool stopped = false;          ///< the stop flag was set: the jobs go on without being followed
  bool cannotStart = false;      ///< a task can never start as submitted: the queued tasks were cancelled
  std::vector<std::string> failures;  ///< one line per failed or cancelled task: label, state, exit code, log
  int exitCode = 0;              ///< 0 when joined; else the first failed task's exit code, or 1; 2 for a
                                 ///< task that can never start (cancelled)
};

/// What submit() did.
struct Submission {
  std::vector<int> submitted;    ///< pieces submitted now (indices)
  std::vector<int> reused;       ///< pieces already done, or still queued/running from before
  std::string arrayJob;          ///< the array's job id ("" when no piece needed submitting)
  std::string joinJob;           ///< the join's job id ("" when the plan was already joined)
  bool alreadyJoined = false;    ///< nothing to do: the outputs of this very plan exist
};

class Farm {
public:
  /// Keys the pieces (reads the inputs' size and time) and loads the work directory's
  /// record of an earlier submission. Error(Usage) for a plan without pieces, or for a work
  /// directory, partition or time no #SBATCH line can hold. `scheduler`: Slurm when null.
  Farm(Plan plan, Resources resources, std::shared_ptr<Scheduler> scheduler = nullptr);

  /// The plan's directory: `<workDir>/<tool>-<plan key>`.
  const std::filesystem::path& directory() const { return m_directory; }
  const Plan& plan() const { return m_plan; }
  /// Piece i's output path in the directory (empty for pieces that write final outputs).
  std::filesystem::path pieceOutput(int i) const;
  /// Piece i's log file (the task's stdout and stderr).
  std::filesystem::path pieceLog(int i) const;
  std::filesystem::path joinLog() const;

  /// The two batch scripts as submit() writes them (the array's, then the join's), each
  /// headed by its `sbatch` line: what `glint farm --dry-run` prints. Submits nothing.
  std::string scripts() const;

  /// Submits the pieces that are neither done nor live, and the join, under a lock on the
  /// plan's directory. Error(Input) when the scheduler is missing or refuses.
  Submission submit();

  /// Follows the submission until the join has ended or a task failed and nothing is left
  /// running; `progress(done, total, line)` is called whenever something changes (the line
  /// names a queued task's reason and nodes that are down). Returns early, `stopped`, once
  /// `*stop` is set (Ctrl-C): the jobs go on.
  WaitResult wait(const std::function<void(int done, int total, const std::string& line)>& progress = {},
                  const std::atomic<bool>* stop = nullptr);

  /// Each piece's state now (markers, then the scheduler).
  std::vector<PieceStatus> status();

  /// Whether the plan's outputs are the files its join (or, without a join, its pieces)
  /// recorded: "already made by this very job".
  bool joinedBefore() const;
  /// The array's and the join's job ids of the latest submission ("" when none).
  const std::string& arrayJob() const { return m_arrayJob; }
  const std::string& joinJob() const { return m_joinJob; }
  Scheduler& scheduler() { return *m_scheduler; }

private:
  void keyPieces();
  void loadRecord();
  void saveRecord() const;
  std::string pieceScript(const std::vector<int>& indices) const;
  std::string joinScript() const;
  std::vector<std::string> pieceCommand(int i) const;
  std::vector<std::string> joinCommand() const;
  bool pieceDone(int i) const;

  Plan m_plan;
  Resources m_resources;
  std::shared_ptr<Scheduler> m_scheduler;
  std::string m_key;                   ///< the plan's key (all piece keys and the join)
  std::vector<std::string> m_pieceKeys;
  std::filesystem::path m_directory;
  std::string m_arrayJob, m_joinJob;   ///< from submit(), or the record of an earlier one
  std::vector<std::string> m_pieceJobs;  ///< per piece, "ARRAY_TASK" of its latest submission
};


/// Splits frames [first, end) into at most `chunks` ranges whose starts are keyframes (so
/// each range decodes on its own), as even as the keyframes allow. `keyframes` are frame
/// indices, ascending, starting with `first` or earlier. Fewer ranges come back when there
/// are fewer keyframes than chunks.
std::vector<std::pair<std::int64_t, std::int64_t>> splitAtKeyframes(const std::vector<std::int64_t>& keyframes,
                                                                    std::int64_t first, std::int64_t end, int chunks);

/// Splits frames [first, end) into `chunks` ranges as even as possible (a render: any frame
/// may start a piece).
std::vector<std::pair<std::int64_t, std::int64_t>> splitEvenly(std::int64_t first, std::int64_t end, int chunks);

}  // namespace glint::farm
