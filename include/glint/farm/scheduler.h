#pragma once
// glint/farm/scheduler.h — where a farm plan's batch scripts run: the seam between
// farm::Farm (which pieces to submit, when a piece is done, what failed) and a batch system.
//
// Two schedulers keep the same rules:
//
//   slurmScheduler()   Slurm, through its client commands (sbatch, squeue, scontrol, scancel,
//                      sinfo): nothing links Slurm, any version with those commands works.
//   localScheduler(D)  this machine: each submitted job is run by a small detached runner
//                      (bash; its state is files under D), its tasks as child processes, at
//                      most `slots` at a time, after its dependencies succeeded (afterok; a
//                      failed or cancelled dependency cancels it, as Slurm's
//                      --kill-on-invalid-dep=yes). It reads the script's #SBATCH --output and
//                      --chdir as sbatch does (the directives up to the first command line),
//                      so a script whose directives were cut short shows it here too. Jobs
//                      outlive the command that submitted them, as on a cluster. `glint farm
//                      --scheduler local` uses it; so do the farm's tests that run without root.
//
/// ```cpp
/// auto scheduler = glint::farm::localScheduler("/tmp/farm-jobs");
/// glint::farm::JobRequest request;
/// request.script = "/tmp/farm-jobs-demo.sh";       // a bash script, as sbatch takes it
/// request.arrayTasks = {0, 1, 2};                  // SLURM_ARRAY_TASK_ID in each task
/// // const std::string id = scheduler->submit(request);
/// // scheduler->query(id) → {"12_0": {"COMPLETED", "0:0", ""}, ...}
/// ```
//
// Errors are glint::Error, one line: Error(Input) when the scheduler cannot be reached
// (sbatch missing, no Slurm configuration) or refuses a job, with its own reason.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint::farm {

/// What to submit: a batch script, as an array of tasks or as one job.
struct JobRequest {
  std::filesystem::path script;
  std::vector<int> arrayTasks;        ///< the tasks' indices; empty: one job, not an array
  std::vector<std::string> afterOk;   ///< job ids ("12", or "12_3" for one task) that must succeed first
};

/// A task as the scheduler reports it, in Slurm's words.
struct TaskRecord {
  std::string state;     ///< "PENDING", "RUNNING", "COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", ...
  std::string exitCode;  ///< "code:signal", e.g. "3:0", "0:15"
  std::string reason;    ///< why it is pending or ended: "Resources", "PartitionConfig", ...; empty for none
};

/// Whether a state is not final (the task may still run).
bool liveState(const std::string& state);

/// A pending reason in words, for `--wait`'s progress line ("PartitionConfig" → "the
/// request exceeds what the partition allows (CPUs, memory or time)"); the reason itself
/// when it is not one glint knows.
std::string explainReason(const std::string& reason);
/// Whether a pending reason means the job can never start as submitted (the partition's
/// limits, a node count or constraint no node meets): `--wait` stops and says so.
bool reasonIsPermanent(const std::string& reason);

class Scheduler {
public:
  virtual ~Scheduler() = default;
  /// "slurm" or "local".
  virtual const char* name() const = 0;
  /// Why this scheduler cannot be used here, in one line; nullopt when it can.
  virtual std::optional<std::string> unavailable() const = 0;
  /// Submits; the job id ("1234"). Error(Input) with the scheduler's reason when refused.
  virtual std::string submit(const JobRequest& request) = 0;
  /// Every task of job `id` the scheduler still knows, by task id: "ID_T" for an array's
  /// task, "ID" for a plain job. Empty when the job is unknown (purged).
  virtual std::map<std::string, TaskRecord> query(const std::string& id) = 0;
  /// Cancels a job ("12") or one task of an array ("12_3"); a job that ended is left as it is.
  virtual void cancel(const std::string& id) = 0;
  /// Nodes that cannot run work now, one line each ("node1 is down: Not responding"); for
  /// `--wait`'s messages when tasks stay queued.
  virtual std::vector<std::string> nodeProblems() { return {}; }
};

/// Slurm through its client commands.
std::unique_ptr<Scheduler> slurmScheduler();

/// This machine, jobs kept under `spool` (created when missing); `slots`: tasks run at once
/// (0: the machine's cores).
std::unique_ptr<Scheduler> localScheduler(const std::filesystem::path& spool, int slots = 0);

/// What `#SBATCH` lines say, read as sbatch reads them: every line from the second that
/// starts with `#SBATCH`, until the first line that is neither a comment nor blank; each
/// line's words split as sbatch splits them (quotes, backslashes, `#` starting a comment).
/// Options as "--name=value" or "--name value"; short ones as "-o value". Returns each
/// option's long name (without dashes: "output", "chdir", "job-name") and value, in order.
std::vector<std::pair<std::string, std::string>> readDirectives(const std::string& script);

}  // namespace glint::farm
