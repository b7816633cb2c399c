#pragma once
// glint/post/gpu_backend.h — the interface between `glint post`'s job (post/job.h, GL-free)
// and a GPU: what the job asks of one and hands to it. glint's implementation is
// scenes/post_gpu.h's postGpuBackend() (render/post's Chain and FrameStream on a headless
// context); a program without one runs every effect on the CPU (post/cpu.h).

#include "glint/core/math.h"
#include "glint/image/image.h"
#include "glint/post/effects.h"
#include "glint/video/transcode.h"

#include <memory>
#include <string>
#include <vector>

namespace glint::post {

/// The GPU side of a job: the job asks it about devices and hands it the frames, and stays
/// free of GL itself.
class GpuBackend {
public:
  virtual ~GpuBackend() = default;
  /// Whether every device EGL lists is a software rasterizer (known without a context).
  virtual bool onlySoftwareDevices() = 0;
  /// Makes the headless context the work runs in (once; kept until the backend is
  /// destroyed) and returns the GL renderer's name. Error(NoGpu) without OpenGL 4.5.
  virtual std::string start(bool debug) = 0;
  /// The largest texture side of the context.
  virtual int maxTextureSize() = 0;
  /// `frame` (U8 or F32 RGBA) through the effects; `described` gets the chain's description.
  virtual Image runImage(const std::vector<Effect>& effects, const Image& frame, std::string& described) = 0;
  /// A video's frames (U8 RGBA) through the effects, a few in flight, as the transcoder's
  /// middle stage; `described` gets the chain's description.
  virtual std::unique_ptr<video::FrameProcessor> videoProcessor(ivec2 size, const std::vector<Effect>& effects,
                                                                std::string& described) = 0;
};

}  // namespace glint::post
