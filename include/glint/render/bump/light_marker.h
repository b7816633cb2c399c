#pragma once
// glint/render/bump/light_marker.h — a small glowing disc where a point light is, so a
// picture shows what lights it. Drawn as one point sprite with depth test; the same code on
// core and compatibility contexts (the classic DOT3 scene uses it too).

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/core/camera.h"

namespace glint::render::bump {

class LightMarker {
public:
  LightMarker();
  /// Draws a disc of `pixels` diameter at world position `position`, tinted `color`.
  void draw(const Camera& camera, vec3 position, vec3 color = vec3(1.0f, 0.95f, 0.7f), float pixels = 14.0f) const;

private:
  gl::Program m_program;
  gl::VertexArray m_vao;  // empty: the one vertex comes from a uniform
};

}  // namespace glint::render::bump
