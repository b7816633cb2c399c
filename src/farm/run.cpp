// glint farm's run of a plan (farm/run.h): submit or print, report, follow.
#include "glint/farm/run.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"

#include <fmt/format.h>

#include <atomic>
#include <csignal>
#include <cstdint>
#include <filesystem>

namespace glint::farm {

namespace fs = std::filesystem;

namespace {
/// Set by Ctrl-C while `wait` follows the jobs: stop following, say that they go on.
std::atomic<bool> stopFollowing{false};
void onInterrupt(int) { stopFollowing.store(true); }
}  // namespace

std::shared_ptr<Scheduler> makeScheduler(const RunOptions& options, const fs::path& workDir) {
  if (options.scheduler == "local") return localScheduler(workDir / "local-jobs");
  return slurmScheduler();
}

void checkScheduler(const RunOptions& a) {
  if (a.dryRun) return;
  if (auto missing = makeScheduler(a, "/")->unavailable()) throw Error(ErrorKind::Input, *missing);
}

namespace {
/// Follows the jobs with a progress bar until they joined, failed or Ctrl-C; the exit status.
int follow(Farm& job, const RunOptions& a, const std::string& outputs) {
  Progress progress("farm " + job.plan().tool, job.plan().pieces.size());
  std::string last;
  stopFollowing.store(false);
  struct sigaction action {}, oldInt {}, oldTerm {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &oldInt);
  sigaction(SIGTERM, &action, &oldTerm);
  const WaitResult result = job.wait(
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
  if (!result.cannotStart)
    log::error("farm {}: not joined; run the same command again to redo only the failed pieces", job.plan().tool);
  return result.exitCode;
}

}  // namespace

int run(Plan plan, const RunOptions& a) {
  Resources resources{.partition = a.partition, .time = a.time, .memoryMiB = plan.memoryMiB,
                            .cpusPerTask = a.cpusPerTask};
  if (plan.workDir.empty()) plan.workDir = a.workDir.empty() ? fs::path(absolutePath(plan.outputs.front().string())).parent_path()
                                                             : fs::path(a.workDir);
  // The outputs' folders must exist and be writable: found now, not after the cluster's work.
  for (const auto& output : plan.outputs) checkWritable(output);
  Farm job(plan, resources, makeScheduler(a, fs::absolute(plan.workDir)));
  if (a.dryRun) {
    fmt::print("{}", job.scripts());
    return 0;
  }
  const Submission s = job.submit();
  std::string outputs;
  for (const auto& o : job.plan().outputs) outputs += (outputs.empty() ? "" : ", ") + o.string();
  if (s.alreadyJoined) {
    log::info("farm {}: {} already made by this very job (same inputs and options, and the files are the ones its join "
              "wrote): nothing to submit", job.plan().tool, outputs);
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
    if (a.scheduler == "local") log::info("follow it: the same command with --wait");
    else log::info("follow it: squeue -j {}   (or run the same command with --wait)", ids);
    return 0;
  }
  return follow(job, a, outputs);
}

}  // namespace glint::farm
