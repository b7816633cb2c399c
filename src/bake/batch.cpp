// Batches of bakes (bake/job.h): a JSON file's jobs parsed by the command's own option
// definitions (a key is an option's long name), checked together, run one after another
// with their high meshes shared (farm_plan.cpp plans them for a farm).
#include "glint/bake/job.h"

#include "glint/core/json.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/core/text.h"
#include "job_internal.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <mutex>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace glint::bake {

using Json = nlohmann::ordered_json;

namespace {

/// Inside a catch block: the same Error, its message prefixed with `where` ("bake: jobs.json job 2 (crate_low.obj)").
[[noreturn]] void rethrowIn(const std::string& where) {
  try {
    throw;
  } catch (const Error& e) {
    throw Error(e.kind(), fmt::format("{}: {}", where, e.what()));
  }
}

/// A batch file: the defaults and one object per job, in order.
struct BatchFile {
  Json defaults = Json::object();
  std::vector<Json> jobs;
};

BatchFile readBatchFile(const std::string& path) {
  const std::string text = readTextFile(path);  // Error(Input): exit 3, like every unreadable input
  const Json doc = parseJson<Json>(text, fmt::format("bake: {}", path), ErrorKind::Usage);
  if (!doc.is_object())
    fail(ErrorKind::Usage, "bake: {}: a batch file is an object {{\"defaults\": {{...}}, \"bakes\": [...]}}, got {}", path,
         doc.type_name());
  BatchFile batch;
  for (const auto& [key, value] : doc.items()) {
    if (key == "defaults") {
      if (!value.is_object()) fail(ErrorKind::Usage, "bake: {}: \"defaults\" must be an object of options, got {}", path, value.type_name());
      batch.defaults = value;
    } else if (key == "bakes") {
      if (!value.is_array()) fail(ErrorKind::Usage, "bake: {}: \"bakes\" must be a list of jobs, got {}", path, value.type_name());
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (!value[i].is_object())
          fail(ErrorKind::Usage, "bake: {} job {}: a job must be an object of options, got {}", path, i, value[i].type_name());
        batch.jobs.push_back(value[i]);
      }
    } else {
      fail(ErrorKind::Usage, "bake: {}: unknown key '{}' (a batch file has \"defaults\" and \"bakes\")", path, printable(key));
    }
  }
  if (batch.jobs.empty()) fail(ErrorKind::Usage, "bake: {}: no jobs: \"bakes\" is missing or empty", path);
  return batch;
}

/// The option a batch file's key stands for: its long name without the dashes ("size",
/// "output"), or a positional's name ("low"). Null when there is none (help included).
const CLI::Option* optionForKey(const CLI::App& app, const std::string& key) {
  for (const CLI::Option* option : app.get_options()) {
    if (option == app.get_help_ptr()) continue;
    const auto& names = option->get_lnames();
    if (std::find(names.begin(), names.end(), key) != names.end()) return option;
    if (option->get_positional() && names.empty() && option->get_single_name() == key) return option;
  }
  return nullptr;
}

/// `settings` with each key replaced by its option's first name; Error(Usage) naming a key
/// that is no option.
Json canonicalKeys(const CLI::App& app, const Json& settings) {
  Json out = Json::object();
  for (const auto& [key, value] : settings.items()) {
    const CLI::Option* option = optionForKey(app, key);
    if (!option) fail(ErrorKind::Usage, "unknown key '{}': not an option of glint bake (see glint bake --help)", printable(key));
    out[option->get_single_name()] = value;
  }
  return out;
}


/// The bake command's options, made once (a CLI::App with every option is ~0.3 ms to build):
/// parseJob and jobFromSettings share it under its lock.
struct BakeParser {
  std::mutex mutex;
  CLI::App app{"glint bake", "bake"};
  BakeJob bound;
  BakeParser() { addOptions(app, bound, Meshes::Required); }
  static BakeParser& instance() {
    static BakeParser parser;
    return parser;
  }
};

/// Parses a job's argument list exactly as the command line is parsed: the bake command's
/// options, from their defaults. Error(Usage) with CLI11's message.
BakeJob parseJob(const std::vector<std::string>& arguments) {
  BakeParser& parser = BakeParser::instance();
  std::lock_guard lock(parser.mutex);
  parser.bound = BakeJob{};  // CLI11 writes only the options given: the rest keep these defaults
  parser.app.clear();
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 takes them last first
  try {
    parser.app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    fail(ErrorKind::Usage, "{}", e.what());
  }
  return parser.bound;
}

/// Every job of a batch through the command line's option parsing: its argument list
/// (defaults, then the job, then `commandLine`, later layers winning) and its parsed options.
std::vector<BatchJob> parseBatchJobs(const BatchFile& batch, const std::string& file, const Json& commandLine) {
  const int count = int(batch.jobs.size());
  CLI::App prototype{"glint bake", "bake"};
  BakeJob unused;
  addOptions(prototype, unused, Meshes::Required);
  const fs::path base = fs::path(file).parent_path();
  Json defaults;
  try {
    defaults = canonicalKeys(prototype, batch.defaults);
  } catch (const Error&) {
    rethrowIn(fmt::format("bake: {} defaults", file));
  }
  std::vector<BatchJob> jobs(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    BatchJob& job = jobs[std::size_t(i)];
    const Json& raw = batch.jobs[std::size_t(i)];
    const Json* low = raw.contains("low") ? &raw["low"] : batch.defaults.contains("low") ? &batch.defaults["low"] : nullptr;
    job.where = fmt::format("bake: {} job {}", file, i);
    if (low && low->is_string()) job.where += fmt::format(" ({})", printable(low->get<std::string>()));
    try {
      const Json settings = canonicalKeys(prototype, raw);
      job.arguments = argumentsFor(prototype, {&defaults, &settings, &commandLine}, base);
      job.job = parseJob(job.arguments);
    } catch (const Error&) {
      rethrowIn(job.where);
    }
  }
  return jobs;
}

/// The whole batch's checks (loadBatch's): distinct files across every job, the report
/// writable, each job's own checks.
void checkBatch(const std::string& file, const std::vector<BatchJob>& jobs, const ToolSettings& batch) {
  // No output is an input or another output of any job (also with --job, so that every farm
  // task agrees on whether the file is valid).
  std::vector<FileUse> inputs{{file, "the batch file"}}, outputs;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const auto named = [i](const FileUse& f) {
      return FileUse{f.path, f.role.starts_with("the ") ? fmt::format("job {}'s {}", i, f.role.substr(4))
                                                        : fmt::format("job {} {}", i, f.role)};
    };
    for (const FileUse& f : inputFiles(jobs[i].job)) inputs.push_back(named(f));
    for (const FileUse& f : outputFiles(jobs[i].job)) outputs.push_back(named(f));
  }
  outputs.push_back({batch.json, "--json"});
  try {
    checkDistinctFiles(inputs, outputs);
    if (!batch.json.empty() && batch.json != "-") checkWritable(batch.json);
  } catch (const Error&) {
    rethrowIn(fmt::format("bake: {}", file));
  }
  // Every job's own checks (options, folders, memory), each as its bake will make them.
  for (const BatchJob& job : jobs) {
    try {
      ToolRun check("bake", job.job.tool);
      checkJob(job.job, check);
    } catch (const Error&) {
      rethrowIn(job.where);
    }
  }
}

}  // namespace

std::vector<std::string> argumentsFor(const CLI::App& app, const std::vector<const Json*>& layers, const fs::path& base) {
  Json merged = Json::object();
  for (const Json* layer : layers)
    for (const auto& [key, value] : layer->items()) merged[key] = value;
  std::vector<std::string> positionals, named;
  for (const CLI::Option* option : app.get_options()) {
    const std::string& key = option->get_single_name();
    if (option == app.get_help_ptr() || !merged.contains(key)) continue;
    const Json& value = merged[key];
    const std::string spelling = option->get_snames().empty() ? "--" + key : "-" + option->get_snames().front();
    if (option->get_expected_max() == 0) {  // a flag
      if (!value.is_boolean()) fail(ErrorKind::Usage, "'{}' is a flag: true or false, got {}", key, printable(value.dump()));
      if (value.get<bool>()) named.push_back(spelling);
      continue;
    }
    std::string text;
    if (value.is_string()) text = value.get<std::string>();
    else if (value.is_number()) text = value.dump();
    else fail(ErrorKind::Usage, "'{}' takes a value (a string or a number), got {}", key, printable(value.dump()));
    if (option->get_type_name() == kFile && !text.empty() && text != "-") {
      fs::path path(text);
      if (path.is_relative() && !base.empty()) path = base / path;
      text = path.string();
      if (text.starts_with('-')) text = "./" + text;  // a file, not an option
    }
    if (option->get_positional()) {
      positionals.push_back(text);
    } else if (text.starts_with('-')) {  // a negative number: one word, not taken for an option
      named.push_back("--" + key + "=" + text);
    } else {
      named.push_back(spelling);
      named.push_back(text);
    }
  }
  const bool dashed = std::any_of(positionals.begin(), positionals.end(), [](const std::string& p) { return p.starts_with('-'); });
  if (dashed) {  // after "--", where nothing is an option
    named.push_back("--");
    named.insert(named.end(), positionals.begin(), positionals.end());
    return named;
  }
  positionals.insert(positionals.end(), named.begin(), named.end());
  return positionals;
}

BakeJob jobFromSettings(const Json& settings) {
  std::vector<std::string> arguments;
  {
    BakeParser& parser = BakeParser::instance();
    std::lock_guard lock(parser.mutex);
    Json dashed = Json::object();
    for (const auto& [key, value] : settings.items()) {
      std::string name = key;
      std::replace(name.begin(), name.end(), '_', '-');
      dashed[name] = value;
    }
    const Json canonical = canonicalKeys(parser.app, dashed);
    arguments = argumentsFor(parser.app, {&canonical}, {});
  }
  return parseJob(arguments);
}

Json givenOptions(const CLI::App& cmd, const std::vector<const CLI::Option*>& except) {
  Json given = Json::object();
  for (const CLI::Option* option : cmd.get_options()) {
    if (option == cmd.get_help_ptr() || option->count() == 0 || option->get_positional() ||
        std::find(except.begin(), except.end(), option) != except.end())
      continue;
    if (option->get_expected_max() == 0) given[option->get_single_name()] = true;
    else given[option->get_single_name()] = option->results().back();
  }
  return given;
}

std::vector<BatchJob> loadBatch(const std::string& file, const Json& overrides) {
  std::vector<BatchJob> jobs = parseBatchJobs(readBatchFile(file), file, overrides.is_object() ? overrides : Json::object());
  checkBatch(file, jobs, {});
  return jobs;
}

namespace {

/// How one job of a batch ended.
struct Outcome {
  int job = 0;
  double seconds = 0.0;
  int status = 0;  ///< its exit status: 0 done
  std::string error;
};

/// The selected jobs as `glint bake ...` command lines, one a line (--list).
void listJobs(const std::vector<BatchJob>& jobs, const std::vector<int>& selected) {
  for (int i : selected) {
    std::string line = "glint bake";
    for (const std::string& word : jobs[std::size_t(i)].arguments) {
      line += ' ';
      line += shellWord(word);
    }
    std::printf("%s\n", line.c_str());
  }
  std::fflush(stdout);
}

/// One job after another (each bake already uses every core), their high meshes shared:
/// each job's outcome and report entry. A failed job is said and the batch goes on; Ctrl-C
/// stops it (Error(Interrupted), no partial file). `firstFailure`: the first failed job's kind.
std::vector<Outcome> runSelected(const BatchRequest& request, const std::vector<BatchJob>& jobs,
                                 const std::vector<int>& selected, Json& reports, std::optional<ErrorKind>& firstFailure) {
  std::vector<Outcome> outcomes;
  HighMeshCache highCache;  // jobs sharing a high poly read it and build its BVH once
  for (int i : selected) ++highCache.usesLeft[jobs[std::size_t(i)].job.high];
  for (std::size_t k = 0; k < selected.size(); ++k) {
    const int i = selected[k];
    const BatchJob& job = jobs[std::size_t(i)];
    const std::string step = fmt::format("{}/{}", k + 1, selected.size());
    log::info("bake {}: job {}: {} → {}", step, i, job.job.low, job.job.output);
    Outcome outcome{.job = i};
    Json entry = Json::object();
    entry["job"] = i;
    ToolRun run("bake", job.job.tool);
    try {
      highCache.progressLabel = "bake " + step;
      BakeJob withGpu = job.job;
      withGpu.glDebug = withGpu.glDebug || request.glDebug;
      runJob(withGpu, run, &highCache, request.gpu);
      entry["status"] = "ok";
      entry.update(run.finish());
    } catch (const Error& e) {
      if (e.kind() == ErrorKind::Interrupted) throw;
      outcome.status = exitCode(e.kind());
      outcome.error = fmt::format("{}: {}", job.where, e.what());
      log::error("{}", outcome.error);
      if (!firstFailure) firstFailure = e.kind();
      entry["status"] = "failed";
      entry["exit_status"] = outcome.status;
      entry["error"] = outcome.error;
      entry.update(run.completedReport());
    }
    highCache.done(job.job.high);
    outcome.seconds = run.elapsed();
    outcomes.push_back(outcome);
    reports.push_back(std::move(entry));
  }
  return outcomes;
}

/// The batch's --json report: every job's report, the failures, the time.
void writeBatchReport(const BatchRequest& request, Json reports, std::size_t failed, double seconds) {
  Json report;
  report["tool"] = "bake";
  report["version"] = ToolRun::version();
  report["batch"] = request.file;
  report["jobs"] = std::move(reports);
  report["failed"] = failed;
  report["seconds"] = {{"total", seconds}};
  report["peak_memory_mib"] = ToolRun::peakMemoryMiB();
  const std::string text = jsonText(report);
  if (request.tool.json == "-") {
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
  } else {
    writeTextAtomically(request.tool.json, text);
  }
}

/// Each failure was printed when it happened; the batch's error names the failed jobs (ten
/// at most) and has the first one's kind, hence its exit status.
[[noreturn]] void failBatch(const BatchRequest& request, const std::vector<Outcome>& outcomes, std::size_t failed,
                            ErrorKind first) {
  std::string which;
  std::size_t named = 0;
  for (const Outcome& o : outcomes) {
    if (o.status == 0) continue;
    if (++named > 10) {
      which += ", ...";
      break;
    }
    which += fmt::format("{}{}", named == 1 ? "" : ", ", o.job);
  }
  fail(first, "bake: {}: {} of {} job{} failed (job{} {})", request.file, failed, outcomes.size(),
       outcomes.size() == 1 ? "" : "s", failed == 1 ? "" : "s", which);
}

}  // namespace

int runBatch(const BatchRequest& request) {
  // Every job through the command line's option parsing, before anything runs.
  std::vector<BatchJob> jobs = parseBatchJobs(readBatchFile(request.file), request.file, request.overrides);
  // --device auto takes a GPU only where this program has a hardware one (memory estimates).
  const bool anyAuto = std::any_of(jobs.begin(), jobs.end(), [](const BatchJob& j) { return j.job.device == "auto"; });
  const bool hardware = anyAuto && gpuPossible("auto", request.gpu);
  for (BatchJob& j : jobs) j.job.gpuPossible = j.job.device != "auto" || hardware;
  const int count = int(jobs.size());
  if (request.job >= count || request.job < -1)
    fail(ErrorKind::Usage, "bake: --job {} is out of range: {} has {} job{} (0 to {})", request.job, request.file, count,
         count == 1 ? "" : "s", count - 1);
  std::vector<int> selected;
  for (int i = 0; i < count; ++i)
    if (request.job < 0 || request.job == i) selected.push_back(i);
  if (request.list) {
    listJobs(jobs, selected);
    return 0;
  }
  checkBatch(request.file, jobs, request.tool);

  const auto start = std::chrono::steady_clock::now();
  const log::Level level = log::level();
  if (request.tool.quiet && level < log::Level::Warn) log::setLevel(log::Level::Warn);
  Json reports = Json::array();
  std::optional<ErrorKind> firstFailure;
  std::vector<Outcome> outcomes;
  try {
    outcomes = runSelected(request, jobs, selected, reports, firstFailure);
  } catch (...) {
    log::setLevel(level);
    throw;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::size_t failed = std::size_t(std::count_if(outcomes.begin(), outcomes.end(), [](const Outcome& o) { return o.status != 0; }));
  log::info("bake: {}: {} job{} in {:.2f} s, {} ok, {} failed", request.file, outcomes.size(),
            outcomes.size() == 1 ? "" : "s", seconds, outcomes.size() - failed, failed);
  for (const Outcome& o : outcomes) {
    log::info("  job {:<3} {:<40} {:7.2f} s  {}", o.job, jobs[std::size_t(o.job)].job.output, o.seconds,
              o.status == 0 ? std::string("ok") : fmt::format("failed (exit {})", o.status));
  }
  log::setLevel(level);
  if (!request.tool.json.empty()) writeBatchReport(request, std::move(reports), failed, seconds);
  if (firstFailure) failBatch(request, outcomes, failed, *firstFailure);
  return 0;
}

}  // namespace glint::bake
