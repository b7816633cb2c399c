#include "glint/render/depth_view.h"

#include <string>
#include <vector>

namespace glint::render {

DepthView::DepthView(bool linearize, float nearPlane, float farPlane)
    : m_pass("render/depth_view.frag", linearize ? std::vector<std::string>{"LINEARIZE"} : std::vector<std::string>{}),
      m_sampler(gl::Sampler::create("depth-view")) {
  m_pass.program().set("uNear", nearPlane);
  m_pass.program().set("uFar", farPlane);
  // Sample raw depth values: no comparison, no filtering between texels.
  m_sampler.parameter(GL_TEXTURE_MIN_FILTER, GLint(GL_NEAREST));
  m_sampler.parameter(GL_TEXTURE_MAG_FILTER, GLint(GL_NEAREST));
  m_sampler.parameter(GL_TEXTURE_COMPARE_MODE, GLint(GL_NONE));
}

void DepthView::draw(const gl::Texture& depth) const {
  depth.bind(0);
  m_sampler.bind(0);
  m_pass.draw();
  gl::Sampler::unbind(0);
}

}  // namespace glint::render
