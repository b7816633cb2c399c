// glint farm's rules without a cluster and without root (issues 33 and 34): the local
// scheduler runs the very batch scripts a Slurm cluster gets, as child processes, so the
// submit / resubmit-only-what-failed / cancel / failure-report logic of farm::Farm is tested
// here; a scheduler written in this file stands in for Slurm's answers that a single machine
// never gives (a task that can never start). The pieces run a stand-in for glint (a bash
// script, kFakeGlint) so that each case takes a fraction of a second.
#include "glint/core/error.h"
#include "glint/farm/farm.h"
#include "glint/farm/scheduler.h"
#include "support/cli.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::readBytes;

namespace {

fs::path dir(const std::string& name) { return glint::testing::freshDir("farm-local", name); }

/// A stand-in for glint: `piece OUT TEXT [FAIL_IF]` writes TEXT to OUT (exit 3 while the file
/// FAIL_IF exists); `join OUT PIECES...` concatenates the pieces; `slow OUT SECONDS` sleeps,
/// then writes OUT. Every call appends its arguments, one per line, to args.log beside it.
constexpr const char* kFakeGlint = R"(#!/bin/bash
log="$(dirname "$0")/args.log"
printf '[%s]\n' "$@" >> "$log"
case $1 in
  piece) if [ -n "${4:-}" ] && [ -e "$4" ]; then echo "failing as asked" >&2; exit 3; fi; printf '%s' "$3" > "$2" ;;
  join) out=$2; shift 2; cat -- "$@" > "$out" ;;
  slow) sleep "$3"; printf 'slow' > "$2" ;;
  *) exit 9 ;;
esac
)";

fs::path fakeGlint(const fs::path& d) {
  const fs::path path = d / "fake-glint";
  std::ofstream(path) << kFakeGlint;
  fs::permissions(path, fs::perms::owner_all);
  return path;
}

/// Names that break scripts that do not quote: a line break followed by a command, $(),
/// backticks, quotes, a semicolon, a comment sign, non-ASCII.
const std::vector<std::string> kEvil = {
    "b\ntouch PWNED #.mp4", "$(touch PWNED)", "`touch PWNED`", "it's \"quoted\"", "a; touch PWNED", "#SBATCH --mem=1",
    "clip – ünïcode ✓", "100% done %a %j"};

/// A plan of one piece per evil text (each writes its text) and a join concatenating them.
farm::Plan evilPlan(const fs::path& d, const fs::path& work) {
  farm::Plan plan{.tool = "post", .title = kEvil[0] + " → " + kEvil[1]};
  for (std::size_t i = 0; i < kEvil.size(); ++i) {
    farm::Piece piece{.label = kEvil[i], .command = {"piece", farm::kPieceOutput, kEvil[i]}, .extension = ".txt"};
    piece.inputs = {d / "fake-glint"};
    plan.pieces.push_back(piece);
  }
  plan.join = {"join", (d / ("out " + kEvil[0])).string(), farm::kAllPieceOutputs};
  plan.outputs = {d / ("out " + kEvil[0])};
  plan.workDir = work;
  return plan;
}

std::string expectedJoin() {
  std::string all;
  for (const auto& e : kEvil) all += e;
  return all;
}

bool anyPwned(const fs::path& d) {
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(d, ec))
    if (e.path().filename() == "PWNED") return true;
  return fs::exists(fs::current_path() / "PWNED");
}

farm::Resources resources(const fs::path& d) {
  return {.partition = "a b's", .time = "1:00:00", .memoryMiB = 512, .cpusPerTask = 1, .glint = fakeGlint(d).string()};
}

}  // namespace

TEST(FarmScripts, EveryStringIsQuotedEscapedOrRefusedAndEveryDirectiveIsKept) {
  const fs::path d = dir("scripts");
  const fs::path work = d / "work $(touch PWNED) `x` 'q' ; 50%";
  farm::Farm job(evilPlan(d, work), resources(d), farm::localScheduler(d / "spool"));
  const std::string scripts = job.scripts();
  // Two scripts, each headed by a comment naming it; split them.
  const std::size_t joinAt = scripts.find("\n\n# ");
  ASSERT_NE(joinAt, std::string::npos);
  const std::string pieces = scripts.substr(scripts.find("#!/bin/bash"), joinAt - scripts.find("#!/bin/bash"));
  const std::string join = scripts.substr(scripts.find("#!/bin/bash", joinAt));
  for (const std::string* script : {&pieces, &join}) {
    const auto directives = farm::readDirectives(*script);
    std::map<std::string, std::string> byName(directives.begin(), directives.end());
    EXPECT_EQ(directives.size(), 7u) << *script;  // job-name output chdir partition time mem cpus-per-task
    EXPECT_EQ(byName["chdir"], job.directory().string());
    std::string doubled;  // sbatch expands %: the directory's own are doubled
    for (char c : job.directory().string()) doubled += c == '%' ? std::string("%%") : std::string(1, c);
    EXPECT_EQ(byName["output"], doubled + (script == &pieces ? "/logs/piece-%a.log" : "/logs/join.log"));
    EXPECT_EQ(byName["partition"], "a b's");
    EXPECT_EQ(byName["time"], "1:00:00");
    EXPECT_EQ(byName["mem"], "512M");
    EXPECT_EQ(byName["cpus-per-task"], "1");
    // Every comment is one line: no evil text starts a line of its own.
    std::stringstream lines(*script);
    std::string line;
    while (std::getline(lines, line)) EXPECT_FALSE(line.starts_with("touch PWNED")) << line;
  }
  EXPECT_NE(pieces.find("b\\ntouch PWNED #.mp4"), std::string::npos) << "the label, escaped, in its comment";

  // Run: no evil text runs, every piece gets its text as one argument, the log goes where
  // --output says (the directives were read).
  const farm::Submission s = job.submit();
  EXPECT_EQ(s.submitted.size(), kEvil.size());
  const farm::WaitResult r = job.wait();
  ASSERT_TRUE(r.joined) << (r.failures.empty() ? "" : r.failures.front());
  EXPECT_EQ(readBytes(d / ("out " + kEvil[0])), expectedJoin());
  EXPECT_FALSE(anyPwned(d));
  for (std::size_t i = 0; i < kEvil.size(); ++i) {
    EXPECT_TRUE(fs::exists(job.pieceLog(int(i)))) << job.pieceLog(int(i));
    EXPECT_NE(readBytes(d / "args.log").find("[" + kEvil[i] + "]"), std::string::npos) << kEvil[i];
  }
  EXPECT_TRUE(fs::exists(job.joinLog()));
}

TEST(FarmScripts, AStringNoDirectiveCanHoldIsRefusedInOneLine) {
  const fs::path d = dir("refused");
  for (const auto& [work, partition] : std::vector<std::pair<std::string, std::string>>{
           {(d / "a\nb").string(), ""}, {(d / "back\\slash").string(), ""}, {(d / "w").string(), "p\n#SBATCH --mem=1"}}) {
    try {
      farm::Farm job(evilPlan(d, work), {.partition = partition, .glint = fakeGlint(d).string()},
                     farm::localScheduler(d / "spool"));
      ADD_FAILURE() << "accepted " << work << " / " << partition;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage);
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

TEST(FarmLocal, AFailedPieceStopsTheJoinAndARerunRedoesOnlyIt) {
  const fs::path d = dir("rerun");
  std::ofstream(d / "fail-1") << "";
  const auto plan = [&] {
    farm::Plan p{.tool = "cut", .title = "rerun"};
    for (int i = 0; i < 3; ++i)
      p.pieces.push_back({.label = fmt::format("shard {}/3", i + 1),
                          .command = {"piece", farm::kPieceOutput, std::to_string(i), (d / fmt::format("fail-{}", i)).string()},
                          .extension = ".txt"});
    p.join = {"join", (d / "out.txt").string(), farm::kAllPieceOutputs};
    p.outputs = {d / "out.txt"};
    p.workDir = d / "work";
    return p;
  };
  auto scheduler = std::shared_ptr<farm::Scheduler>(farm::localScheduler(d / "spool"));
  const std::string glint = fakeGlint(d).string();  // once: the program's size and time key the plan
  {
    farm::Farm job(plan(), {.glint = glint}, scheduler);
    EXPECT_EQ(job.submit().submitted.size(), 3u);
    const farm::WaitResult r = job.wait();
    EXPECT_FALSE(r.joined);
    EXPECT_EQ(r.exitCode, 3);
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_NE(r.failures[0].find("piece 1 (shard 2/3): FAILED, exit code 3"), std::string::npos) << r.failures[0];
    EXPECT_NE(readBytes(job.pieceLog(1)).find("failing as asked"), std::string::npos);
    EXPECT_FALSE(fs::exists(d / "out.txt"));
  }
  fs::remove(d / "fail-1");
  farm::Farm again(plan(), {.glint = glint}, scheduler);
  const auto before = fs::last_write_time(again.pieceLog(0));
  const farm::Submission s = again.submit();
  EXPECT_EQ(s.submitted, std::vector<int>{1});
  EXPECT_EQ(s.reused, (std::vector<int>{0, 2}));
  ASSERT_TRUE(again.wait().joined);
  EXPECT_EQ(readBytes(d / "out.txt"), "012");
  EXPECT_EQ(fs::last_write_time(again.pieceLog(0)), before) << "piece 0 ran again";

  // Done: the same plan submits nothing...
  farm::Farm third(plan(), {.glint = glint}, scheduler);
  EXPECT_TRUE(third.submit().alreadyJoined);
  // ...until its output is no longer the file the join wrote (garbage put in its place).
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::ofstream(d / "out.txt") << "garbage";
  farm::Farm fourth(plan(), {.glint = glint}, scheduler);
  const farm::Submission redo = fourth.submit();
  EXPECT_FALSE(redo.alreadyJoined);
  EXPECT_EQ(redo.submitted.size(), 3u);  // the join removed the intermediates: every piece again
  ASSERT_TRUE(fourth.wait().joined);
  EXPECT_EQ(readBytes(d / "out.txt"), "012");
}

TEST(FarmLocal, ACancelledTaskIsNamedAndTheJoinNeverRuns) {
  const fs::path d = dir("cancel");
  farm::Plan plan{.tool = "post", .title = "cancel"};
  plan.pieces.push_back({.label = "frames 0:1", .command = {"slow", farm::kPieceOutput, "0"}, .extension = ".txt"});
  plan.pieces.push_back({.label = "frames 1:2", .command = {"slow", farm::kPieceOutput, "30"}, .extension = ".txt"});
  plan.join = {"join", (d / "out.txt").string(), farm::kAllPieceOutputs};
  plan.outputs = {d / "out.txt"};
  plan.workDir = d / "work";
  auto scheduler = std::shared_ptr<farm::Scheduler>(farm::localScheduler(d / "spool"));
  farm::Farm job(plan, {.glint = fakeGlint(d).string()}, scheduler);
  const farm::Submission s = job.submit();
  // Cancel task 1 once it runs.
  const std::string task = s.arrayJob + "_1";
  for (int i = 0; i < 200 && scheduler->query(task)[task].state != "RUNNING"; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  ASSERT_EQ(scheduler->query(task)[task].state, "RUNNING");
  const auto start = std::chrono::steady_clock::now();
  scheduler->cancel(task);
  const farm::WaitResult r = job.wait();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10)) << "the sleep was not killed";
  EXPECT_FALSE(r.joined);
  ASSERT_EQ(r.failures.size(), 1u);
  EXPECT_NE(r.failures[0].find("piece 1 (frames 1:2): CANCELLED"), std::string::npos) << r.failures[0];
  EXPECT_FALSE(fs::exists(d / "out.txt"));
  const auto joinState = scheduler->query(s.joinJob);
  ASSERT_EQ(joinState.size(), 1u);
  EXPECT_EQ(joinState.begin()->second.state, "CANCELLED");
}

TEST(FarmLocal, TwoIdenticalSubmissionsAtOnceSubmitOnce) {
  const fs::path d = dir("twice");
  farm::Plan plan{.tool = "post", .title = "twice"};
  for (int i = 0; i < 2; ++i)
    plan.pieces.push_back({.label = fmt::format("frames {}", i), .command = {"slow", farm::kPieceOutput, "1"}, .extension = ".txt"});
  plan.join = {"join", (d / "out.txt").string(), farm::kAllPieceOutputs};
  plan.outputs = {d / "out.txt"};
  plan.workDir = d / "work";
  auto scheduler = std::shared_ptr<farm::Scheduler>(farm::localScheduler(d / "spool"));
  const std::string glint = fakeGlint(d).string();
  const auto submitAndWait = [&] {
    farm::Farm job(plan, {.glint = glint}, scheduler);
    const farm::Submission s = job.submit();
    const farm::WaitResult r = job.wait();
    return std::make_pair(s, r);
  };
  auto first = std::async(std::launch::async, submitAndWait);
  auto second = std::async(std::launch::async, submitAndWait);
  const auto [s1, r1] = first.get();
  const auto [s2, r2] = second.get();
  EXPECT_TRUE(r1.joined) << (r1.failures.empty() ? "" : r1.failures[0]);
  EXPECT_TRUE(r2.joined) << (r2.failures.empty() ? "" : r2.failures[0]);
  EXPECT_EQ(s1.submitted.size() + s2.submitted.size(), 2u) << "one of them submitted, the other followed";
  EXPECT_EQ(readBytes(d / "out.txt"), "slowslow");
}

namespace {
/// Slurm's answers that one machine never gives: every task pending for `reason`.
class PendingScheduler final : public farm::Scheduler {
public:
  explicit PendingScheduler(std::string reason) : m_reason(std::move(reason)) {}
  const char* name() const override { return "pending"; }
  std::optional<std::string> unavailable() const override { return std::nullopt; }
  std::string submit(const farm::JobRequest& request) override {
    const std::string id = std::to_string(++m_next);
    m_jobs[id] = request.arrayTasks.empty() ? std::vector<int>{} : request.arrayTasks;
    return id;
  }
  std::map<std::string, farm::TaskRecord> query(const std::string& id) override {
    std::map<std::string, farm::TaskRecord> records;
    const auto it = m_jobs.find(id);
    if (it == m_jobs.end()) return records;
    const bool cancelled = m_cancelled.count(id) > 0;
    const farm::TaskRecord record = cancelled ? farm::TaskRecord{"CANCELLED", "0:0", ""}
                                              : farm::TaskRecord{"PENDING", "0:0", m_reason};
    if (it->second.empty()) records[id] = record;
    for (int t : it->second) records[id + "_" + std::to_string(t)] = record;
    return records;
  }
  void cancel(const std::string& id) override { m_cancelled.insert(id.substr(0, id.find('_'))); }
  std::vector<std::string> nodeProblems() override { return {"node n1 is down: Not responding"}; }
  std::set<std::string> m_cancelled;

private:
  std::string m_reason;
  int m_next = 0;
  std::map<std::string, std::vector<int>> m_jobs;
};
}  // namespace

TEST(FarmLocal, ATaskThatCanNeverStartIsReportedAndCancelled) {
  const fs::path d = dir("never");
  farm::Plan plan = evilPlan(d, d / "work");
  auto pending = std::make_shared<PendingScheduler>("PartitionConfig");
  farm::Farm job(plan, {.cpusPerTask = 64, .glint = fakeGlint(d).string()}, pending);
  const farm::Submission s = job.submit();
  const farm::WaitResult r = job.wait();
  EXPECT_FALSE(r.joined);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_TRUE(r.cannotStart);
  ASSERT_FALSE(r.failures.empty());
  EXPECT_NE(r.failures[0].find("can never start: PartitionConfig"), std::string::npos) << r.failures[0];
  EXPECT_TRUE(pending->m_cancelled.count(s.arrayJob));
  EXPECT_TRUE(pending->m_cancelled.count(s.joinJob));
}

TEST(FarmLocal, WaitNamesWhyTasksAreQueuedAndStopsWhenAsked) {
  const fs::path d = dir("queued");
  auto pending = std::make_shared<PendingScheduler>("ReqNodeNotAvail");
  farm::Farm job(evilPlan(d, d / "work"), {.glint = fakeGlint(d).string()}, pending);
  job.submit();
  std::atomic<bool> stop{false};
  std::string seen;
  const farm::WaitResult r = job.wait(
      [&](int, int, const std::string& line) {
        seen = line;
        stop = true;
      },
      &stop);
  EXPECT_TRUE(r.stopped);
  EXPECT_FALSE(r.joined);
  EXPECT_NE(seen.find("queued (ReqNodeNotAvail (the nodes it may use are down"), std::string::npos) << seen;
  EXPECT_NE(seen.find("node n1 is down: Not responding"), std::string::npos) << seen;
  EXPECT_TRUE(pending->m_cancelled.empty()) << "stopping to follow cancels nothing";
}

TEST(FarmScripts, DirectivesAreReadAsSbatchReadsThem) {
  const auto d = farm::readDirectives("#!/bin/bash\n# a comment\n#SBATCH --output='/a b/%a.log' --mem=1G\n"
                                      "#SBATCH -J \"x # y\" # trailing comment\n\n#SBATCH --time=1\necho hi\n"
                                      "#SBATCH --partition=late\n");
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d[0], (std::pair<std::string, std::string>{"output", "/a b/%a.log"}));
  EXPECT_EQ(d[1], (std::pair<std::string, std::string>{"mem", "1G"}));
  EXPECT_EQ(d[2], (std::pair<std::string, std::string>{"job-name", "x # y"}));
  EXPECT_EQ(d[3], (std::pair<std::string, std::string>{"time", "1"}));  // --partition comes after a command: ignored
}
