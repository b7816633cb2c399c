#include "glint/gl/render_target.h"

#include "glint/core/error.h"

#include <algorithm>
#include <string>
#include <string_view>

namespace glint::gl {

void Target::bind() const {
  framebuffer->bind();
  glViewport(origin.x, origin.y, size.x, size.y);
  if (clipped) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(origin.x, origin.y, size.x, size.y);
  } else {
    glDisable(GL_SCISSOR_TEST);
  }
}

Target Target::region(ivec2 corner, ivec2 extent) const {
  const ivec2 lo = glm::clamp(corner, ivec2(0), size);
  const ivec2 hi = glm::clamp(corner + extent, lo, size);
  return {.framebuffer = framebuffer, .size = hi - lo, .origin = origin + lo, .clipped = true};
}

Target Target::column(int i, int n) const {
  const int left = size.x * i / n, right = size.x * (i + 1) / n;
  return region({left, 0}, {right - left, size.y});
}

Target Target::cell(int column, int row, int columns, int rows, int gap) const {
  const int left = size.x * column / columns, right = size.x * (column + 1) / columns;
  const int top = size.y - size.y * row / rows, bottom = size.y - size.y * (row + 1) / rows;
  return region({left + gap, bottom + gap}, {right - left - 2 * gap, top - bottom - 2 * gap});
}

RenderTarget::RenderTarget(ivec2 size, GLenum colorFormat, std::string_view name) : m_size(size) {
  if (size.x <= 0 || size.y <= 0) fail(ErrorKind::Usage, "render size must be positive, got {}x{}", size.x, size.y);
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
  if (size.x > maxSize || size.y > maxSize) {
    fail(ErrorKind::Usage, "render size {}x{} exceeds this GPU's limit of {}", size.x, size.y, maxSize);
  }
  m_color = Texture(GL_TEXTURE_2D, std::string(name) + "-color");
  m_color.storage(colorFormat, size.x, size.y);
  m_color.filtering(GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
  m_depthStencil = Texture(GL_TEXTURE_2D, std::string(name) + "-depth-stencil");
  m_depthStencil.storage(GL_DEPTH24_STENCIL8, size.x, size.y);
  m_depthStencil.filtering(GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
  m_framebuffer = Framebuffer::create(name);
  m_framebuffer.attach(GL_COLOR_ATTACHMENT0, m_color);
  m_framebuffer.attach(GL_DEPTH_STENCIL_ATTACHMENT, m_depthStencil);
  m_framebuffer.checkComplete();
}

namespace {
Image readPixels(const Framebuffer& fb, ivec2 size, GLenum attachment, GLenum format, GLenum type, int channels,
                 PixelType pixelType) {
  Image image(size.x, size.y, channels, pixelType);
  if (attachment != GL_NONE) glNamedFramebufferReadBuffer(fb.id(), fb.isDefault() ? GL_BACK : attachment);
  fb.bind(GL_READ_FRAMEBUFFER);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadnPixels(0, 0, size.x, size.y, format, type, GLsizei(image.bytes().size()), image.bytes().data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  image.flipVertical();
  return image;
}
}  // namespace

Image readColor(const Framebuffer& fb, ivec2 size, GLenum attachment) {
  return readPixels(fb, size, attachment, GL_RGBA, GL_UNSIGNED_BYTE, 4, PixelType::U8);
}

Image readDepth(const Framebuffer& fb, ivec2 size) {
  return readPixels(fb, size, GL_NONE, GL_DEPTH_COMPONENT, GL_FLOAT, 1, PixelType::F32);
}

Image readStencil(const Framebuffer& fb, ivec2 size) {
  return readPixels(fb, size, GL_NONE, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, 1, PixelType::U8);
}

Image readTexture(const Texture& texture, int level, int layer, int channels, PixelType type) {
  const int w = std::max(1, texture.width() >> level);
  const int h = std::max(1, texture.height() >> level);
  static constexpr GLenum kFormats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  const GLenum format = kFormats[channels - 1];
  const GLenum glType = type == PixelType::F32 ? GL_FLOAT : type == PixelType::U16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_BYTE;
  Image image(w, h, channels, type);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (texture.target() == GL_TEXTURE_2D) {
    glGetTextureImage(texture.id(), level, format, glType, GLsizei(image.bytes().size()), image.bytes().data());
  } else {
    glGetTextureSubImage(texture.id(), level, 0, 0, layer, w, h, 1, format, glType, GLsizei(image.bytes().size()),
                         image.bytes().data());
  }
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  image.flipVertical();
  return image;
}

}  // namespace glint::gl
