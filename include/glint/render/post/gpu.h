#pragma once
// glint/render/post/gpu.h — `glint post`'s GPU backend: the GL side a post job
// (post/job.h) hands its frames to. It makes its headless context when the job first needs
// the GPU, runs images through a Chain (U8 or F32 frames) and videos through a FrameStream
// (pixel buffer objects, a few frames in flight).
//
/// ```cpp
/// #include <glint/post/job.h>
/// glint::post::PostJob job;
/// job.input = "photo.png";
/// job.output = "npr.png";
/// const std::vector<std::string> specs = {"posterize"};
/// job.effects = glint::post::parseEffects(specs);
/// glint::ToolRun run("post", {});
/// const auto gpu = glint::render::post::gpuBackend();
/// const glint::post::PostStats stats = glint::post::runJob(job, run, gpu.get());
/// ```
#include "glint/post/job.h"

#include <memory>

namespace glint::render::post {

/// A new GPU backend; its context is made by the job (GpuBackend::start) and lives as long
/// as the backend.
std::unique_ptr<glint::post::GpuBackend> gpuBackend();

}  // namespace glint::render::post
