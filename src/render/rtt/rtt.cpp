#include "glint/render/rtt/rtt.h"

#include "glint/core/error.h"
#include "glint/core/camera.h"
#include "glint/render/state.h"

#include <string>

namespace glint::render::rtt {
namespace {
gl::Texture makeTexture(int size, std::string_view label) {
  if (size <= 0) fail(ErrorKind::Usage, "render-to-texture size must be positive, got {}", size);
  gl::Texture texture(GL_TEXTURE_2D, label);
  texture.storage(GL_RGBA8, size, size, 1, 0);
  texture.filtering(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
  return texture;
}

void clearBound(vec4 clear) {
  PipelineState{}.apply();  // the default state for what is drawn next
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, clear);
}
}  // namespace

CopyToTexture::CopyToTexture(int size, std::string_view label) : m_size(size), m_texture(makeTexture(size, label)) {}

void CopyToTexture::render(const gl::Target& window, const DrawFn& draw, vec4 clear) {
  if (window.size.x < m_size || window.size.y < m_size) {
    fail(ErrorKind::Usage,
         "copy-to-texture needs a window at least {0}x{0} for a {0}x{0} texture, but it is {1}x{2} (use a smaller "
         "texture or a framebuffer object)",
         m_size, window.size.x, window.size.y);
  }
  window.framebuffer->bind();
  glViewport(0, 0, m_size, m_size);
  // Only the texture's corner of the window is cleared and drawn.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, m_size, m_size);
  clearBound(clear);
  glDisable(GL_SCISSOR_TEST);
  draw({m_size, m_size});
  window.framebuffer->bind(GL_READ_FRAMEBUFFER);
  if (!window.framebuffer->isDefault()) glNamedFramebufferReadBuffer(window.framebuffer->id(), GL_COLOR_ATTACHMENT0);
  m_texture.copyFromReadFramebuffer(0, 0, m_size, m_size);
  m_texture.generateMipmap();
  window.bind();
}

FramebufferTexture::FramebufferTexture(int size, std::string_view label)
    : m_size(size),
      m_texture(makeTexture(size, label)),
      m_depthStencil(GL_DEPTH24_STENCIL8, size, size, 0, std::string(label) + "-depth-stencil"),
      m_framebuffer(gl::Framebuffer::create(std::string(label) + "-fbo")) {
  m_framebuffer.attach(GL_COLOR_ATTACHMENT0, m_texture, 0);
  m_framebuffer.attach(GL_DEPTH_STENCIL_ATTACHMENT, m_depthStencil);
  m_framebuffer.checkComplete();
}

void FramebufferTexture::render(const DrawFn& draw, vec4 clear) {
  const SavedTarget saved;  // the caller's framebuffer and viewport, put back on return
  m_framebuffer.bind();
  glViewport(0, 0, m_size, m_size);
  clearBound(clear);
  draw({m_size, m_size});
  m_texture.generateMipmap();
}

RttContent::RttContent()
    : m_program(gl::Program::fromFiles({"rtt/content.vert", "rtt/content.frag"})),
      m_torus(makeTorus(0.8f, 0.3f, 64, 32), {}, "rtt-torus"),
      m_cube(makeCube(0.7f), {}, "rtt-cube"),
      m_floor(makePlane(8.0f), {}, "rtt-floor") {}

void RttContent::draw(ivec2 size, float time) const {
  const Camera camera = Camera::orbit(vec3(0.0f, -0.2f, 0.0f), 3.6f, 0.4f, 0.45f, 45.0f, float(size.x) / float(size.y));
  PipelineState{.depthTest = true, .cull = true}.apply();
  m_program.use();
  m_program.set("uViewProj", camera.viewProjection());
  m_program.set("uFloor", true);
  m_program.set("uModel", glm::translate(mat4(1.0f), vec3(0.0f, -1.2f, 0.0f)));
  m_floor.draw();
  m_program.set("uFloor", false);
  m_program.set("uModel", glm::rotate(mat4(1.0f), 0.9f * time, glm::normalize(vec3(1.0f, 1.0f, 0.2f))));
  m_torus.draw();
  mat4 cube = glm::rotate(mat4(1.0f), -1.3f * time, vec3(0.0f, 1.0f, 0.0f));
  m_program.set("uModel", glm::rotate(cube, 0.7f, vec3(1.0f, 0.0f, 0.0f)));
  m_cube.draw();
}

}  // namespace glint::render::rtt
