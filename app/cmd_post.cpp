// glint post IN -o OUT -e EFFECT... — WWDC 2003 session 212's post-processing on an image, every frame of
// a video, a camera or an FFmpeg lavfi source. Thin: the options, the job, its run and its
// report are the library's (post/job.h); the GPU backend is scenes/post_gpu.h's.
#include "common.h"

#include "glint/post/job.h"
#include "glint/scenes/post_gpu.h"

#include <fmt/format.h>

#include <memory>

namespace glint::app {

Command postCommand(CLI::App& app, const GlobalOptions& global) {
  struct Args {
    post::PostArgs post;
    ToolSettings tool;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("post", "Post-process an image, a video, a camera or a lavfi source on the GPU "
                                         "(sepia, Sobel, Kuwahara, FFT filters)");
  cmd->footer(post::helpFooter());
  post::addOptions(*cmd, a->post);
  addToolOptions(*cmd, a->tool, "input, output, effects, frames read/written/dropped, fps, audio, rotation, partial");
  return Command{.run = [a, &global] {
                   if (a->post.listEffects) {
                     fmt::print("{}", post::effectHelp());
                     return 0;
                   }
                   ToolRun run("post", a->tool);
                   const post::PostJob job = post::makeJob(a->post, global.glDebug);
                   const auto gpu = scenes::postGpuBackend();
                   return post::finishJob(post::runJob(job, run, gpu.get()), run);
                 },
                 .readsImages = false};  // images load OpenImageIO themselves (runImage, runStill)
}

}  // namespace glint::app
