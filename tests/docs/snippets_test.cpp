// Every code example a reader meets in a public header or README.md is compiled into this
// test (extract_snippets writes them into it, so an example that does not compile breaks
// the build), and the ones fenced ```cpp run are run. This test checks the extraction
// itself against an independent scan of the files, so an example cannot silently drop out.
#include "snippets.h"

#include "glint/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// "FILE:LINE" of every line whose text, after an optional comment marker, is ```cpp
/// or ```cpp run, in the public headers and README.md.
std::set<std::string> fencesInSources() {
  const fs::path root = GLINT_SOURCE_DIR;
  std::vector<fs::path> files{root / "README.md"};
  for (const auto& entry : fs::recursive_directory_iterator(root / "include" / "glint"))
    if (entry.path().extension() == ".h") files.push_back(entry.path());
  const std::regex fence(R"(^\s*(//[/!]?\s?)?```cpp( run)?\s*$)");
  std::set<std::string> found;
  for (const fs::path& file : files) {
    std::ifstream in(file);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number)
      if (std::regex_match(line, fence)) found.insert(fs::relative(file, root).string() + ":" + std::to_string(number));
  }
  return found;
}

}  // namespace

TEST(DocsSnippets, EveryExampleInTheHeadersAndReadmeIsCompiled) {
  std::set<std::string> compiled;
  for (const auto& s : glint::docs::snippets()) compiled.insert(s.where);
  const std::set<std::string> expected = fencesInSources();
  EXPECT_FALSE(expected.empty());
  std::vector<std::string> missing, extra;
  std::ranges::set_difference(expected, compiled, std::back_inserter(missing));
  std::ranges::set_difference(compiled, expected, std::back_inserter(extra));
  EXPECT_TRUE(missing.empty()) << "examples not compiled (the build's file list misses them): "
                               << ::testing::PrintToString(missing);
  EXPECT_TRUE(extra.empty()) << "compiled examples no longer in the sources: " << ::testing::PrintToString(extra);
}

TEST(DocsSnippets, RunnableExamplesRun) {
  const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "docs-snippets";
  fs::create_directories(dir);
  const fs::path previous = fs::current_path();
  fs::current_path(dir);  // examples write their outputs here
  int ran = 0;
  for (const auto& s : glint::docs::snippets()) {
    if (!s.run) continue;
    SCOPED_TRACE(s.where);
    try {
      s.body();
    } catch (const glint::Error& e) {
      ADD_FAILURE() << s.where << ": " << e.what();
    }
    ++ran;
  }
  fs::current_path(previous);
  EXPECT_GT(ran, 0) << "no example is fenced ```cpp run";
}
