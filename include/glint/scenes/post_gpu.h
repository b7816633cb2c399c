#pragma once
// glint/scenes/post_gpu.h — `glint post`'s GPU backend: the GL side a post job
// (post/job.h, GL-free) hands its frames to through post::GpuBackend (post/gpu_backend.h).
// It makes its headless context when the job first needs the GPU, runs images through
// render/post's Chain (U8 or F32 frames) and videos through its FrameStream (pixel buffer
// objects, a few frames in flight). It joins a GL technique to a tool's video pipeline, so
// it sits with the other compositions in scenes/, above both: render/ links neither the
// video layer nor the farm.
//
/// ```cpp
/// #include <glint/post/job.h>
/// glint::post::PostJob job;
/// job.input = "photo.png";
/// job.output = "npr.png";
/// const std::vector<std::string> specs = {"posterize"};
/// job.effects = glint::post::parseEffects(specs);
/// glint::ToolRun run("post", {});
/// const auto gpu = glint::scenes::postGpuBackend();
/// const glint::post::PostStats stats = glint::post::runJob(job, run, gpu.get());
/// ```
#include "glint/post/gpu_backend.h"

#include <memory>

namespace glint::scenes {

/// A backend whose context is made on first use (GpuBackend::start).
std::unique_ptr<glint::post::GpuBackend> postGpuBackend();

}  // namespace glint::scenes
