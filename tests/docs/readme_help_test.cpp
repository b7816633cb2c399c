// Help that tells (issue 34): every option README's command table names for a command is
// in that command's own --help, so a user who reads one finds it in the other. The table is
// read from README.md as a user reads it: each row's first cell holds the command lines
// (`glint bake LOW HIGH -o OUT [--size WxH] ...`); each option there must appear in the help
// of the (sub)command that line names.
#include "support/cli.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using glint::testing::runGlint;

namespace {

/// The first cells of README's "The `glint` command" table.
std::vector<std::string> commandCells() {
  std::ifstream in(fs::path(GLINT_SOURCE_DIR) / "README.md");
  std::vector<std::string> cells;
  std::string line;
  bool inTable = false;
  while (std::getline(in, line)) {
    if (line.starts_with("## The `glint` command")) inTable = true;
    else if (inTable && line.starts_with("## ")) break;
    if (!inTable || !line.starts_with("| `")) continue;
    // The first cell ends at the first " | " outside backticks.
    bool code = false;
    std::size_t end = std::string::npos;
    for (std::size_t i = 2; i < line.size(); ++i) {
      if (line[i] == '`') code = !code;
      if (!code && line.compare(i, 3, " | ") == 0) {
        end = i;
        break;
      }
    }
    cells.push_back(line.substr(2, end == std::string::npos ? std::string::npos : end - 2));
  }
  return cells;
}

/// Each `glint ...` code span of a cell: the subcommand path ("bake", "farm post") and the
/// options the span names.
struct Usage {
  std::vector<std::string> command;
  /// The options, each a group of alternatives (`--shards N|--chunks N`: either).
  std::vector<std::vector<std::string>> options;
};

/// The options a code span names, alternatives (written `a|b`) grouped.
std::vector<std::vector<std::string>> optionsOf(const std::string& text) {
  static const std::regex option("(^|[\\s\\[|(])(--[a-z][a-z0-9-]*|-[a-zA-Z])\\b");
  std::vector<std::vector<std::string>> groups;
  for (std::sregex_iterator o(text.begin(), text.end(), option), e; o != e; ++o) {
    const std::string name = (*o)[2];
    std::size_t before = std::size_t(o->position(2));
    while (before > 0 && text[before - 1] == ' ') --before;
    const bool alternative = before > 0 && text[before - 1] == '|' && !groups.empty();
    if (alternative) groups.back().push_back(name);
    else groups.push_back({name});
  }
  return groups;
}

std::vector<Usage> usagesOf(const std::string& cell) {
  std::vector<Usage> usages;
  static const std::regex span("`(glint [^`]*)`");
  for (std::sregex_iterator it(cell.begin(), cell.end(), span), end; it != end; ++it) {
    std::string text = (*it)[1];
    for (char& c : text)
      if (c == '\\') c = ' ';  // README escapes the table's | as \|
    std::stringstream words(text);
    std::string word;
    words >> word;  // glint
    Usage u;
    words >> word;
    u.command.push_back(word);
    // farm's and raster's subcommands: `glint farm cut|post|render`, `glint raster lecture|mesh`.
    if (word == "farm") {
      std::string next;
      words >> next;
      for (std::size_t at = 0; at <= next.size();) {
        const std::size_t bar = next.find('|', at);
        const std::string sub = next.substr(at, bar == std::string::npos ? std::string::npos : bar - at);
        if (!sub.empty() && sub != "bake" && sub.find('.') == std::string::npos) {
          Usage f{{"farm", sub}, {}};
          usages.push_back(f);
        } else if (sub == "bake") {
          usages.push_back({{"farm", "bake"}, {}});
        }
        if (bar == std::string::npos) break;
        at = bar + 1;
      }
      for (auto& f : usages)
        if (f.command.size() == 2 && f.options.empty()) f.options = optionsOf(text);
      continue;
    }
    u.options = optionsOf(text);
    usages.push_back(u);
  }
  return usages;
}

}  // namespace

TEST(ReadmeHelp, EveryOptionTheCommandTableNamesIsInThatCommandsHelp) {
  const auto cells = commandCells();
  ASSERT_GE(cells.size(), 10u) << "README's command table was not found";
  std::map<std::string, std::string> helps;
  int checked = 0;
  for (const std::string& cell : cells) {
    for (const Usage& u : usagesOf(cell)) {
      std::string path;
      for (const auto& c : u.command) path += (path.empty() ? "" : " ") + c;
      if (!helps.count(path)) {
        const auto r = runGlint(path + " --help");
        ASSERT_EQ(r.status, 0) << "glint " << path << " --help: " << r.output;
        helps[path] = r.output;
      }
      for (const auto& group : u.options) {
        bool found = false;
        for (const std::string& option : group) found = found || helps[path].find(option) != std::string::npos;
        EXPECT_TRUE(found) << "README names " << group.front() << (group.size() > 1 ? " (or an alternative)" : "")
                           << " for `glint " << path << "`, which --help does not mention";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 40) << "too few options found: the table's format changed?";
}

TEST(ReadmeHelp, BakeHelpSaysUdimFirst) {
  const auto r = runGlint("bake --help");
  ASSERT_EQ(r.status, 0);
  const std::size_t udim = r.output.find("UDIM");
  ASSERT_NE(udim, std::string::npos) << r.output;
  EXPECT_LT(udim, r.output.find("Examples:")) << "UDIM comes before the examples";
}
