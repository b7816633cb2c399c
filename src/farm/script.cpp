#include "script.h"

#include "glint/core/error.h"
#include "glint/core/text.h"
#include "glint/farm/scheduler.h"

#include <fmt/format.h>

#include <utility>
#include <vector>

namespace glint::farm {

namespace detail {

std::string commentText(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (c == '\\') out += "\\\\";
    else if (u < 0x20 || u == 0x7f) out += fmt::format("\\x{:02x}", u);
    else out += c;
  }
  return out;
}

std::string scriptWord(std::string_view word) {
  bool control = false;
  for (const char c : word) control = control || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  if (!control) return shellWord(word);
  std::string out = "$'";
  for (const char c : word) {
    if (c == '\'' || c == '\\') out += std::string("\\") + c;
    else out += commentText(std::string_view(&c, 1));
  }
  return out + "'";
}

std::string directiveValue(std::string_view value, std::string_view what) {
  for (const char c : value) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      fail(ErrorKind::Usage, "farm: {} '{}' holds a control character (a line break, say): an #SBATCH line cannot "
           "hold it; choose another", what, printable(value));
    }
    if (c == '\\') {
      fail(ErrorKind::Usage, "farm: {} '{}' holds a backslash, which sbatch reads as an escape (and which stops Slurm "
           "expanding %a in log names); choose another", what, printable(value));
    }
  }
  if (value.empty()) fail(ErrorKind::Usage, "farm: {} is empty", what);
  // Quoted as a shell word: sbatch's directive parser takes '...' and \' as the shell does.
  return shellWord(value);
}

std::string outputPattern(std::string_view directory, std::string_view file, std::string_view what) {
  (void)directiveValue(directory, what);  // the checks, on the text as given
  std::string doubled;
  for (const char c : directory) doubled += c == '%' ? std::string("%%") : std::string(1, c);
  return shellWord(doubled + "/" + std::string(file));
}

}  // namespace detail

namespace {

/// One #SBATCH line's words, split as sbatch splits a directive: whitespace between words,
/// quotes (' or ") group, a backslash takes the next character as it is, an unquoted `#`
/// ends the line.
std::vector<std::string> directiveWords(std::string_view line) {
  std::vector<std::string> words;
  std::string word;
  bool inWord = false, escaped = false;
  char quote = 0;
  for (const char c : line) {
    if (escaped) {
      word += c;
      escaped = false;
      inWord = true;
      continue;
    }
    if (c == '\\') {
      escaped = true;
      inWord = true;
      continue;
    }
    if (quote) {
      if (c == quote) quote = 0;
      else word += c;
      continue;
    }
    if (c == '"' || c == '\'') {
      quote = c;
      inWord = true;
      continue;
    }
    if (c == '#') break;
    if (c == ' ' || c == '\t') {
      if (inWord) words.push_back(std::exchange(word, {}));
      inWord = false;
      continue;
    }
    word += c;
    inWord = true;
  }
  if (inWord) words.push_back(word);
  return words;
}

std::string longName(const std::string& option) {
  if (option.starts_with("--")) return option.substr(2);
  static const std::pair<const char*, const char*> shorts[] = {
      {"-o", "output"}, {"-e", "error"}, {"-D", "chdir"}, {"-J", "job-name"}, {"-p", "partition"},
      {"-t", "time"},   {"-c", "cpus-per-task"}, {"-a", "array"}, {"-d", "dependency"}};
  for (const auto& [s, l] : shorts)
    if (option == s) return l;
  return option.substr(1);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> readDirectives(const std::string& script) {
  std::vector<std::pair<std::string, std::string>> directives;
  std::size_t start = 0;
  bool first = true;
  while (start < script.size()) {
    std::size_t end = script.find('\n', start);
    if (end == std::string::npos) end = script.size();
    const std::string_view line(script.data() + start, end - start);
    start = end + 1;
    if (first) {  // the interpreter line
      first = false;
      if (line.starts_with("#!")) continue;
    }
    const std::size_t text = line.find_first_not_of(" \t\r");
    if (text == std::string_view::npos) continue;  // blank
    if (line[text] != '#') break;                  // the first command: no directive after it counts
    if (!line.starts_with("#SBATCH")) continue;
    const std::vector<std::string> words = directiveWords(line.substr(7));
    for (std::size_t i = 0; i < words.size(); ++i) {
      const std::string& w = words[i];
      if (!w.starts_with('-')) continue;
      const std::size_t eq = w.find('=');
      if (eq != std::string::npos) {
        directives.emplace_back(longName(w.substr(0, eq)), w.substr(eq + 1));
      } else if (i + 1 < words.size() && !words[i + 1].starts_with('-')) {
        directives.emplace_back(longName(w), words[i + 1]);
        ++i;
      } else {
        directives.emplace_back(longName(w), "");
      }
    }
  }
  return directives;
}

bool liveState(const std::string& s) {
  return s == "PENDING" || s == "CONFIGURING" || s == "RUNNING" || s == "COMPLETING" || s == "SUSPENDED" ||
         s == "REQUEUED" || s == "REQUEUE_HOLD" || s == "REQUEUE_FED" || s == "RESIZING" || s == "SIGNALING" ||
         s == "STAGE_OUT" || s == "RESV_DEL_HOLD";
}

namespace {
struct Reason {
  const char* name;
  const char* words;
  bool permanent;
};
// Slurm's job reason codes (squeue(1), "JOB REASON CODES") that a farm user meets.
constexpr Reason kReasons[] = {
    {"Resources", "waiting for free CPUs or memory", false},
    {"Priority", "other jobs go first", false},
    {"Dependency", "waiting for the pieces", false},
    {"BeginTime", "waiting for its start time", false},
    {"JobHeldUser", "held (scontrol release)", false},
    {"JobHeldAdmin", "held by an administrator", false},
    {"ReqNodeNotAvail", "the nodes it may use are down, drained or reserved", false},
    {"NodeDown", "a node it needs is down", false},
    {"PartitionDown", "the partition is down", false},
    {"PartitionInactive", "the partition is inactive", false},
    {"Reservation", "waiting for its reservation", false},
    {"QOSMaxCpuPerUserLimit", "your CPU limit is reached", false},
    {"AssocGrpCpuLimit", "your account's CPU limit is reached", false},
    {"PartitionConfig", "the request exceeds what the partition allows: CPUs, memory or time per task", true},
    {"PartitionNodeLimit", "the request needs more nodes than the partition allows", true},
    {"PartitionTimeLimit", "--time is above the partition's limit", true},
    {"BadConstraints", "no node can meet the request: CPUs or memory per task", true},
    {"InvalidQOS", "the job's QOS is not valid", true},
    {"InvalidAccount", "the job's account is not valid", true},
    {"DependencyNeverSatisfied", "a piece it waits for failed", true},
    {"runner gone", "its runner process is gone (the machine restarted?)", true},
};
}  // namespace

std::string explainReason(const std::string& reason) {
  for (const Reason& r : kReasons)
    if (reason == r.name) return fmt::format("{} ({})", r.name, r.words);
  return reason;
}

bool reasonIsPermanent(const std::string& reason) {
  for (const Reason& r : kReasons)
    if (reason == r.name) return r.permanent;
  return false;
}

}  // namespace glint::farm
