// glint cut SCENE... -o OUT --light x,y,z — the shadow cutter: static shadows cut into the
// geometry. Thin: the options and the job are the library's (cut/job.h).
#include "common.h"

#include "glint/cut/job.h"

#include <memory>

namespace glint::app {

Command cutCommand(CLI::App& app, const GlobalOptions&) {
  struct Args {
    cut::CutJob job;
    ToolSettings tool;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("cut", "Cut static shadows into geometry: pieces tagged with the lights that reach them");
  cmd->footer(cut::helpFooter());
  cut::addOptions(*cmd, a->job);
  addToolOptions(*cmd, a->tool, "triangles in and polygons out, counts and areas per light, clipped pairs, predicates");
  return Command{.run = [a] {
                   ToolRun run("cut", a->tool);
                   cut::runJob(a->job, run);
                   run.finish();
                   return 0;
                 },
                 .readsImages = false};
}

}  // namespace glint::app
