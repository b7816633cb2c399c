#include "glint/render/water/field_view.h"

#include "glint/render/state.h"

#include <algorithm>

namespace glint::render::water {

FieldView::FieldView() : m_pass("water/field_view.frag") {}

void FieldView::draw(const gl::Texture& field, FieldKind kind, ivec2 viewport, float gain) const {
  PipelineState{.depthTest = true}.apply();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, vec4(0.05f, 0.06f, 0.08f, 1.0f));
  const int side = std::min(viewport.x, viewport.y);
  glViewport((viewport.x - side) / 2, (viewport.y - side) / 2, side, side);
  field.bind(0);
  gl::Sampler::unbind(0);
  m_pass.program().set("uField", 0);
  m_pass.program().set("uHeight", kind == FieldKind::Height);
  m_pass.program().set("uGain", gain);
  m_pass.draw();
  glViewport(0, 0, viewport.x, viewport.y);
}

}  // namespace glint::render::water
