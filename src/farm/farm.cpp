#include "glint/farm/farm.h"

#include "glint/core/json.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/hash.h"
#include "glint/core/options.h"
#include "glint/core/text.h"
#include "process.h"
#include "script.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

namespace fs = std::filesystem;

namespace glint::farm {

namespace {

std::string hex(std::uint64_t value) { return fmt::format("{:016x}", value); }

void addString(Fnv1a& h, const std::string& text) {
  h.add(std::uint64_t(text.size()));
  h.addBytes(text.data(), text.size());
}

/// A file's identity for keys: absolute path, size and modification time (0s when missing).
void addFile(Fnv1a& h, const fs::path& path) {
  addString(h, fs::absolute(path).lexically_normal().string());
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    h.add(std::int64_t(st.st_size));
    h.add(std::int64_t(st.st_mtim.tv_sec));
    h.add(std::int64_t(st.st_mtim.tv_nsec));
  } else {
    h.add(std::int64_t(-1));
  }
}

fs::path selfExecutable() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path("glint") : self;
}

std::string quoteCommand(const std::vector<std::string>& argv) {
  std::string line;
  for (const auto& a : argv) line += (line.empty() ? "" : " ") + detail::scriptWord(a);
  return line;
}

std::string readSmall(const fs::path& path) {
  std::ifstream in(path);
  std::string text;
  std::getline(in, text);
  return text;
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A file as the markers record it: "SIZE SECONDS.NANOSECONDS" (what `stat -c '%s %.9Y'`
/// prints), "" when it is missing or empty.
std::string fingerprint(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || st.st_size <= 0) return {};
  return fmt::format("{} {}.{:09}", std::int64_t(st.st_size), std::int64_t(st.st_mtim.tv_sec),
                     std::int64_t(st.st_mtim.tv_nsec));
}

/// Whether `record` (a marker: its key, then one fingerprint line per file) is `key`'s and
/// every file is still the one it recorded.
bool recordMatches(const std::string& record, const std::string& key, const std::vector<fs::path>& files) {
  std::stringstream lines(record);
  std::string line;
  if (!std::getline(lines, line) || line != key) return false;
  for (const auto& file : files) {
    if (!std::getline(lines, line)) return false;
    const std::string now = fingerprint(file);
    if (now.empty() || now != line) return false;
  }
  return true;
}

/// The bash lines that record `key` and the files of the array `files` into `path`
/// (a marker), atomically.
std::string recordLines(const std::string& key, const std::string& array, const std::string& path) {
  return fmt::format("{{ echo {}; for f in \"${{{}[@]}}\"; do stat -c '%s %.9Y' -- \"$f\"; done; }} > \"{}.tmp\" && "
                     "mv -f \"{}.tmp\" \"{}\"\n", key, array, path, path, path);
}

/// An exclusive lock on a file, released when destroyed.
class FileLock {
public:
  explicit FileLock(const fs::path& path) {
    m_fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (m_fd < 0) fail(ErrorKind::Output, "farm: cannot open the lock '{}': {}", path.string(), std::strerror(errno));
    while (::flock(m_fd, LOCK_EX) != 0 && errno == EINTR) {
    }
  }
  ~FileLock() {
    if (m_fd >= 0) ::close(m_fd);
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

private:
  int m_fd = -1;
};

}  // namespace

std::int64_t taskMemoryMiB(const Split& split, double estimateMiB) {
  if (split.memoryMiB > 0) return split.memoryMiB;
  return (std::int64_t(std::ceil(estimateMiB * 1.25)) + 63) / 64 * 64;
}

std::vector<std::string> pieceSettings(const ToolSettings& given, const Split& split, std::int64_t taskMiB) {
  ToolSettings s{.threads = given.threads > 0 ? given.threads : split.cpusPerTask, .quiet = given.quiet,
                 .maxMemory = !given.maxMemory.empty() ? given.maxMemory : taskMiB > 0 ? std::to_string(taskMiB) : ""};
  return toolArguments(s);
}

std::string absolutePath(const std::string& path) {
  if (path.empty() || path == "-") return path;
  return fs::absolute(path).lexically_normal().string();
}

std::vector<std::pair<std::int64_t, std::int64_t>> splitEvenly(std::int64_t first, std::int64_t end, int chunks) {
  std::vector<std::pair<std::int64_t, std::int64_t>> ranges;
  const std::int64_t count = end - first;
  if (count <= 0 || chunks <= 0) return ranges;
  const std::int64_t n = std::min<std::int64_t>(chunks, count);
  for (std::int64_t i = 0; i < n; ++i) ranges.emplace_back(first + count * i / n, first + count * (i + 1) / n);
  return ranges;
}

std::vector<std::pair<std::int64_t, std::int64_t>> splitAtKeyframes(const std::vector<std::int64_t>& keyframes,
                                                                    std::int64_t first, std::int64_t end, int chunks) {
  // Candidate starts: keyframes strictly inside (first, end); the first range starts at `first`
  // (the source seeks to the keyframe at or before it).
  std::vector<std::int64_t> inside;
  for (std::int64_t k : keyframes)
    if (k > first && k < end) inside.push_back(k);
  std::vector<std::int64_t> starts{first};
  for (const auto& [ideal, unused] : splitEvenly(first, end, chunks)) {
    (void)unused;
    if (ideal == first) continue;
    // The keyframe nearest the even split point, after the last start chosen.
    std::int64_t best = -1;
    for (std::int64_t k : inside)
      if (k > starts.back() && (best < 0 || std::llabs(k - ideal) < std::llabs(best - ideal))) best = k;
    if (best > 0) starts.push_back(best);
  }
  std::vector<std::pair<std::int64_t, std::int64_t>> ranges;
  for (std::size_t i = 0; i < starts.size(); ++i) ranges.emplace_back(starts[i], i + 1 < starts.size() ? starts[i + 1] : end);
  return ranges;
}

Farm::Farm(Plan plan, Resources resources, std::shared_ptr<Scheduler> scheduler)
    : m_plan(std::move(plan)), m_resources(std::move(resources)), m_scheduler(std::move(scheduler)) {
  if (!m_scheduler) m_scheduler = slurmScheduler();
  if (m_plan.pieces.empty()) fail(ErrorKind::Usage, "farm {}: nothing to do (no pieces)", m_plan.tool);
  if (m_resources.glint.empty()) m_resources.glint = selfExecutable().string();
  if (m_plan.workDir.empty()) m_plan.workDir = fs::current_path();
  m_plan.workDir = fs::absolute(m_plan.workDir).lexically_normal();
  // What goes into #SBATCH lines, checked before anything is written (script.h).
  (void)detail::directiveValue(m_plan.workDir.string(), "the work directory");
  if (!m_resources.partition.empty()) (void)detail::directiveValue(m_resources.partition, "--partition");
  if (!m_resources.time.empty()) (void)detail::directiveValue(m_resources.time, "--time");
  keyPieces();
  m_directory = m_plan.workDir / fmt::format("{}-{}", m_plan.tool, m_key.substr(0, 12));
  m_pieceJobs.assign(m_plan.pieces.size(), "");
  loadRecord();
}

void Farm::keyPieces() {
  Fnv1a planHash;
  addString(planHash, "glint-farm-1");
  addString(planHash, m_plan.tool);
  addFile(planHash, m_resources.glint);  // a new glint redoes the work
  for (std::size_t i = 0; i < m_plan.pieces.size(); ++i) {
    const Piece& piece = m_plan.pieces[i];
    Fnv1a h;
    addString(h, m_plan.tool);
    addFile(h, m_resources.glint);
    h.add(std::uint64_t(i));
    for (const auto& arg : piece.command) addString(h, arg);
    addString(h, piece.extension);
    for (const auto& input : piece.inputs) addFile(h, input);
    for (const auto& output : piece.outputs) addString(h, fs::absolute(output).lexically_normal().string());
    m_pieceKeys.push_back(hex(h.value()));
    addString(planHash, m_pieceKeys.back());
  }
  for (const auto& arg : m_plan.join) addString(planHash, arg);
  for (const auto& output : m_plan.outputs) addString(planHash, fs::absolute(output).lexically_normal().string());
  m_key = hex(planHash.value());
}

fs::path Farm::pieceOutput(int i) const {
  const Piece& piece = m_plan.pieces.at(std::size_t(i));
  if (piece.extension.empty()) return {};
  return m_directory / fmt::format("piece{}-{}{}", i, m_pieceKeys[std::size_t(i)].substr(0, 12), piece.extension);
}

fs::path Farm::pieceLog(int i) const { return m_directory / "logs" / fmt::format("piece-{}.log", i); }
fs::path Farm::joinLog() const { return m_directory / "logs" / "join.log"; }

namespace {
fs::path markerOf(const fs::path& dir, const std::string& key) { return dir / (key + ".done"); }
fs::path rcOf(const fs::path& dir, const std::string& key) { return dir / (key + ".rc"); }
}  // namespace

namespace {
/// The files a piece's marker records: its output in the work directory, or the final
/// outputs it writes itself.
std::vector<fs::path> recordedFiles(const fs::path& pieceOutput, const Piece& piece) {
  if (!pieceOutput.empty()) return {pieceOutput};
  std::vector<fs::path> files;
  for (const auto& o : piece.outputs) files.push_back(fs::absolute(o).lexically_normal());
  return files;
}
}  // namespace

bool Farm::pieceDone(int i) const {
  const auto& key = m_pieceKeys[std::size_t(i)];
  return recordMatches(readAll(markerOf(m_directory, key)), key,
                       recordedFiles(pieceOutput(i), m_plan.pieces[std::size_t(i)]));
}

bool Farm::joinedBefore() const {
  if (m_plan.join.empty()) {
    for (int i = 0; i < int(m_plan.pieces.size()); ++i)
      if (!pieceDone(i)) return false;
    return true;
  }
  std::vector<fs::path> outputs;
  for (const auto& o : m_plan.outputs) outputs.push_back(fs::absolute(o).lexically_normal());
  return recordMatches(readAll(m_directory / "joined"), m_key, outputs);
}

std::vector<std::string> Farm::pieceCommand(int i) const {
  std::vector<std::string> argv{m_resources.glint};
  for (const auto& arg : m_plan.pieces.at(std::size_t(i)).command)
    argv.push_back(arg == kPieceOutput ? pieceOutput(i).string() : arg);
  return argv;
}

std::vector<std::string> Farm::joinCommand() const {
  std::vector<std::string> argv{m_resources.glint};
  for (const auto& arg : m_plan.join) {
    if (arg == kAllPieceOutputs) {
      for (int i = 0; i < int(m_plan.pieces.size()); ++i) argv.push_back(pieceOutput(i).string());
    } else {
      argv.push_back(arg);
    }
  }
  return argv;
}

namespace {
std::string directives(const Resources& r, const std::string& name, const fs::path& directory, const std::string& log) {
  std::string text = fmt::format("#SBATCH --job-name={}\n#SBATCH --output={}\n#SBATCH --chdir={}\n", name,
                                 detail::outputPattern(directory.string() + "/logs", log, "the work directory"),
                                 detail::directiveValue(directory.string(), "the work directory"));
  if (!r.partition.empty()) text += fmt::format("#SBATCH --partition={}\n", detail::directiveValue(r.partition, "--partition"));
  if (!r.time.empty()) text += fmt::format("#SBATCH --time={}\n", detail::directiveValue(r.time, "--time"));
  if (r.memoryMiB > 0) text += fmt::format("#SBATCH --mem={}M\n", r.memoryMiB);
  if (r.cpusPerTask > 0) text += fmt::format("#SBATCH --cpus-per-task={}\n", r.cpusPerTask);
  return text;
}

/// The body's first lines: where the files are, and the folder the command was given in
/// (tasks get absolute paths; a folder a node lacks is not an error).
std::string bodyStart(const fs::path& directory) {
  return fmt::format("set -u\ndir={}\ncd -- {} 2>/dev/null || true\n", detail::scriptWord(directory.string()),
                     detail::scriptWord(fs::current_path().string()));
}
}  // namespace

std::string Farm::pieceScript(const std::vector<int>& indices) const {
  std::string text = "#!/bin/bash\n";
  text += fmt::format("# glint farm {}: {} — piece $SLURM_ARRAY_TASK_ID of {} (task i runs piece i).\n", m_plan.tool,
                      detail::commentText(m_plan.title), m_plan.pieces.size());
  text += "# Each piece is a plain glint call; the marker <key>.done says it finished (exit 0) and what it wrote.\n";
  text += directives(m_resources, "glint-" + m_plan.tool, m_directory, "piece-%a.log");
  text += bodyStart(m_directory);
  text += "case \"${SLURM_ARRAY_TASK_ID:?this script runs as a task of sbatch --array}\" in\n";
  for (int i : indices) {
    const Piece& piece = m_plan.pieces[std::size_t(i)];
    std::vector<std::string> outputs;
    for (const auto& o : recordedFiles(pieceOutput(i), piece)) outputs.push_back(o.string());
    text += fmt::format("  {})  # {}\n    key={}\n    outputs=({})\n    cmd=({})\n    ;;\n", i,
                        detail::commentText(piece.label), m_pieceKeys[std::size_t(i)], quoteCommand(outputs),
                        quoteCommand(pieceCommand(i)));
  }
  text += "  *) echo \"glint farm: no piece $SLURM_ARRAY_TASK_ID in this script\" >&2; exit 2 ;;\nesac\n";
  text += "rm -f \"$dir/$key.done\" \"$dir/$key.rc\"\n";
  text += "echo \"glint farm: $(hostname): ${cmd[*]}\"\n";
  text += "\"${cmd[@]}\"\nrc=$?\n";
  text += "for f in \"${outputs[@]}\"; do\n"
          "  if [ \"$rc\" -eq 0 ] && [ ! -s \"$f\" ]; then echo \"glint farm: exit 0 but no output '$f'\" >&2; rc=1; fi\n"
          "done\n";
  text += "echo \"$rc\" > \"$dir/$key.rc\"\n";
  text += "if [ \"$rc\" -eq 0 ]; then\n  " + recordLines("\"$key\"", "outputs", "$dir/$key.done") + "fi\n";
  text += "exit \"$rc\"\n";
  return text;
}

std::string Farm::joinScript() const {
  std::string text = "#!/bin/bash\n";
  text += fmt::format("# glint farm {}: {} — the join, after every piece succeeded (afterok).\n", m_plan.tool,
                      detail::commentText(m_plan.title));
  text += "# The intermediates are removed only after the join command succeeded; joined records the outputs.\n";
  text += directives(m_resources, "glint-" + m_plan.tool + "-join", m_directory, "join.log");
  text += bodyStart(m_directory);
  std::vector<std::string> outputs, pieces;
  for (const auto& o : m_plan.outputs) outputs.push_back(fs::absolute(o).lexically_normal().string());
  for (int i = 0; i < int(m_plan.pieces.size()); ++i) {
    if (!pieceOutput(i).empty()) pieces.push_back(pieceOutput(i).string());
    pieces.push_back(markerOf(m_directory, m_pieceKeys[std::size_t(i)]).string());
    pieces.push_back(rcOf(m_directory, m_pieceKeys[std::size_t(i)]).string());
  }
  text += fmt::format("outputs=({})\npieces=({})\ncmd=({})\n", quoteCommand(outputs), quoteCommand(pieces),
                      quoteCommand(joinCommand()));
  text += "echo \"glint farm: $(hostname): ${cmd[*]}\"\n";
  text += "\"${cmd[@]}\" || exit $?\n";
  text += "for f in \"${outputs[@]}\"; do [ -s \"$f\" ] || { echo \"glint farm: the join wrote no '$f'\" >&2; exit 1; }; done\n";
  text += recordLines(m_key, "outputs", "$dir/joined");
  text += "rm -f \"${pieces[@]}\"\n";
  return text;
}

std::string Farm::scripts() const {
  std::vector<int> all(m_plan.pieces.size());
  for (int i = 0; i < int(all.size()); ++i) all[std::size_t(i)] = i;
  const std::string dir = detail::commentText(m_directory.string());
  std::string text = fmt::format("# {}/pieces.sh — sbatch --array=0-{} {}/pieces.sh\n", dir, all.size() - 1, dir);
  text += pieceScript(all);
  if (!m_plan.join.empty()) {
    text += fmt::format("\n# {}/join.sh — sbatch --dependency=afterok:ARRAY_JOB --kill-on-invalid-dep=yes {}/join.sh\n",
                        dir, dir);
    text += joinScript();
  }
  return text;
}

void Farm::loadRecord() {
  const fs::path path = m_directory / "submission.json";
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  try {
    const auto record = nlohmann::json::parse(readTextFile(path));
    m_arrayJob = record.value("array", "");
    m_joinJob = record.value("join", "");
    const auto& pieces = record.at("pieces");
    for (std::size_t i = 0; i < m_pieceJobs.size() && i < pieces.size(); ++i) m_pieceJobs[i] = pieces[i].get<std::string>();
  } catch (const std::exception&) {
    // A damaged record only loses the knowledge of live tasks; markers still say what is done.
  }
}

void Farm::saveRecord() const {
  nlohmann::json record{{"key", m_key}, {"array", m_arrayJob}, {"join", m_joinJob}, {"pieces", m_pieceJobs}};
  writeTextAtomically(m_directory / "submission.json", jsonText(record));
}

std::vector<PieceStatus> Farm::status() {
  std::vector<PieceStatus> states(m_plan.pieces.size());
  // Ask the scheduler first, then look at the markers: a task that ends in between is then
  // seen as done rather than as completed without its marker.
  std::set<std::string> arrays;
  for (const auto& job : m_pieceJobs)
    if (!job.empty()) arrays.insert(job.substr(0, job.find('_')));
  std::map<std::string, TaskRecord> known;  // "A_T" → record
  for (const auto& array : arrays) known.merge(m_scheduler->query(array));
  for (int i = 0; i < int(states.size()); ++i) {
    PieceStatus& s = states[std::size_t(i)];
    s.jobId = m_pieceJobs[std::size_t(i)];
    if (pieceDone(i)) {
      s.state = PieceState::Done;
      s.slurmState = "COMPLETED";
      continue;
    }
    if (s.jobId.empty()) continue;  // Missing: never submitted
    const std::string rc = readSmall(rcOf(m_directory, m_pieceKeys[std::size_t(i)]));
    if (const auto it = known.find(s.jobId); it != known.end()) {
      s.slurmState = it->second.state;
      s.exitCode = it->second.exitCode;
      s.reason = it->second.reason;
      if (s.slurmState == "PENDING" || s.slurmState == "CONFIGURING") s.state = PieceState::Queued;
      else if (liveState(s.slurmState)) s.state = PieceState::Running;
      else s.state = PieceState::Failed;
      if (s.slurmState == "COMPLETED") s.reason = "its output is missing or was changed since";
    } else {
      s.state = PieceState::Failed;  // the scheduler no longer knows the task and it left no marker
      s.slurmState = "ENDED";
    }
    if (s.state == PieceState::Failed && !rc.empty() && rc != "0") s.exitCode = rc;
  }
  return states;
}

Submission Farm::submit() {
  Submission result;
  std::error_code ec;
  fs::create_directories(m_directory / "logs", ec);
  if (ec) fail(ErrorKind::Output, "farm: cannot create the work directory '{}': {}", m_directory.string(), ec.message());
  // One submission at a time per plan: a second identical command waits here, then sees the
  // first one's jobs in the record and follows them.
  const FileLock lock(m_directory / "lock");
  loadRecord();
  if (joinedBefore()) {
    result.alreadyJoined = true;
    return result;
  }
  if (auto missing = m_scheduler->unavailable()) throw Error(ErrorKind::Input, *missing);

  const auto states = status();
  std::vector<int> needed;
  std::vector<std::string> dependencies;
  for (int i = 0; i < int(states.size()); ++i) {
    const PieceState s = states[std::size_t(i)].state;
    if (s == PieceState::Done) {
      result.reused.push_back(i);
    } else if (s == PieceState::Queued || s == PieceState::Running) {
      result.reused.push_back(i);
      dependencies.push_back(m_pieceJobs[std::size_t(i)]);
    } else {
      needed.push_back(i);
    }
  }
  if (!needed.empty()) {
    const fs::path script = m_directory / "pieces.sh";
    writeTextAtomically(script, pieceScript(needed));
    for (int i : needed) {
      fs::remove(markerOf(m_directory, m_pieceKeys[std::size_t(i)]), ec);
      fs::remove(rcOf(m_directory, m_pieceKeys[std::size_t(i)]), ec);
    }
    m_arrayJob = m_scheduler->submit({.script = script, .arrayTasks = needed});
    for (int i : needed) m_pieceJobs[std::size_t(i)] = m_arrayJob + "_" + std::to_string(i);
    dependencies.insert(dependencies.begin(), m_arrayJob);
    result.arrayJob = m_arrayJob;
    saveRecord();  // before the join: a failure below still leaves the pieces known
  }
  result.submitted = needed;
  // A join from the last submission that is still waiting: kept when nothing was resubmitted
  // (it waits for exactly these pieces), else cancelled (it would wait for a failed one).
  std::string oldJoinState;
  if (!m_joinJob.empty())
    for (const auto& [id, record] : m_scheduler->query(m_joinJob)) oldJoinState = record.state;
  if (!m_plan.join.empty() && liveState(oldJoinState)) {
    if (needed.empty()) {
      result.joinJob = m_joinJob;
      saveRecord();
      return result;
    }
    m_scheduler->cancel(m_joinJob);
  }
  if (!m_plan.join.empty()) {
    const fs::path script = m_directory / "join.sh";
    writeTextAtomically(script, joinScript());
    fs::remove(m_directory / "joined", ec);
    m_joinJob = m_scheduler->submit({.script = script, .afterOk = dependencies});
    result.joinJob = m_joinJob;
  }
  saveRecord();
  return result;
}

namespace {
/// The pieces counted by state: what wait() reports and decides on.
struct PieceCounts {
  int done = 0, running = 0, queued = 0;
  std::vector<int> failed, neverStart;
  std::map<std::string, int> reasons;  // why the queued ones wait
};

/// Counts `states` by state; queued pieces that can never start are listed too.
PieceCounts countPieces(const std::vector<PieceStatus>& states) {
  PieceCounts c;
  for (int i = 0; i < int(states.size()); ++i) {
    const PieceStatus& s = states[std::size_t(i)];
    switch (s.state) {
      case PieceState::Done: ++c.done; break;
      case PieceState::Running: ++c.running; break;
      case PieceState::Queued:
        ++c.queued;
        if (!s.reason.empty()) ++c.reasons[s.reason];
        if (reasonIsPermanent(s.reason)) c.neverStart.push_back(i);
        break;
      case PieceState::Failed: c.failed.push_back(i); break;
      case PieceState::Missing: c.failed.push_back(i); break;
    }
  }
  return c;
}

/// The exit code a failed task reports: Slurm's "code:signal" code when above 0, else 1.
int failedExitCode(const std::string& exitCode) {
  int code = 0;
  try {
    code = parseInt(exitCode.substr(0, exitCode.find(':')), "an exit code", 0, 255);
  } catch (const Error&) {
  }
  return code > 0 ? code : 1;
}

/// The report line of failed piece `i`: its state, the reason, the exit code and the log.
std::string pieceFailure(const Farm& farm, int i, const PieceStatus& s) {
  std::string what =
      s.state == PieceState::Missing ? "never submitted" : (s.slurmState.empty() ? "failed" : s.slurmState);
  if (s.slurmState == "COMPLETED" || (!s.reason.empty() && s.reason != "NonZeroExitCode"))
    what += fmt::format(" ({})", s.reason);
  return fmt::format("piece {} ({}): {}{}; log: {}", i, farm.plan().pieces[std::size_t(i)].label, what,
                     s.exitCode.empty() ? "" : ", exit code " + s.exitCode, farm.pieceLog(i).string());
}

/// wait()'s progress line: the counts, why the queued ones wait, the join, nodes that are down.
std::string progressLine(const PieceCounts& c, int total, bool hasJoin, const TaskRecord& join, Scheduler& scheduler) {
  std::string line = fmt::format("{}/{} pieces done, {} running, {} queued", c.done, total, c.running, c.queued);
  if (!c.reasons.empty()) {
    const auto most = std::max_element(c.reasons.begin(), c.reasons.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
    line += fmt::format(" ({})", explainReason(most->first));
  }
  if (!c.failed.empty()) line += fmt::format(", {} failed", c.failed.size());
  if (c.done == total && hasJoin) {
    line += join.state == "RUNNING" ? " · joining"
                                    : fmt::format(" · join queued{}", join.reason.empty() || join.reason == "Dependency"
                                                                          ? ""
                                                                          : " (" + explainReason(join.reason) + ")");
  }
  if ((c.queued > 0 && c.running == 0) || (c.done == total && join.state == "PENDING")) {
    for (const auto& problem : scheduler.nodeProblems()) line += "; " + problem;
  }
  return line;
}

/// Reports the tasks that can never start (the join too when `join` is given) and cancels
/// every task of the submission.
void cancelNeverStarting(Farm& farm, const std::vector<std::string>& pieceJobs, const std::vector<PieceStatus>& states,
                         const std::vector<int>& neverStart, const TaskRecord* join, WaitResult& result) {
  for (int i : neverStart) {
    const PieceStatus& s = states[std::size_t(i)];
    result.failures.push_back(fmt::format("piece {} ({}): can never start: {}", i,
                                          farm.plan().pieces[std::size_t(i)].label, explainReason(s.reason)));
  }
  if (join) result.failures.push_back(fmt::format("join: can never start: {}", explainReason(join->reason)));
  if (!farm.arrayJob().empty()) farm.scheduler().cancel(farm.arrayJob());
  for (const auto& job : pieceJobs)
    if (!job.empty() && job.substr(0, job.find('_')) != farm.arrayJob()) farm.scheduler().cancel(job);
  if (!farm.joinJob().empty()) farm.scheduler().cancel(farm.joinJob());
  result.failures.push_back("the queued tasks were cancelled: change the request (--cpus-per-task, --mem, --time, "
                            "--partition) and run again");
  result.exitCode = 2;
  result.cannotStart = true;
}

/// Reports how the submission ended without its outputs: every failed piece, else the join;
/// a join still waiting for a failed piece is cancelled.
void reportEnded(Farm& farm, const std::vector<PieceStatus>& states, const std::vector<int>& failed,
                 const TaskRecord& join, WaitResult& result) {
  for (int i : failed) {
    const PieceStatus& s = states[std::size_t(i)];
    result.failures.push_back(pieceFailure(farm, i, s));
    if (result.exitCode == 0) result.exitCode = failedExitCode(s.exitCode);
  }
  if (failed.empty()) {
    result.failures.push_back(fmt::format("join: {}{}; log: {}", join.state.empty() ? "ended" : join.state,
                                          join.exitCode.empty() ? "" : ", exit code " + join.exitCode,
                                          farm.joinLog().string()));
    result.exitCode = failedExitCode(join.exitCode);
  } else if (!farm.joinJob().empty() && liveState(join.state)) {
    farm.scheduler().cancel(farm.joinJob());  // its dependency can never be satisfied
  }
}
}  // namespace

WaitResult Farm::wait(const std::function<void(int, int, const std::string&)>& progress, const std::atomic<bool>* stop) {
  WaitResult result;
  const int total = int(m_plan.pieces.size());
  std::string lastLine;
  const auto stopped = [&] { return stop && stop->load(); };
  while (true) {
    if (joinedBefore()) {
      result.joined = true;
      if (progress) progress(total, total, "joined");
      return result;
    }
    if (stopped()) {
      result.stopped = true;
      return result;
    }
    const auto states = status();
    const PieceCounts counts = countPieces(states);
    TaskRecord join;
    if (!m_plan.join.empty() && !m_joinJob.empty())
      for (const auto& [id, record] : m_scheduler->query(m_joinJob)) join = record;
    // A task that can never start as submitted (more CPUs than any node has): said, and
    // cancelled, instead of "queued" forever.
    const bool joinNeverStarts = counts.done == total && join.state == "PENDING" && reasonIsPermanent(join.reason);
    if (!counts.neverStart.empty() || joinNeverStarts) {
      cancelNeverStarting(*this, m_pieceJobs, states, counts.neverStart, joinNeverStarts ? &join : nullptr, result);
      return result;
    }
    const bool live = counts.running + counts.queued > 0;
    const bool joinEnded = !m_plan.join.empty() && (m_joinJob.empty() || !liveState(join.state));
    if (!live && (!counts.failed.empty() || joinEnded)) {
      if (joinedBefore()) continue;  // the join finished between the two looks
      reportEnded(*this, states, counts.failed, join, result);
      return result;
    }
    const std::string line = progressLine(counts, total, !m_plan.join.empty(), join, *m_scheduler);
    if (progress && line != lastLine) progress(counts.done, total, line);
    lastLine = line;
    for (int i = 0; i < 6 && !stopped(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace glint::farm
