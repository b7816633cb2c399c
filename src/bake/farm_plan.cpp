// `glint farm bake` (bake/job.h): a batch file's bakes as a farm's pieces, one task per bake
// (`glint bake --batch FILE --job i`), with every check a bake makes first; no join.
#include "glint/bake/job.h"

#include "glint/core/file.h"
#include "job_internal.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace glint::bake {

farm::Plan farmPlan(const BatchRequest& request, const farm::Split& split) {
  const std::vector<BatchJob> jobs = loadBatch(request.file, request.overrides);  // every check a bake makes
  double most = 0.0;
  for (const BatchJob& b : jobs) most = std::max(most, estimateMemoryMiB(b.job));
  farm::Plan plan{.tool = "bake"};
  plan.memoryMiB = farm::taskMemoryMiB(split, most);
  const std::string file = farm::absolutePath(request.file);
  plan.title = fmt::format("{} ({} bake{})", fs::path(file).filename().string(), jobs.size(), jobs.size() == 1 ? "" : "s");
  plan.workDir = split.workDir.empty() ? fs::path(file).parent_path() : split.workDir;
  // The options given with the farm command, for every job, as `glint bake` takes them.
  std::vector<std::string> overrides;
  {
    CLI::App prototype{"glint bake", "bake"};
    BakeJob unused;
    addOptions(prototype, unused, Meshes::Required);
    overrides = argumentsFor(prototype, {&request.overrides}, fs::path(file).parent_path());
  }
  const std::vector<std::string> limits = farm::pieceSettings(request.tool, split, plan.memoryMiB);
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const BatchJob& b = jobs[i];
    farm::Piece piece{.label = b.where.substr(b.where.find(" job ") + 1),
                      .command = {"bake", "--batch", file, "--job", std::to_string(i)}};
    piece.command.insert(piece.command.end(), overrides.begin(), overrides.end());
    piece.command.insert(piece.command.end(), limits.begin(), limits.end());
    piece.inputs.push_back(file);
    for (const FileUse& in : inputFiles(b.job))
      if (!in.path.empty()) piece.inputs.push_back(farm::absolutePath(in.path.string()));
    for (const FileUse& out : outputFiles(b.job)) {
      if (out.path.empty() || out.path == "-") continue;
      piece.outputs.push_back(farm::absolutePath(out.path.string()));
      plan.outputs.push_back(farm::absolutePath(out.path.string()));
    }
    plan.pieces.push_back(std::move(piece));
  }
  return plan;
}

}  // namespace glint::bake
