// glint bake LOW HIGH -o OUT — the normal mapper: high-poly detail into a texture for the
// low poly; glint bake --batch JOBS.json [--job I | --list] — many bakes from one file.
// Thin: the options, the checks, the bake and the batches are the library's (bake/job.h).
#include "common.h"

#include "glint/core/json.h"

#include "glint/bake/job.h"
#include "glint/core/error.h"
#include "glint/scenes/bake_gpu.h"

#include <memory>

namespace glint::app {

Command bakeCommand(CLI::App& app, const GlobalOptions& global) {
  auto a = std::make_shared<bake::BakeJob>();
  auto request = std::make_shared<bake::BatchRequest>();
  auto* cmd = app.add_subcommand("bake", "Bake a high-poly mesh's detail into a normal map (and AO, height, curvature, "
                                         "... maps; UDIM tiles) for a low-poly mesh");
  cmd->footer(bake::helpFooter());
  bake::addOptions(*cmd, *a, bake::Meshes::Optional);  // LOW HIGH -o are checked in run: --batch replaces them
  CLI::Option* batch = cmd->add_option("--batch", request->file, "Run the bakes a JSON file lists (instead of LOW "
                                       "HIGH -o; see the footer)")->type_name("FILE");
  CLI::Option* job = cmd->add_option("--job", request->job, "With --batch: run only this job (0-based)")
                         ->type_name("I")->needs(batch);
  CLI::Option* list = cmd->add_flag("--list", request->list, "With --batch: print the jobs as glint bake command "
                                    "lines, run nothing")->needs(batch);
  auto describe = std::make_shared<bool>(false);
  cmd->add_flag("--describe", *describe, "Print the options and maps as JSON (names, help, defaults, the sample counts "
                "--samples takes): what a front end such as the Blender add-on builds its panel from; bake nothing");
  return Command{.run = [a, request, cmd, batch, job, list, describe, &global] {
                   if (*describe) {
                     std::fputs(jsonText(bake::describe()).c_str(), stdout);
                     return 0;
                   }
                   if (!request->file.empty() || batch->count() > 0) {
                     if (cmd->get_option("low")->count() > 0 || cmd->get_option("high")->count() > 0)
                       fail(ErrorKind::Usage, "bake: --batch takes the meshes from {}: give no LOW HIGH with it", request->file);
                     if (job->count() > 0 && request->job < 0)
                       fail(ErrorKind::Usage, "bake: --job {} is out of range: jobs are numbered from 0", request->job);
                     // The options given with --batch apply to every job (--json is the batch's own report).
                     request->overrides = bake::givenOptions(*cmd, {batch, job, list, cmd->get_option("--json")});
                     request->tool = a->tool;
                     const auto gpu = scenes::bakeGpuBackend();  // (its context only when a job takes the GPU)
                     request->gpu = gpu.get();
                     request->glDebug = global.glDebug;
                     return bake::runBatch(*request);
                   }
                   for (const char* name : {"low", "high", "--output"})
                     if (cmd->get_option(name)->count() == 0) fail(ErrorKind::Usage, "{} is required (see --help)", name);
                   ToolRun run("bake", a->tool);
                   a->glDebug = global.glDebug;
                   const auto gpu = scenes::bakeGpuBackend();
                   bake::runJob(*a, run, nullptr, gpu.get());
                   run.finish();
                   return 0;
                 },
                 // The OpenImageIO module is started by the command itself, only when it reads an
                 // image or writes another format than PNG (libspng): its 0.3 s of dynamic linking
                 // would take the second core from the mesh parser.
                 .readsImages = false};
}

}  // namespace glint::app
