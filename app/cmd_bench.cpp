// glint bench — run benchmark suites; table on stdout, JSON to a file.
#include "common.h"

#include "glint/bench/bench.h"
#include "glint/core/json.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/scenes/runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace glint::app {

namespace {
struct BenchArgs {
  std::vector<std::string> suites;
  std::string json;
};
}  // namespace

Command benchCommand(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<BenchArgs>();
  auto* cmd = app.add_subcommand("bench", "Run benchmarks: each reports ratios against a peer measured in the same run");
  std::string names;
  for (const auto& s : bench::Suites::builtin().all()) names += fmt::format("\n  {:<10} {}", s.name, s.description);
  cmd->footer("Suites:" + (names.empty() ? std::string("\n  (none yet)") : names));
  cmd->add_option("suites", args->suites, "Suites to run (default: all)");
  cmd->add_option("--json", args->json, "Also write the results as JSON to this file");
  return Command{.run = [args, &global] {
    const auto& all = bench::Suites::builtin().all();
    std::vector<const bench::Suite*> chosen;
    for (const auto& name : args->suites) {
      auto it = std::find_if(all.begin(), all.end(), [&](const bench::Suite& s) { return s.name == name; });
      if (it == all.end()) fail(ErrorKind::Usage, "unknown benchmark suite '{}' (`glint bench --help` lists them)", name);
      chosen.push_back(&*it);
    }
    if (args->suites.empty())
      for (const auto& s : all) chosen.push_back(&s);
    if (chosen.empty()) fail(ErrorKind::Usage, "no benchmark suites are built in yet");
    if (!args->json.empty()) checkWritable(args->json);
    scenes::ContextPool contexts(global.glDebug);
    contexts.use(gl::Profile::Core);
    nlohmann::ordered_json json = nlohmann::ordered_json::array();
    for (const auto* suite : chosen) {
      log::info("bench {}: {}", suite->name, suite->description);
      bench::Recorder recorder;
      suite->run(recorder);
      fmt::print("{}\n", bench::formatTable(suite->name, recorder));
      json.push_back(bench::toJson(suite->name, recorder));
    }
    if (!args->json.empty()) writeTextAtomically(args->json, jsonText(json));
    return 0;
  }};
}

}  // namespace glint::app
