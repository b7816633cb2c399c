#include "glint/gl/objects.h"

#include "glint/core/error.h"

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

namespace glint::gl {

Buffer::Buffer(std::size_t bytes, const void* data, GLbitfield flags, std::string_view name) : m_size(bytes) {
  glCreateBuffers(1, &m_id);
  // Zero-sized storage is an error in GL; keep one byte so empty meshes stay valid objects.
  glNamedBufferStorage(m_id, GLsizeiptr(std::max<std::size_t>(bytes, 1)), bytes ? data : nullptr, flags);
  if (!name.empty()) label(name);
}

void Buffer::update(std::size_t offset, std::size_t bytes, const void* data) {
  if (offset + bytes > m_size) fail(ErrorKind::Internal, "buffer update out of range ({} + {} > {})", offset, bytes, m_size);
  glNamedBufferSubData(m_id, GLintptr(offset), GLsizeiptr(bytes), data);
}

VertexArray::VertexArray(CreateTag, std::string_view name) {
  glCreateVertexArrays(1, &m_id);
  if (!name.empty()) label(name);
}

void VertexArray::attribute(GLuint location, GLuint binding, GLint components, GLuint offset, GLenum type,
                            bool normalized) {
  glEnableVertexArrayAttrib(m_id, location);
  if (type == GL_INT || type == GL_UNSIGNED_INT) {
    glVertexArrayAttribIFormat(m_id, location, components, type, offset);
  } else {
    glVertexArrayAttribFormat(m_id, location, components, type, normalized ? GL_TRUE : GL_FALSE, offset);
  }
  glVertexArrayAttribBinding(m_id, location, binding);
}

void VertexArray::vertexBuffer(GLuint binding, const Buffer& buffer, GLintptr offset, GLsizei stride) {
  glVertexArrayVertexBuffer(m_id, binding, buffer.id(), offset, stride);
}

void VertexArray::indexBuffer(const Buffer& buffer) { glVertexArrayElementBuffer(m_id, buffer.id()); }

int mipLevelCount(int width, int height, int depth) {
  const auto largest = unsigned(std::max({width, height, depth, 1}));
  return int(std::bit_width(largest));
}

Texture::Texture(GLenum target, std::string_view name) : m_target(target) {
  glCreateTextures(target, 1, &m_id);
  if (!name.empty()) label(name);
}

void Texture::storage(GLenum internalFormat, int width, int height, int depth, int levels) {
  if (width <= 0 || height <= 0 || depth <= 0) {
    fail(ErrorKind::Internal, "texture storage needs a positive size, got {}x{}x{}", width, height, depth);
  }
  if (m_target == GL_TEXTURE_CUBE_MAP && width != height) {
    fail(ErrorKind::Input, "cube map faces must be square, got {}x{}", width, height);
  }
  const int fullChain = mipLevelCount(width, m_target == GL_TEXTURE_3D ? std::max(height, depth) : height);
  m_levels = levels <= 0 ? fullChain : std::min(levels, fullChain);
  m_format = internalFormat;
  m_width = width;
  m_height = height;
  m_depth = depth;
  switch (m_target) {
    case GL_TEXTURE_2D:
    case GL_TEXTURE_CUBE_MAP: glTextureStorage2D(m_id, m_levels, internalFormat, width, height); break;
    case GL_TEXTURE_2D_ARRAY:
    case GL_TEXTURE_3D: glTextureStorage3D(m_id, m_levels, internalFormat, width, height, depth); break;
    default: fail(ErrorKind::Internal, "unsupported texture target 0x{:x}", m_target);
  }
}

void Texture::upload(int level, int width, int height, GLenum format, GLenum type, const void* pixels, int layer,
                     int depth) {
  // Rows of glint images are tightly packed; GL's default alignment of 4 would skew
  // odd-width RGB or single-channel uploads.
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (m_target == GL_TEXTURE_2D) {
    glTextureSubImage2D(m_id, level, 0, 0, width, height, format, type, pixels);
  } else {
    // DSA treats cube maps as 6-layer arrays: the face is the z offset.
    glTextureSubImage3D(m_id, level, 0, 0, layer, width, height, depth, format, type, pixels);
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

void Texture::filtering(GLenum minFilter, GLenum magFilter, GLenum wrap) const {
  parameter(GL_TEXTURE_MIN_FILTER, GLint(minFilter));
  parameter(GL_TEXTURE_MAG_FILTER, GLint(magFilter));
  parameter(GL_TEXTURE_WRAP_S, GLint(wrap));
  parameter(GL_TEXTURE_WRAP_T, GLint(wrap));
  parameter(GL_TEXTURE_WRAP_R, GLint(wrap));
}

Sampler::Sampler(CreateTag, std::string_view name) {
  glCreateSamplers(1, &m_id);
  if (!name.empty()) label(name);
}

Renderbuffer::Renderbuffer(GLenum internalFormat, int width, int height, int samples, std::string_view name)
    : m_width(width), m_height(height) {
  glCreateRenderbuffers(1, &m_id);
  if (samples > 0) {
    glNamedRenderbufferStorageMultisample(m_id, samples, internalFormat, width, height);
  } else {
    glNamedRenderbufferStorage(m_id, internalFormat, width, height);
  }
  if (!name.empty()) label(name);
}

Framebuffer::Framebuffer(CreateTag, std::string_view name) {
  glCreateFramebuffers(1, &m_id);
  if (!name.empty()) label(name);
}

void Framebuffer::attach(GLenum attachment, const Texture& texture, int level) {
  glNamedFramebufferTexture(m_id, attachment, texture.id(), level);
}

void Framebuffer::attachLayer(GLenum attachment, const Texture& texture, int layer, int level) {
  glNamedFramebufferTextureLayer(m_id, attachment, texture.id(), level, layer);
}

void Framebuffer::attach(GLenum attachment, const Renderbuffer& renderbuffer) {
  glNamedFramebufferRenderbuffer(m_id, attachment, GL_RENDERBUFFER, renderbuffer.id());
}

void Framebuffer::drawBuffers(std::span<const GLenum> buffers) const {
  glNamedFramebufferDrawBuffers(m_id, GLsizei(buffers.size()), buffers.data());
}

namespace {
const char* statusName(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_UNDEFINED: return "undefined";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "incomplete attachment";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "no attachments";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER: return "draw buffer without attachment";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER: return "read buffer without attachment";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "unsupported format combination";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "mismatched sample counts";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "mismatched layered attachments";
    default: return "unknown status";
  }
}

std::string attachmentName(GLenum a) {
  if (a >= GL_COLOR_ATTACHMENT0 && a < GL_COLOR_ATTACHMENT0 + 32) return fmt::format("GL_COLOR_ATTACHMENT{}", a - GL_COLOR_ATTACHMENT0);
  if (a == GL_DEPTH_ATTACHMENT) return "GL_DEPTH_ATTACHMENT";
  if (a == GL_STENCIL_ATTACHMENT) return "GL_STENCIL_ATTACHMENT";
  return fmt::format("0x{:x}", a);
}

// Which attachment makes the framebuffer incomplete: an attachment is "attachment
// complete" only if it has a non-zero size and a format renderable at that point.
std::string diagnoseAttachments(GLuint fb) {
  GLint maxColor = 8;
  glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &maxColor);
  std::vector<GLenum> points = {GL_DEPTH_ATTACHMENT, GL_STENCIL_ATTACHMENT};
  for (GLint i = 0; i < maxColor; ++i) points.push_back(GL_COLOR_ATTACHMENT0 + GLenum(i));
  std::string attached;
  for (GLenum p : points) {
    GLint type = GL_NONE;
    glGetNamedFramebufferAttachmentParameteriv(fb, p, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type == GL_NONE) continue;
    GLint name = 0;
    glGetNamedFramebufferAttachmentParameteriv(fb, p, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    GLint width = 0, height = 0, internal = 0;
    if (type == GL_TEXTURE) {
      GLint level = 0;
      glGetNamedFramebufferAttachmentParameteriv(fb, p, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, &level);
      glGetTextureLevelParameteriv(GLuint(name), level, GL_TEXTURE_WIDTH, &width);
      glGetTextureLevelParameteriv(GLuint(name), level, GL_TEXTURE_HEIGHT, &height);
      glGetTextureLevelParameteriv(GLuint(name), level, GL_TEXTURE_INTERNAL_FORMAT, &internal);
    } else {
      glGetNamedRenderbufferParameteriv(GLuint(name), GL_RENDERBUFFER_WIDTH, &width);
      glGetNamedRenderbufferParameteriv(GLuint(name), GL_RENDERBUFFER_HEIGHT, &height);
      glGetNamedRenderbufferParameteriv(GLuint(name), GL_RENDERBUFFER_INTERNAL_FORMAT, &internal);
    }
    if (width == 0 || height == 0) return fmt::format("{} has no storage", attachmentName(p));
    attached += fmt::format("{}{} {}x{} format 0x{:x}", attached.empty() ? "" : ", ", attachmentName(p), width,
                            height, internal);
  }
  return attached.empty() ? "nothing is attached" : "attachments: " + attached;
}
}  // namespace

void Framebuffer::checkComplete() const {
  const GLenum status = glCheckNamedFramebufferStatus(m_id, GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return;
  fail(ErrorKind::Internal, "framebuffer incomplete ({}): {}", statusName(status), diagnoseAttachments(m_id));
}

Query::Query(GLenum target, std::string_view name) : m_target(target) {
  glCreateQueries(target, 1, &m_id);
  if (!name.empty()) label(name);
}

bool Query::available() const {
  GLuint ready = 0;
  glGetQueryObjectuiv(m_id, GL_QUERY_RESULT_AVAILABLE, &ready);
  return ready != 0;
}

GLuint64 Query::result() const {
  GLuint64 value = 0;
  glGetQueryObjectui64v(m_id, GL_QUERY_RESULT, &value);
  return value;
}


void Buffer::read(std::size_t offset, std::size_t bytes, void* out) const {
  glGetNamedBufferSubData(m_id, GLintptr(offset), GLsizeiptr(bytes), out);
}

void* Buffer::map(std::size_t offset, std::size_t bytes, GLbitfield access) const {
  return glMapNamedBufferRange(m_id, GLintptr(offset), GLsizeiptr(bytes), access);
}

void Texture::bindImage(GLuint unit, GLenum access, GLenum format, int level) const {
  glBindImageTexture(unit, m_id, level, GL_FALSE, 0, access, format);
}

void Texture::read(int level, GLenum format, GLenum type, std::size_t bytes, void* out) const {
  glGetTextureImage(m_id, level, format, type, GLsizei(bytes), out);
}

void Texture::clear(int level, GLenum format, GLenum type, const void* value) const {
  glClearTexImage(m_id, level, format, type, value);
}

void Texture::copyFromReadFramebuffer(int x, int y, int width, int height) const {
  glCopyTextureSubImage2D(m_id, 0, 0, 0, x, y, width, height);
}

void Framebuffer::clearColor(int drawBuffer, const float rgba[4]) const {
  glClearNamedFramebufferfv(m_id, GL_COLOR, drawBuffer, rgba);
}

void Framebuffer::clearDepthStencil(float depth, int stencil) const {
  glClearNamedFramebufferfi(m_id, GL_DEPTH_STENCIL, 0, depth, stencil);
}

void Framebuffer::blitTo(const Framebuffer& target, std::array<int, 4> from, std::array<int, 4> to, GLbitfield mask,
                         GLenum filter) const {
  glBlitNamedFramebuffer(m_id, target.m_id, from[0], from[1], from[2], from[3], to[0], to[1], to[2], to[3], mask,
                         filter);
}

}  // namespace glint::gl
