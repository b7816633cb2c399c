#include "glint/render/bump/light_marker.h"

#include "glint/render/state.h"

namespace glint::render::bump {

LightMarker::LightMarker()
    : m_program(gl::Program::fromFiles({"bump/light_marker.vert", "bump/light_marker.frag"})),
      m_vao(gl::VertexArray::create("light-marker")) {}

void LightMarker::draw(const Camera& camera, vec3 position, vec3 color, float pixels) const {
  m_program.set("uViewProjection", camera.viewProjection());
  m_program.set("uPosition", position);
  m_program.set("uColor", color);
  m_program.set("uPixels", pixels);
  // Soft edge blended over the picture; depth-tested so the polygon can hide the light.
  PipelineState{.depthTest = true, .depthWrite = false,
                .blend = {.enabled = true, .src = GL_SRC_ALPHA, .dst = GL_ONE_MINUS_SRC_ALPHA}}.apply();
  glEnable(GL_PROGRAM_POINT_SIZE);
  m_program.use();
  m_vao.bind();
  glDrawArrays(GL_POINTS, 0, 1);
  glBindVertexArray(0);
  glDisable(GL_PROGRAM_POINT_SIZE);
  PipelineState{.depthTest = true}.apply();
}

}  // namespace glint::render::bump
