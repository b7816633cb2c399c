// farm::slurmScheduler: Slurm through its client commands (scheduler.h).
#include "glint/core/error.h"
#include "glint/core/text.h"
#include "glint/farm/scheduler.h"
#include "process.h"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace glint::farm {

using detail::runProcess;

namespace {

constexpr const char* kMissingSlurm =
    "sbatch not found: glint farm submits through Slurm's client commands; install Debian's slurm-client "
    "(apt install slurm-client) and point SLURM_CONF at the cluster's slurm.conf (or run on this machine with "
    "--scheduler local)";

std::string firstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

/// Slurm's own message for a failed client command, as one line a user can act on.
std::string slurmError(const std::string& output) {
  if (output.find("DNS SRV lookup failed") != std::string::npos ||
      output.find("Could not establish a configuration source") != std::string::npos) {
    const char* conf = std::getenv("SLURM_CONF");
    return fmt::format("Slurm found no cluster to submit to: {} and DNS has no Slurm controller record; point "
                       "SLURM_CONF at the cluster's slurm.conf (or run on this machine with --scheduler local)",
                       conf ? fmt::format("SLURM_CONF is '{}'", printable(conf))
                            : std::string("SLURM_CONF is not set, /etc/slurm/slurm.conf does not exist"));
  }
  if (output.find("Unable to contact slurm controller") != std::string::npos)
    return "Slurm's controller (slurmctld) does not answer: " + printable(firstLine(output));
  return printable(firstLine(output));
}

/// "0-3,5,7-8%2" → {0,1,2,3,5,7,8}; anything else in the text is not a task.
std::vector<int> parseTaskRange(const std::string& text) {
  std::vector<int> tasks;
  const std::string body = text.substr(0, text.find('%'));
  for (const std::string_view part : splitFields(body, ',')) {
    if (part.empty()) continue;
    const std::size_t dash = part.find('-');
    try {
      const int lo = parseInt(part.substr(0, dash), "a task id", 0, 1 << 30);
      const int hi = dash == std::string_view::npos ? lo : parseInt(part.substr(dash + 1), "a task id", lo, 1 << 30);
      for (int t = lo; t <= hi && t - lo < 1000000; ++t) tasks.push_back(t);
    } catch (const Error&) {
      // not a task range Slurm writes: skipped
    }
  }
  return tasks;
}

/// The reason code at the start of Slurm's Reason field ("ReqNodeNotAvail,_UnavailableNodes:n1" →
/// "ReqNodeNotAvail"); Slurm writes the spaces of longer reasons as underscores.
std::string reasonCode(const std::string& field) {
  std::string code = field.substr(0, field.find_first_of(",("));
  for (char& c : code)
    if (c == '_') c = ' ';
  return code == "None" ? std::string() : code;
}

class Slurm final : public Scheduler {
public:
  const char* name() const override { return "slurm"; }

  std::optional<std::string> unavailable() const override {
    if (!detail::onPath("sbatch")) return std::string(kMissingSlurm);
    return std::nullopt;
  }

  std::string submit(const JobRequest& request) override {
    if (auto missing = unavailable()) throw Error(ErrorKind::Input, *missing);
    std::vector<std::string> argv{"sbatch", "--parsable"};
    if (!request.arrayTasks.empty()) {
      std::string array;
      for (int t : request.arrayTasks) array += (array.empty() ? "" : ",") + std::to_string(t);
      argv.push_back("--array=" + array);
    }
    if (!request.afterOk.empty()) {
      std::string dep = "--dependency=afterok";
      for (const auto& d : request.afterOk) dep += ":" + d;
      argv.push_back(dep);
      argv.push_back("--kill-on-invalid-dep=yes");
    }
    argv.push_back(request.script.string());
    const auto r = runProcess(argv);
    if (r.exitCode != 0) fail(ErrorKind::Input, "farm: Slurm refused the job: {}", slurmError(r.output));
    std::string id = firstLine(r.output);
    id = id.substr(0, id.find(';'));  // "1234;cluster"
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
      fail(ErrorKind::Input, "farm: sbatch answered '{}' instead of a job id", printable(firstLine(r.output)));
    return id;
  }

  std::map<std::string, TaskRecord> query(const std::string& id) override {
    std::map<std::string, TaskRecord> tasks;
    if (id.empty()) return tasks;
    const auto result = runProcess({"scontrol", "show", "job", "-o", id});
    if (result.exitCode != 0) return tasks;  // unknown (purged) or no controller: nothing known
    std::stringstream lines(result.output);
    std::string line;
    while (std::getline(lines, line)) {
      std::map<std::string, std::string> record;
      std::stringstream fields(line);
      std::string field;
      while (fields >> field) {
        const auto eq = field.find('=');
        if (eq != std::string::npos) record[field.substr(0, eq)] = field.substr(eq + 1);
      }
      if (!record.count("JobId")) continue;
      const TaskRecord task{record["JobState"], record["ExitCode"], reasonCode(record["Reason"])};
      const auto array = record.find("ArrayJobId");
      const auto taskIds = record.find("ArrayTaskId");
      if (array != record.end() && taskIds != record.end()) {
        for (int t : parseTaskRange(taskIds->second)) tasks[array->second + "_" + std::to_string(t)] = task;
      } else {
        tasks[record["JobId"]] = task;
      }
    }
    return tasks;
  }

  void cancel(const std::string& id) override { runProcess({"scancel", id}); }

  std::vector<std::string> nodeProblems() override {
    std::vector<std::string> problems;
    const auto r = runProcess({"sinfo", "-h", "-N", "-o", "%N|%T|%E"});
    if (r.exitCode != 0) return problems;
    std::stringstream lines(r.output);
    std::string line;
    while (std::getline(lines, line)) {
      const auto fields = splitFields(line, '|');
      if (fields.size() < 3) continue;
      const std::string state(fields[1]);
      const bool bad = state.find("down") != std::string::npos || state.find("drain") != std::string::npos ||
                       state.find("fail") != std::string::npos || state.find("not_responding") != std::string::npos ||
                       state.ends_with('*');
      if (!bad) continue;
      std::string reason(fields[2]);
      problems.push_back(fmt::format("node {} is {}{}", printable(std::string(fields[0])), printable(state),
                                     reason.empty() || reason == "none" ? "" : ": " + printable(reason)));
    }
    return problems;
  }
};

}  // namespace

std::unique_ptr<Scheduler> slurmScheduler() { return std::make_unique<Slurm>(); }

}  // namespace glint::farm
