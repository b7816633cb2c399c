// farm::localScheduler: batch scripts run on this machine as Slurm would run them
// (scheduler.h). Each job is a directory of small files under the spool; a detached bash
// runner (kRunner, fixed text: no user string is part of it) waits for the job's
// dependencies, runs its tasks as child processes and writes each task's state.
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/text.h"
#include "glint/farm/scheduler.h"
#include "process.h"

#include <fmt/format.h>
#include <sys/file.h>
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace glint::farm {

namespace fs = std::filesystem;

namespace {

// The runner: `bash runner.sh SPOOL/ID`. Files of a job directory: script (the submitted
// script, copied as sbatch copies it), tasks ("0 1 2"), array (1 for an array), after (job
// ids), slots, chdir, name, log.T (each task's log, from --output), state.T ("STATE
// EXIT REASON"), runner.pid, pid.T (a running task's process group), cancel / cancel.T.
constexpr const char* kRunner = R"RUNNER(#!/bin/bash
# glint farm's local scheduler (include/glint/farm/scheduler.h): runs the job in directory $1
# as Slurm would, its tasks as child processes after its dependencies. Every value it needs
# is a file in that directory: no user text is part of this script.
set -u
job=$1
spool=${job%/*}
id=${job##*/}
echo $$ > "$job/runner.pid"
put() { printf '%s %s %s\n' "$2" "$3" "$4" > "$job/.tmp.state.$1" && mv -f "$job/.tmp.state.$1" "$job/state.$1"; }
final() { local st rest; read -r st rest < "$job/state.$1"; case $st in PENDING|RUNNING) return 1 ;; esac; return 0; }
tasks=$(<"$job/tasks")
slots=$(<"$job/slots")
array=$(<"$job/array")
cancel_rest() { local t; for t in $tasks; do final "$t" || put "$t" CANCELLED "$1" "$2"; done; }
alive() {
  local p
  p=$(cat "$spool/$1/runner.pid" 2>/dev/null) || return 0
  kill -0 "$p" 2>/dev/null
}
verdict() {
  local dep=$1 dir=$spool/${1%%_*} st rest f v=ok files
  if [ "${dep#*_}" != "$dep" ]; then files=("$dir/state.${dep#*_}"); else files=("$dir"/state.*); fi
  for f in "${files[@]}"; do
    [ -e "$f" ] || { echo fail; return; }
    read -r st rest < "$f"
    case $st in
      COMPLETED) ;;
      PENDING|RUNNING) if alive "${dep%%_*}"; then v=wait; else echo fail; return; fi ;;
      *) echo fail; return ;;
    esac
  done
  echo $v
}
for dep in $(<"$job/after"); do
  while :; do
    [ -e "$job/cancel" ] && { cancel_rest 0:0 None; exit 0; }
    case $(verdict "$dep") in
      ok) break ;;
      fail) cancel_rest 0:0 DependencyNeverSatisfied; exit 0 ;;
    esac
    sleep 0.2
  done
done
run_task() {
  local t=$1 rc log dir
  if [ -e "$job/cancel" ] || [ -e "$job/cancel.$t" ]; then put "$t" CANCELLED 0:0 None; return; fi
  put "$t" RUNNING 0:0 None
  log=$(<"$job/log.$t")
  dir=$(<"$job/chdir")
  (
    cd -- "$dir" || exit 1
    export SLURM_JOB_ID=$id SLURM_JOB_NAME="$(<"$job/name")"
    if [ "$array" = 1 ]; then export SLURM_ARRAY_JOB_ID=$id SLURM_ARRAY_TASK_ID=$t; fi
    exec setsid bash "$job/script"
  ) < /dev/null >> "$log" 2>&1 &
  echo $! > "$job/pid.$t"
  wait $!
  rc=$?
  if [ -e "$job/cancel" ] || [ -e "$job/cancel.$t" ]; then put "$t" CANCELLED 0:15 None
  elif [ "$rc" -eq 0 ]; then put "$t" COMPLETED 0:0 None
  elif [ "$rc" -gt 128 ]; then put "$t" FAILED "0:$((rc - 128))" NonZeroExitCode
  else put "$t" FAILED "$rc:0" NonZeroExitCode; fi
}
for t in $tasks; do
  while [ "$(jobs -rp | wc -l)" -ge "$slots" ]; do wait -n; done
  run_task "$t" &
done
wait
)RUNNER";

std::string readLine(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

void writeFile(const fs::path& path, const std::string& text) { writeTextAtomically(path, text); }

/// A running process whose command line names `needle` (so a reused pid is not taken for it).
bool processAlive(const std::string& pidText, const std::string& needle) {
  int pid = 0;
  try {
    pid = parseInt(pidText, "a pid", 1, 1 << 30);
  } catch (const Error&) {
    return false;
  }
  std::ifstream in(fmt::format("/proc/{}/cmdline", pid), std::ios::binary);
  std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return !cmdline.empty() && cmdline.find(needle) != std::string::npos;
}

/// Slurm's filename pattern for a task: %A and %j the job id, %a the task, %x the job
/// name, %% a percent sign; other patterns are left as they are.
std::string expandPattern(const std::string& pattern, const std::string& id, int task, const std::string& name) {
  std::string out;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%' || i + 1 == pattern.size()) {
      out += pattern[i];
      continue;
    }
    const char c = pattern[++i];
    if (c == '%') out += '%';
    else if (c == 'A' || c == 'j') out += id;
    else if (c == 'a') out += std::to_string(task);
    else if (c == 'x') out += name;
    else out += std::string("%") + c;
  }
  return out;
}

class Local final : public Scheduler {
public:
  Local(fs::path spool, int slots) : m_spool(fs::absolute(spool).lexically_normal()), m_slots(slots) {
    if (m_slots <= 0) m_slots = int(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  }

  const char* name() const override { return "local"; }

  std::optional<std::string> unavailable() const override {
    for (const char* program : {"bash", "setsid"})
      if (!detail::onPath(program)) return fmt::format("the local scheduler needs '{}' on PATH", program);
    return std::nullopt;
  }

  std::string submit(const JobRequest& request) override {
    if (auto missing = unavailable()) throw Error(ErrorKind::Input, *missing);
    std::error_code ec;
    fs::create_directories(m_spool, ec);
    if (ec) fail(ErrorKind::Output, "farm: cannot create the local scheduler's directory '{}': {}", m_spool.string(), ec.message());
    const fs::path runner = m_spool / "runner.sh";
    if (readTextFileOr(runner) != kRunner) writeFile(runner, kRunner);
    for (const auto& dep : request.afterOk) {
      if (!fs::exists(m_spool / dep.substr(0, dep.find('_')), ec))
        fail(ErrorKind::Input, "farm: the local scheduler refused the job: it depends on job {}, which it does not know",
             printable(dep));
    }
    const std::string script = readTextFile(request.script);
    const std::string id = nextId();
    const fs::path job = m_spool / id;
    fs::create_directories(job, ec);
    if (ec) fail(ErrorKind::Output, "farm: cannot create '{}': {}", job.string(), ec.message());
    writeFile(job / "script", script);

    // What sbatch would take from the directives.
    std::string output, chdir = fs::current_path().string(), name = request.script.filename().string();
    for (const auto& [option, value] : readDirectives(script)) {
      if (option == "output") output = value;
      else if (option == "chdir") chdir = value;
      else if (option == "job-name") name = value;
    }
    const bool array = !request.arrayTasks.empty();
    if (output.empty()) output = array ? "slurm-%A_%a.out" : "slurm-%j.out";
    const std::vector<int> tasks = array ? request.arrayTasks : std::vector<int>{0};
    std::string taskList;
    for (int t : tasks) {
      taskList += (taskList.empty() ? "" : " ") + std::to_string(t);
      fs::path log = expandPattern(output, id, t, name);
      if (log.is_relative()) log = fs::path(chdir) / log;
      writeFile(job / fmt::format("log.{}", t), log.string() + "\n");
      writeFile(job / fmt::format("state.{}", t),
                fmt::format("PENDING 0:0 {}\n", request.afterOk.empty() ? "None" : "Dependency"));
    }
    std::string after;
    for (const auto& d : request.afterOk) after += (after.empty() ? "" : " ") + d;
    writeFile(job / "tasks", taskList + "\n");
    writeFile(job / "array", array ? "1\n" : "0\n");
    writeFile(job / "after", after + "\n");
    writeFile(job / "slots", std::to_string(m_slots) + "\n");
    writeFile(job / "chdir", chdir + "\n");
    writeFile(job / "name", name + "\n");
    // Detached: its own session, its output in the job directory, not a child of this process.
    const auto r = detail::runProcess({"bash", "-c", "exec </dev/null >\"$1/runner.log\" 2>&1; exec setsid -f bash \"$0\" \"$1\"",
                                       runner.string(), job.string()});
    if (r.exitCode != 0) fail(ErrorKind::Input, "farm: the local scheduler could not start job {}: {}", id, printable(r.output));
    return id;
  }

  std::map<std::string, TaskRecord> query(const std::string& id) override {
    std::map<std::string, TaskRecord> records;
    const std::string jobId = id.substr(0, id.find('_'));
    const fs::path job = m_spool / jobId;
    std::error_code ec;
    if (jobId.empty() || jobId.find_first_not_of("0123456789") != std::string::npos || !fs::is_directory(job, ec))
      return records;
    const bool array = readLine(job / "array") == "1";
    const std::string pid = readLine(job / "runner.pid");
    const bool runnerGone = !pid.empty() && !processAlive(pid, job.string());
    std::stringstream tasks(readLine(job / "tasks"));
    int t = 0;
    while (tasks >> t) {
      std::stringstream line(readLine(job / fmt::format("state.{}", t)));
      TaskRecord record;
      line >> record.state >> record.exitCode >> record.reason;
      if (record.reason == "None") record.reason.clear();
      if (runnerGone && liveState(record.state)) {
        // The runner wrote every final state before it ended: it was killed with the job.
        record = {"NODE_FAIL", "0:0", "runner gone"};
      }
      const std::string key = array ? fmt::format("{}_{}", jobId, t) : jobId;
      if (id.find('_') == std::string::npos || key == id) records[key] = record;
    }
    return records;
  }

  void cancel(const std::string& id) override {
    const std::string jobId = id.substr(0, id.find('_'));
    const fs::path job = m_spool / jobId;
    std::error_code ec;
    if (jobId.empty() || !fs::is_directory(job, ec)) return;
    const bool one = id.find('_') != std::string::npos;
    const std::string task = one ? id.substr(id.find('_') + 1) : "";
    writeFile(job / (one ? "cancel." + task : std::string("cancel")), "\n");
    // Running tasks: their process groups. Twice, for a task that was starting.
    for (int round = 0; round < 2; ++round) {
      for (const auto& entry : fs::directory_iterator(job, ec)) {
        const std::string file = entry.path().filename().string();
        if (!file.starts_with("pid.") || (one && file != "pid." + task)) continue;
        int pid = 0;
        try {
          pid = parseInt(readLine(entry.path()), "a pid", 2, 1 << 30);
        } catch (const Error&) {
          continue;
        }
        ::kill(-pid, SIGTERM);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    // Tasks that had not started are cancelled now, as scancel does (the runner, which
    // looks at the cancel file before it starts a task, may only confirm it).
    std::stringstream tasks(readLine(job / "tasks"));
    int t = 0;
    while (tasks >> t) {
      if (one && std::to_string(t) != task) continue;
      const fs::path state = job / fmt::format("state.{}", t);
      std::stringstream line(readLine(state));
      std::string now;
      line >> now;
      if (now == "PENDING") writeFile(state, "CANCELLED 0:0 None\n");
    }
  }

private:
  static std::string readTextFileOr(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  /// The next job id, under a lock on the spool's counter (several glint processes submit).
  std::string nextId() {
    const fs::path counter = m_spool / "next-id";
    const int fd = ::open(counter.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) fail(ErrorKind::Output, "farm: cannot open '{}': {}", counter.string(), std::strerror(errno));
    ::flock(fd, LOCK_EX);
    char buffer[32] = {};
    const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
    long next = 1;
    if (n > 0) next = std::max(1L, std::strtol(buffer, nullptr, 10));
    const std::string text = std::to_string(next + 1) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) != ssize_t(text.size())) {
      ::close(fd);
      fail(ErrorKind::Output, "farm: cannot write '{}': {}", counter.string(), std::strerror(errno));
    }
    ::close(fd);  // releases the lock
    return std::to_string(next);
  }

  fs::path m_spool;
  int m_slots = 1;
};

}  // namespace

std::unique_ptr<Scheduler> localScheduler(const fs::path& spool, int slots) { return std::make_unique<Local>(spool, slots); }

}  // namespace glint::farm
