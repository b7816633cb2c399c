// The plumbing every offline tool shares (core/tool.h): reports, phases, threads,
// interrupts and quiet mode, checked on a real run without any tool around it.
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/core/tool.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <thread>

using namespace glint;
namespace fs = std::filesystem;

namespace {
fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "tool" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::size_t allowedThreads() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}
}  // namespace

TEST(ToolRun, ReportHasTheToolsFieldsAndTheCommonOnes) {
  const fs::path dir = freshDir("report");
  {
    ToolRun run("demo", {.threads = 1, .json = (dir / "r.json").string()});
    {
      auto timed = run.phase("load");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    run.addSeconds("trace", 0.5);
    run.addSeconds("trace", 0.25);  // phases accumulate
    run.report()["triangles"] = 42;
    run.report()["ratio"] = std::numeric_limits<double>::quiet_NaN();  // no JSON spelling: null
    run.recordWarning("something odd");
    EXPECT_FALSE(fs::exists(dir / "r.json"));  // nothing before finish()
    run.finish();
  }
  std::ifstream in(dir / "r.json");
  const auto r = nlohmann::json::parse(in);
  EXPECT_EQ(r["tool"], "demo");
  EXPECT_FALSE(r["version"].get<std::string>().empty());
  EXPECT_EQ(r["threads"], 1);
  EXPECT_EQ(r["triangles"], 42);
  EXPECT_TRUE(r["ratio"].is_null());
  EXPECT_GE(r["seconds"]["load"].get<double>(), 0.019);
  EXPECT_DOUBLE_EQ(r["seconds"]["trace"].get<double>(), 0.75);
  EXPECT_GE(r["seconds"]["total"].get<double>(), r["seconds"]["load"].get<double>());
  EXPECT_GT(r["peak_memory_mib"].get<double>(), 1.0);
  EXPECT_EQ(r["warnings"], nlohmann::json::array({"something odd"}));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no temporaries
}

TEST(ToolRun, NoReportUnlessAsked) {
  const fs::path dir = freshDir("none");
  const fs::path before = fs::current_path();
  fs::current_path(dir);
  {
    ToolRun run("demo", {});
    run.finish();
  }
  fs::current_path(before);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(ToolRun, ThreadCapHoldsForTheRunOnly) {
  const std::size_t all = allowedThreads();
  {
    ToolRun run("demo", {.threads = 1});
    EXPECT_EQ(allowedThreads(), 1u);
    EXPECT_EQ(run.threads(), 1);
  }
  EXPECT_EQ(allowedThreads(), all);
  try {
    ToolRun run("demo", {.threads = -2});
    FAIL() << "a negative thread count was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
  }
}

TEST(ToolRun, CtrlCSetsTheFlagAndStopsTheTool) {
  ToolRun run("demo", {});
  EXPECT_FALSE(run.interrupted());
  EXPECT_NO_THROW(run.throwIfInterrupted());
  std::raise(SIGINT);  // the run's handler catches it: the test process goes on
  EXPECT_TRUE(run.cancelFlag().load());
  try {
    run.throwIfInterrupted();
    FAIL() << "no error after Ctrl-C";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Interrupted);
    EXPECT_EQ(exitCode(e.kind()), 130);
  }
}

TEST(ToolRun, ANewRunStartsUninterruptedAndSigtermCountsToo) {
  {
    ToolRun run("demo", {});
    std::raise(SIGTERM);
    EXPECT_TRUE(run.interrupted());
  }
  ToolRun next("demo", {});
  EXPECT_FALSE(next.interrupted());
}

TEST(ToolRun, QuietSilencesInfoForTheRunOnly) {
  log::setLevel(log::Level::Info);
  {
    ToolRun run("demo", {.quiet = true});
    EXPECT_EQ(log::level(), log::Level::Warn);
    EXPECT_FALSE(run.showProgress());
  }
  EXPECT_EQ(log::level(), log::Level::Info);
  ToolRun loud("demo", {});
  EXPECT_TRUE(loud.showProgress());
}
