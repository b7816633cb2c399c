#pragma once
// What the Pipe Dream renderer's passes (renderer.cpp) and its debug views (debug_views.cpp)
// share: not part of the public header.
#include "glint/core/math.h"

#include <epoxy/gl.h>

namespace glint::render::pipedream::detail {

// While a step draws into the colour buffer (sRGB): blending in linear light, writes
// encoded. Off again after, for whatever the application draws next.
struct FramebufferSrgb {
  FramebufferSrgb() { glEnable(GL_FRAMEBUFFER_SRGB); }
  ~FramebufferSrgb() { glDisable(GL_FRAMEBUFFER_SRGB); }
  FramebufferSrgb(const FramebufferSrgb&) = delete;
  FramebufferSrgb& operator=(const FramebufferSrgb&) = delete;
};

// The debug views' linear colours (the colour buffer encodes them).
inline const vec4 kVolumeWire{0.20f, 0.38f, 1.0f, 1.0f};
inline const vec4 kEdgeColor{0.015f, 0.015f, 0.02f, 1.0f};

}  // namespace glint::render::pipedream::detail
