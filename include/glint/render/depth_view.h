#pragma once
// glint/render/depth_view.h — draws a depth texture as a gray image.
//
// White = 1.0 (far), black = 0.0 (near), the lecture's convention. With
// `linearize`, perspective depth is first mapped back to eye distance between
// near and far, which spreads the values out for perspective scenes.

#include "glint/gl/objects.h"
#include "glint/render/gpu_mesh.h"

namespace glint::render {

class DepthView {
public:
  DepthView() = default;
  explicit DepthView(bool linearize, float nearPlane = 0.1f, float farPlane = 100.0f);
  /// Draws `depth` (a depth or depth-stencil texture) over the current viewport.
  void draw(const gl::Texture& depth) const;

private:
  FullscreenPass m_pass;
  gl::Sampler m_sampler;
};

}  // namespace glint::render
