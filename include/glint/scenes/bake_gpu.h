#pragma once
// glint/scenes/bake_gpu.h — `glint bake --device gpu`'s backend: the GL side the baker
// (bake/, GL-free) hands its rays to through bake::GpuBackend (bake/gpu_backend.h). It
// makes its headless context when a bake first needs the GPU, builds the high poly's BVH
// (raytrace/bvh.h) and traces through scenes/bake_tracer.h's compute shaders. It joins a GL
// technique to a tool, so it sits with the other compositions in scenes/, above both.
//
/// ```cpp
/// #include <glint/bake/baker.h>
/// glint::bake::BakeOptions options;
/// const auto gpu = glint::scenes::bakeGpuBackend();
/// options.gpu = gpu.get();
/// options.device = glint::bake::Device::Gpu;
/// // glint::bake::bake(low, high, options): every ray on the GPU
/// ```
#include "glint/bake/gpu_backend.h"

#include <memory>

namespace glint::scenes {

/// A backend whose context is made on first use (GpuBackend::start).
std::unique_ptr<glint::bake::GpuBackend> bakeGpuBackend();

}  // namespace glint::scenes
