#pragma once
// glint/farm/run.h — `glint farm`'s run of a plan: checks, prints (--dry-run), submits,
// reports what was submitted and, with `wait`, follows the jobs with a progress bar until
// they joined, failed or Ctrl-C (which stops following, not the jobs). The command is a
// table of tools over this call.
//
/// ```cpp
/// glint::farm::Plan plan;  // from a tool's farmPlan (cut/job.h, ...)
/// glint::farm::RunOptions options;
/// options.scheduler = "local";
/// options.dryRun = true;
/// // const int status = glint::farm::run(plan, options);  // prints the two batch scripts
/// ```
#include "glint/farm/farm.h"

#include <filesystem>
#include <memory>
#include <string>

namespace glint::farm {

/// What `glint farm` was asked besides the tool's job.
struct RunOptions {
  std::string partition, time;     ///< --partition, --time
  int cpusPerTask = 0;             ///< --cpus-per-task
  std::string workDir;             ///< --work-dir; empty: the first output's folder
  std::string scheduler = "slurm";  ///< "slurm" or "local"
  bool dryRun = false;             ///< print the scripts, submit nothing
  bool wait = false;               ///< follow the jobs to the end
};

/// The scheduler `options` name; the local one keeps its jobs under `workDir`/local-jobs.
std::shared_ptr<Scheduler> makeScheduler(const RunOptions& options, const std::filesystem::path& workDir);

/// Error(Input) when the scheduler cannot be used here (sbatch missing): before any work.
/// Nothing to check for --dry-run.
void checkScheduler(const RunOptions& options);

/// Runs the plan as `glint farm` does; the exit status (0; the first failed task's; 2 for a
/// task that can never start; 130 when Ctrl-C stopped the following).
int run(Plan plan, const RunOptions& options);

}  // namespace glint::farm
