#include "glint/farm/farm.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/hash.h"
#include "glint/core/text.h"
#include "process.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;

namespace glint::farm {

using detail::runProcess;

namespace {

constexpr const char* kMissingSlurm =
    "sbatch not found: glint farm submits through Slurm's client commands; install Debian's slurm-client "
    "(apt install slurm-client) and point SLURM_CONF at the cluster's slurm.conf";

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
  for (const auto& a : argv) line += (line.empty() ? "" : " ") + shellWord(a);
  return line;
}

/// "0-3,5,7-8%2" → {0,1,2,3,5,7,8}.
std::set<int> parseTaskRange(const std::string& text) {
  std::set<int> tasks;
  const std::string body = text.substr(0, text.find('%'));
  std::stringstream parts(body);
  std::string part;
  while (std::getline(parts, part, ',')) {
    if (part.empty()) continue;
    const auto dash = part.find('-');
    try {
      const int lo = std::stoi(part.substr(0, dash));
      const int hi = dash == std::string::npos ? lo : std::stoi(part.substr(dash + 1));
      for (int t = lo; t <= hi && t - lo < 1000000; ++t) tasks.insert(t);
    } catch (const std::exception&) {
    }
  }
  return tasks;
}

/// One job record of `scontrol show job -o`: its Key=Value fields.
using JobRecord = std::map<std::string, std::string>;

std::vector<JobRecord> showJobs(const std::string& jobId) {
  std::vector<JobRecord> records;
  if (jobId.empty()) return records;
  const auto result = runProcess({"scontrol", "show", "job", "-o", jobId});
  if (result.exitCode != 0) return records;  // unknown (purged) or no controller: nothing known
  std::stringstream lines(result.output);
  std::string line;
  while (std::getline(lines, line)) {
    JobRecord record;
    std::stringstream fields(line);
    std::string field;
    while (fields >> field) {
      const auto eq = field.find('=');
      if (eq != std::string::npos) record[field.substr(0, eq)] = field.substr(eq + 1);
    }
    if (record.count("JobId")) records.push_back(std::move(record));
  }
  return records;
}

bool liveState(const std::string& s) {
  return s == "PENDING" || s == "CONFIGURING" || s == "RUNNING" || s == "COMPLETING" || s == "SUSPENDED" ||
         s == "REQUEUED" || s == "RESIZING" || s == "SIGNALING" || s == "STAGE_OUT";
}

std::string firstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

std::string readSmall(const fs::path& path) {
  std::ifstream in(path);
  std::string text;
  std::getline(in, text);
  return text;
}

}  // namespace

std::optional<std::string> slurmMissing() {
  if (!detail::onPath("sbatch")) return std::string(kMissingSlurm);
  return std::nullopt;
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

Farm::Farm(Plan plan, Resources resources) : m_plan(std::move(plan)), m_resources(std::move(resources)) {
  if (m_plan.pieces.empty()) fail(ErrorKind::Usage, "farm {}: nothing to do (no pieces)", m_plan.tool);
  if (m_resources.glint.empty()) m_resources.glint = selfExecutable().string();
  if (m_plan.workDir.empty()) m_plan.workDir = fs::current_path();
  m_plan.workDir = fs::absolute(m_plan.workDir).lexically_normal();
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

bool Farm::pieceDone(int i) const {
  const auto key = m_pieceKeys[std::size_t(i)];
  std::error_code ec;
  if (readSmall(markerOf(m_directory, key)) != key) return false;
  const fs::path out = pieceOutput(i);
  if (!out.empty()) return fs::file_size(out, ec) > 0 && !ec;
  for (const auto& output : m_plan.pieces[std::size_t(i)].outputs)
    if (!(fs::file_size(output, ec) > 0 && !ec)) return false;
  return true;
}

bool Farm::joinedBefore() const {
  std::error_code ec;
  if (m_plan.join.empty()) {
    for (int i = 0; i < int(m_plan.pieces.size()); ++i)
      if (!pieceDone(i)) return false;
    return true;
  }
  if (readSmall(m_directory / "joined") != m_key) return false;
  for (const auto& output : m_plan.outputs)
    if (!(fs::file_size(output, ec) > 0 && !ec)) return false;
  return true;
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
std::string directives(const Resources& r, const std::string& name, const fs::path& log) {
  std::string text = fmt::format("#SBATCH --job-name={}\n#SBATCH --output={}\n#SBATCH --chdir={}\n", name,
                                 shellWord(log.string()), shellWord(fs::current_path().string()));
  if (!r.partition.empty()) text += fmt::format("#SBATCH --partition={}\n", r.partition);
  if (!r.time.empty()) text += fmt::format("#SBATCH --time={}\n", r.time);
  if (r.memoryMiB > 0) text += fmt::format("#SBATCH --mem={}M\n", r.memoryMiB);
  if (r.cpusPerTask > 0) text += fmt::format("#SBATCH --cpus-per-task={}\n", r.cpusPerTask);
  return text;
}
}  // namespace

std::string Farm::pieceScript(const std::vector<int>& indices) const {
  std::string text = "#!/bin/bash\n";
  text += fmt::format("# glint farm {}: {} — piece $SLURM_ARRAY_TASK_ID of {} (task i runs piece i).\n", m_plan.tool,
                      m_plan.title, m_plan.pieces.size());
  text += "# Each piece is a plain glint call; the marker <key>.done says it finished (exit 0).\n";
  text += directives(m_resources, "glint-" + m_plan.tool, m_directory / "logs" / "piece-%a.log");
  text += fmt::format("set -u\ndir={}\n", shellWord(m_directory.string()));
  text += "case \"${SLURM_ARRAY_TASK_ID:?this script runs as a task of sbatch --array}\" in\n";
  for (int i : indices) {
    const Piece& piece = m_plan.pieces[std::size_t(i)];
    std::vector<std::string> outputs;
    if (!piece.extension.empty()) outputs.push_back(pieceOutput(i).string());
    for (const auto& o : piece.outputs) outputs.push_back(fs::absolute(o).lexically_normal().string());
    text += fmt::format("  {})  # {}\n    key={}\n    outputs=({})\n    cmd=({})\n    ;;\n", i, piece.label,
                        m_pieceKeys[std::size_t(i)], quoteCommand(outputs), quoteCommand(pieceCommand(i)));
  }
  text += "  *) echo \"glint farm: no piece $SLURM_ARRAY_TASK_ID in this script\" >&2; exit 2 ;;\nesac\n";
  text += "rm -f \"$dir/$key.done\" \"$dir/$key.rc\"\n";
  text += "echo \"glint farm: $(hostname): ${cmd[*]}\"\n";
  text += "\"${cmd[@]}\"\nrc=$?\n";
  text += "for f in \"${outputs[@]}\"; do\n"
          "  if [ \"$rc\" -eq 0 ] && [ ! -s \"$f\" ]; then echo \"glint farm: exit 0 but no output '$f'\" >&2; rc=1; fi\n"
          "done\n";
  text += "echo \"$rc\" > \"$dir/$key.rc\"\n";
  text += "if [ \"$rc\" -eq 0 ]; then echo \"$key\" > \"$dir/$key.done.tmp\" && mv \"$dir/$key.done.tmp\" \"$dir/$key.done\"; fi\n";
  text += "exit \"$rc\"\n";
  return text;
}

std::string Farm::joinScript() const {
  std::string text = "#!/bin/bash\n";
  text += fmt::format("# glint farm {}: {} — the join, after every piece succeeded (afterok).\n", m_plan.tool, m_plan.title);
  text += "# The intermediates are removed only after the join command succeeded.\n";
  text += directives(m_resources, "glint-" + m_plan.tool + "-join", joinLog());
  text += fmt::format("set -u\ndir={}\n", shellWord(m_directory.string()));
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
  text += fmt::format("echo {} > \"$dir/joined.tmp\" && mv \"$dir/joined.tmp\" \"$dir/joined\"\n", m_key);
  text += "rm -f \"${pieces[@]}\"\n";
  return text;
}

std::string Farm::scripts() const {
  std::vector<int> all(m_plan.pieces.size());
  for (int i = 0; i < int(all.size()); ++i) all[std::size_t(i)] = i;
  std::string text = fmt::format("# {}/pieces.sh — sbatch --array=0-{} {}/pieces.sh\n", m_directory.string(),
                                 all.size() - 1, m_directory.string());
  text += pieceScript(all);
  if (!m_plan.join.empty()) {
    text += fmt::format("\n# {}/join.sh — sbatch --dependency=afterok:ARRAY_JOB --kill-on-invalid-dep=yes {}/join.sh\n",
                        m_directory.string(), m_directory.string());
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
  writeTextAtomically(m_directory / "submission.json", record.dump(2) + "\n");
}

std::vector<PieceStatus> Farm::status() {
  std::vector<PieceStatus> states(m_plan.pieces.size());
  // Ask Slurm first, then look at the markers: a task that ends in between is then seen as
  // done rather than as completed without its marker.
  std::set<std::string> arrays;
  for (const auto& job : m_pieceJobs)
    if (!job.empty()) arrays.insert(job.substr(0, job.find('_')));
  std::map<std::string, std::pair<std::string, std::string>> known;  // "A_T" → (state, exit code)
  for (const auto& array : arrays) {
    for (const auto& record : showJobs(array)) {
      const auto a = record.find("ArrayJobId");
      const auto t = record.find("ArrayTaskId");
      if (a == record.end() || t == record.end()) continue;
      const std::string state = record.count("JobState") ? record.at("JobState") : "";
      const std::string exit = record.count("ExitCode") ? record.at("ExitCode") : "";
      for (int task : parseTaskRange(t->second)) known[a->second + "_" + std::to_string(task)] = {state, exit};
    }
  }
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
      s.slurmState = it->second.first;
      s.exitCode = it->second.second;
      if (s.slurmState == "PENDING" || s.slurmState == "CONFIGURING") s.state = PieceState::Queued;
      else if (liveState(s.slurmState)) s.state = PieceState::Running;
      else s.state = PieceState::Failed;
    } else {
      s.state = PieceState::Failed;  // Slurm no longer knows the task and it left no marker
      s.slurmState = "ENDED";
    }
    if (s.state == PieceState::Failed && !rc.empty() && rc != "0") s.exitCode = rc;
  }
  return states;
}

Submission Farm::submit() {
  Submission result;
  if (joinedBefore()) {
    result.alreadyJoined = true;
    return result;
  }
  if (auto missing = slurmMissing()) throw Error(ErrorKind::Input, *missing);
  std::error_code ec;
  fs::create_directories(m_directory / "logs", ec);
  if (ec) fail(ErrorKind::Output, "farm: cannot create the work directory '{}': {}", m_directory.string(), ec.message());

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
  const auto sbatch = [&](std::vector<std::string> argv, const fs::path& script, const std::string& what) {
    argv.insert(argv.begin(), {"sbatch", "--parsable"});
    argv.push_back(script.string());
    const auto r = runProcess(argv);
    if (r.exitCode != 0) fail(ErrorKind::Input, "farm: Slurm refused the {}: {}", what, firstLine(r.output));
    std::string id = firstLine(r.output);
    id = id.substr(0, id.find(';'));  // "1234;cluster"
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
      fail(ErrorKind::Input, "farm: sbatch answered '{}' instead of a job id", firstLine(r.output));
    return id;
  };
  if (!needed.empty()) {
    const fs::path script = m_directory / "pieces.sh";
    writeTextAtomically(script, pieceScript(needed));
    std::string array;
    for (int i : needed) {
      array += (array.empty() ? "" : ",") + std::to_string(i);
      fs::remove(markerOf(m_directory, m_pieceKeys[std::size_t(i)]), ec);
      fs::remove(rcOf(m_directory, m_pieceKeys[std::size_t(i)]), ec);
    }
    m_arrayJob = sbatch({"--array=" + array}, script, "pieces");
    for (int i : needed) m_pieceJobs[std::size_t(i)] = m_arrayJob + "_" + std::to_string(i);
    dependencies.insert(dependencies.begin(), m_arrayJob);
    result.arrayJob = m_arrayJob;
  }
  result.submitted = needed;
  // A join from the last submission that is still waiting: kept when nothing was resubmitted
  // (it waits for exactly these pieces), else cancelled (it would wait for a failed one).
  std::string oldJoinState;
  if (!m_joinJob.empty())
    for (const auto& record : showJobs(m_joinJob))
      if (record.count("JobState")) oldJoinState = record.at("JobState");
  if (!m_plan.join.empty() && liveState(oldJoinState)) {
    if (needed.empty()) {
      result.joinJob = m_joinJob;
      saveRecord();
      return result;
    }
    runProcess({"scancel", m_joinJob});
  }
  if (!m_plan.join.empty()) {
    const fs::path script = m_directory / "join.sh";
    writeTextAtomically(script, joinScript());
    fs::remove(m_directory / "joined", ec);
    std::vector<std::string> argv;
    if (!dependencies.empty()) {
      std::string dep = "--dependency=afterok";
      for (const auto& d : dependencies) dep += ":" + d;
      argv = {dep, "--kill-on-invalid-dep=yes"};
    }
    m_joinJob = sbatch(argv, script, "join");
    result.joinJob = m_joinJob;
  }
  saveRecord();
  return result;
}

WaitResult Farm::wait(const std::function<void(int, int, const std::string&)>& progress) {
  WaitResult result;
  const int total = int(m_plan.pieces.size());
  std::string lastLine;
  while (true) {
    if (joinedBefore()) {
      result.joined = true;
      if (progress) progress(total, total, "joined");
      return result;
    }
    const auto states = status();
    int done = 0, running = 0, queued = 0;
    std::vector<int> failed;
    for (int i = 0; i < total; ++i) {
      switch (states[std::size_t(i)].state) {
        case PieceState::Done: ++done; break;
        case PieceState::Running: ++running; break;
        case PieceState::Queued: ++queued; break;
        case PieceState::Failed: failed.push_back(i); break;
        case PieceState::Missing: failed.push_back(i); break;
      }
    }
    std::string joinState;
    std::string joinExit;
    if (!m_plan.join.empty() && !m_joinJob.empty()) {
      for (const auto& record : showJobs(m_joinJob)) {
        joinState = record.count("JobState") ? record.at("JobState") : "";
        joinExit = record.count("ExitCode") ? record.at("ExitCode") : "";
      }
    }
    const bool live = running + queued > 0;
    const bool joinEnded = !m_plan.join.empty() && (m_joinJob.empty() || (!liveState(joinState)));
    if (!live && (!failed.empty() || joinEnded)) {
      if (joinedBefore()) continue;  // the join finished between the two looks
      for (int i : failed) {
        const PieceStatus& s = states[std::size_t(i)];
        result.failures.push_back(fmt::format(
            "piece {} ({}): {}{}; log: {}", i, m_plan.pieces[std::size_t(i)].label,
            s.state == PieceState::Missing ? "never submitted" : (s.slurmState.empty() ? "failed" : s.slurmState),
            s.exitCode.empty() ? "" : ", exit code " + s.exitCode, pieceLog(i).string()));
        if (result.exitCode == 0) {
          const int code = std::atoi(s.exitCode.c_str());
          result.exitCode = code > 0 ? code : 1;
        }
      }
      if (failed.empty()) {
        result.failures.push_back(fmt::format("join: {}{}; log: {}", joinState.empty() ? "ended" : joinState,
                                              joinExit.empty() ? "" : ", exit code " + joinExit, joinLog().string()));
        const int code = std::atoi(joinExit.c_str());
        result.exitCode = code > 0 ? code : 1;
      } else if (!m_joinJob.empty() && liveState(joinState)) {
        runProcess({"scancel", m_joinJob});  // its dependency can never be satisfied
      }
      return result;
    }
    std::string line = fmt::format("{}/{} pieces done, {} running, {} queued{}", done, total, running, queued,
                                   failed.empty() ? "" : fmt::format(", {} failed", failed.size()));
    if (done == total && !m_plan.join.empty()) line += joinState == "RUNNING" ? " · joining" : " · join queued";
    if (progress && line != lastLine) progress(done, total, line);
    lastLine = line;
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
}

}  // namespace glint::farm
