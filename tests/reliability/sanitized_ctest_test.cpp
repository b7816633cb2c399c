// scripts/sanitized-ctest, which runs make sanitize's tests: a test that fails once and
// passes alone is a flake (the step passes), a test that fails twice fails the step, and
// the step ends with a digest naming each failure and the lines that say what happened.
// Checked on a small ctest project written here, as CI would run the script.
#include "support/cli.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace glint::testing;

namespace {

const std::string kScript = std::string(GLINT_SOURCE_DIR) + "/scripts/sanitized-ctest";

// A ctest project: Flaky fails on its first run only (it leaves a marker), Broken always
// fails with a gtest-like report (only when withBroken), Fine passes.
std::filesystem::path writeProject(const std::string& name, bool withBroken) {
  const auto dir = freshDir("sanitized-ctest", name);
  std::ofstream cmake(dir / "CMakeLists.txt");
  cmake << "cmake_minimum_required(VERSION 3.16)\nproject(p NONE)\nenable_testing()\n"
        << "add_test(NAME Suite.Flaky COMMAND sh -c \"if [ -f flaked ]; then exit 0; fi; touch flaked; "
           "echo 'flaky.cpp:3: Failure'; echo '==7==ERROR: LeakSanitizer: detected memory leaks'; exit 1\")\n"
        << "add_test(NAME Suite.Fine COMMAND true)\n";
  if (withBroken)
    cmake << "add_test(NAME Suite.Broken COMMAND sh -c \"echo 'broken.cpp:9: Failure'; echo '  Which is: 1'; "
             "echo 'noise that says nothing'; exit 1\")\n";
  cmake.close();
  const auto configured = runShell(std::string(GLINT_CMAKE) + " -S " + shellQuote(dir) + " -B " + shellQuote(dir / "build"));
  EXPECT_EQ(configured.status, 0) << configured.output;
  return dir / "build";
}

std::string afterDigest(const std::string& output) {
  const auto at = output.rfind("sanitized-ctest: digest");
  return at == std::string::npos ? "" : output.substr(at);
}

}  // namespace

TEST(SanitizedCtest, AFailureThatPassesAloneIsAFlakeAndTheStepPasses) {
  const auto build = writeProject("flake", false);
  const auto r = runShell(kScript + " " + shellQuote(build) + " -j2");
  EXPECT_EQ(r.status, 0) << r.output;
  const std::string digest = afterDigest(r.output);
  EXPECT_NE(digest.find("flaked (passed alone): Suite.Flaky"), std::string::npos) << r.output;
  EXPECT_NE(digest.find("flaky.cpp:3: Failure"), std::string::npos) << "the first run's report is kept";
  EXPECT_NE(digest.find("ERROR: LeakSanitizer"), std::string::npos);
  EXPECT_EQ(digest.find("Suite.Fine"), std::string::npos) << "passing tests are not in the digest";
}

TEST(SanitizedCtest, AFailureThatRepeatsFailsTheStepAndTheDigestEndsTheOutput) {
  const auto build = writeProject("repeat", true);
  const auto r = runShell(kScript + " " + shellQuote(build) + " -j2");
  EXPECT_EQ(r.status, 1) << r.output;
  const std::string digest = afterDigest(r.output);
  EXPECT_NE(digest.find("FAILED TWICE: Suite.Broken"), std::string::npos) << r.output;
  EXPECT_NE(digest.find("broken.cpp:9: Failure"), std::string::npos);
  EXPECT_NE(digest.find("Which is: 1"), std::string::npos);
  EXPECT_EQ(digest.find("noise that says nothing"), std::string::npos) << "only the lines that say what happened";
  EXPECT_NE(digest.find("flaked (passed alone): Suite.Flaky"), std::string::npos);
  // The digest is the last thing printed: a CI log's tail names the causes.
  EXPECT_EQ(r.output.substr(r.output.size() - digest.size()), digest);
}

TEST(SanitizedCtest, AllPassingIsQuietAboutRetries) {
  const auto build = writeProject("pass", false);
  std::ofstream(build / "flaked").put('\n');  // Flaky has already "failed once": it passes now
  const auto r = runShell(kScript + " " + shellQuote(build));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("sanitized-ctest:"), std::string::npos) << r.output;
}
