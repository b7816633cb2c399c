// bench rtt — render to texture: copy from the window vs a framebuffer object (the VGP353 lecture:
// copy-to-texture is the "easiest and least efficient form"). Both render the same
// content and build mipmaps; the copy method pays for the extra copy and clears.
#include "glint/bench/bench.h"
#include "glint/gl/render_target.h"
#include "glint/gl/timer.h"
#include "glint/render/rtt/rtt.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

namespace glint::bench {
namespace {

constexpr int kRepeats = 10;

void runRtt(Recorder& recorder) {
  render::rtt::RttContent content;
  const auto draw = [&](ivec2 size) { content.draw(size, 0.5f); };
  for (int size : {256, 512, 1024, 2048}) {
    if (quick() && size > 256) break;
    const std::string group = fmt::format("{0}x{0}", size);
    // A headless context has no window: an offscreen framebuffer of the texture's size stands in.
    gl::RenderTarget window({size, size}, GL_RGBA8, "bench-window");
    render::rtt::CopyToTexture copy(size);
    render::rtt::FramebufferTexture fbo(size);
    const auto copyWork = [&] { copy.render(window.target(), draw); };
    const auto fboWork = [&] { fbo.render(draw); };
    recorder.record({.group = group, .name = "copy gpu", .value = gl::GpuTimer::measureMs(copyWork, kRepeats, 2),
                     .unit = "ms", .note = "draw in window + glCopyTextureSubImage2D + mipmaps"});
    recorder.record({.group = group, .name = "fbo gpu", .value = gl::GpuTimer::measureMs(fboWork, kRepeats, 2),
                     .unit = "ms", .ratioTo = "copy gpu", .note = "draw into the texture + mipmaps"});
    recorder.record({.group = group, .name = "copy wall", .value = wallMs(copyWork, kRepeats), .unit = "ms"});
    recorder.record({.group = group, .name = "fbo wall", .value = wallMs(fboWork, kRepeats), .unit = "ms", .ratioTo = "copy wall"});
  }
}

}  // namespace

/// The "rtt" suite (bench/bench.cpp lists it).
void runRttSuite(Recorder& r) { runRtt(r); }

}  // namespace glint::bench
