#include "glint/render/env/dynamic_cube.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <string>

namespace glint::render::env {

DynamicCubeMap::DynamicCubeMap(int size, std::string_view label) : m_size(size) {
  if (size <= 0) fail(ErrorKind::Usage, "dynamic cube map size must be positive, got {}", size);
  m_cube = gl::Texture(GL_TEXTURE_CUBE_MAP, label);
  m_cube.storage(GL_RGBA8, size, size, 1, 0);
  m_cube.filtering(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
  // Depth is only needed while drawing a face and never sampled: a renderbuffer.
  m_depth = gl::Renderbuffer(GL_DEPTH24_STENCIL8, size, size, 0, std::string(label) + "-depth");
  m_framebuffer = gl::Framebuffer::create(std::string(label) + "-fbo");
  m_framebuffer.attachLayer(GL_COLOR_ATTACHMENT0, m_cube, 0);
  m_framebuffer.attach(GL_DEPTH_STENCIL_ATTACHMENT, m_depth);
  m_framebuffer.checkComplete();
}

Camera DynamicCubeMap::faceCamera(int face, vec3 centre, float nearPlane, float farPlane) {
  // The cube map convention's axes: window right/up of each face are the spec table's
  // s/t directions, which makes side faces "upside down" (up = −Y).
  static const vec3 kForward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const vec3 kUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  if (face < 0 || face > 5) fail(ErrorKind::Internal, "cube face {} out of range", face);
  return Camera::lookAt(centre, centre + kForward[face], kUp[face], 90.0f, 1.0f, nearPlane, farPlane);
}

void DynamicCubeMap::render(vec3 centre, const std::function<void(const Camera&)>& draw, vec4 clear,
                            float nearPlane, float farPlane) {
  const SavedTarget saved;  // the caller's framebuffer and viewport, put back on return
  for (int face = 0; face < 6; ++face) {
    m_framebuffer.attachLayer(GL_COLOR_ATTACHMENT0, m_cube, face, 0);
    m_framebuffer.bind();
    glViewport(0, 0, m_size, m_size);
    PipelineState{}.apply();  // the default state for what is drawn next
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, clear);
    draw(faceCamera(face, centre, nearPlane, farPlane));
  }
  m_cube.generateMipmap();
}

}  // namespace glint::render::env
