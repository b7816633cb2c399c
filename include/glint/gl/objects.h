#pragma once
// glint/gl/objects.h — move-only RAII owners for every OpenGL object glint uses.
//
// Contents
//   Object<Kind>     the common owner: id(), label(), release(), reset()
//   Buffer           immutable storage (glNamedBufferStorage), updates, binding
//   VertexArray      attribute formats and buffer bindings (DSA)
//   Texture          2D, cube, 2D array, 3D: immutable storage, uploads, mipmaps, parameters
//   Sampler          filtering/wrap/anisotropy state separate from textures
//   Renderbuffer     depth/stencil or colour storage that is never sampled
//   Framebuffer      attachments, completeness check naming the failing attachment
//   Query            timer, samples-passed and occlusion queries
//
// Every object is created with direct state access (glCreate*), so creating one
// never disturbs a binding. Copy is deleted; moving transfers ownership and
// leaves the source empty (id 0). Objects must be destroyed while their context
// is current — owners (scenes, techniques) are destroyed before the context.
//
// Labels (glObjectLabel) show up in debug messages and GPU debuggers: pass one.
//
// Common mistakes
//   - A texture's storage is immutable: call a storage function once, then upload.
//   - Texture::bind(unit) binds to a texture unit (glBindTextureUnit), not a target.
//   - Framebuffer::checkComplete() throws naming the attachment; call it after attaching.

#include "glint/core/math.h"

#include <epoxy/gl.h>

#include <array>
#include <cstddef>
#include <span>
#include <string_view>
#include <utility>

namespace glint::gl {

/// The deleter of each object kind; Object<Kind> calls Kind::destroy(id).
template <typename Kind>
class Object {
public:
  Object() = default;
  ~Object() { reset(); }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  Object(Object&& other) noexcept : m_id(std::exchange(other.m_id, 0)), m_owned(other.m_owned) {}
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      m_id = std::exchange(other.m_id, 0);
      m_owned = other.m_owned;
    }
    return *this;
  }

  /// The GL name, for calls the classes here do not wrap: keep such calls inside gl/, or
  /// at an interop boundary (ImGui's texture ids, another library's GL code).
  GLuint id() const { return m_id; }
  explicit operator bool() const { return m_id != 0; }
  /// Gives up ownership: the caller must delete the object.
  GLuint release() { return std::exchange(m_id, 0); }
  /// Deletes the object now (no-op when empty).
  void reset() {
    if (m_id && m_owned) Kind::destroy(m_id);
    m_id = 0;
  }
  /// Names the object in debug output.
  void label(std::string_view name) const {
    if (m_id) glObjectLabel(Kind::kLabelType, m_id, GLsizei(name.size()), name.data());
  }

protected:
  explicit Object(GLuint id, bool owned = true) : m_id(id), m_owned(owned) {}
  GLuint m_id = 0;
  bool m_owned = true;
};

// ---------------------------------------------------------------------------
struct BufferKind {
  static constexpr GLenum kLabelType = GL_BUFFER;
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};

class Buffer : public Object<BufferKind> {
public:
  Buffer() = default;
  /// Immutable storage of `bytes` bytes, optionally initialised. `flags` as for
  /// glNamedBufferStorage (GL_DYNAMIC_STORAGE_BIT to allow update()).
  Buffer(std::size_t bytes, const void* data, GLbitfield flags = 0, std::string_view name = {});
  template <typename T>
  Buffer(std::span<const T> data, GLbitfield flags = 0, std::string_view name = {})
      : Buffer(data.size_bytes(), data.data(), flags, name) {}

  std::size_t size() const { return m_size; }
  /// Needs GL_DYNAMIC_STORAGE_BIT.
  void update(std::size_t offset, std::size_t bytes, const void* data);
  /// glBindBufferBase for uniform/storage buffers.
  void bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, m_id); }
  /// glBindBuffer: a bind point without an index (GL_PIXEL_PACK_BUFFER / UNPACK for
  /// asynchronous transfers, GL_ARRAY_BUFFER for the fixed-function path's pointers).
  /// Unbind with unbind(target) when done, so later pixel transfers use client memory.
  void bind(GLenum target) const { glBindBuffer(target, m_id); }
  static void unbind(GLenum target) { glBindBuffer(target, 0); }
  /// Copies `bytes` bytes at `offset` into `out` (glGetNamedBufferSubData; waits for the GPU).
  void read(std::size_t offset, std::size_t bytes, void* out) const;
  /// glMapNamedBufferRange over [offset, offset + bytes); nullptr when GL refuses.
  void* map(std::size_t offset, std::size_t bytes, GLbitfield access) const;

private:
  std::size_t m_size = 0;
};

// ---------------------------------------------------------------------------
struct VertexArrayKind {
  static constexpr GLenum kLabelType = GL_VERTEX_ARRAY;
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};

class VertexArray : public Object<VertexArrayKind> {
public:
  struct CreateTag {};
  VertexArray() = default;
  explicit VertexArray(CreateTag, std::string_view name = {});
  static VertexArray create(std::string_view name = {}) { return VertexArray(CreateTag{}, name); }

  /// Float attribute `location` reading `components` floats at `offset` of binding `binding`.
  void attribute(GLuint location, GLuint binding, GLint components, GLuint offset, GLenum type = GL_FLOAT,
                 bool normalized = false);
  void vertexBuffer(GLuint binding, const Buffer& buffer, GLintptr offset, GLsizei stride);
  void indexBuffer(const Buffer& buffer);
  void bind() const { glBindVertexArray(m_id); }
};

// ---------------------------------------------------------------------------
struct TextureKind {
  static constexpr GLenum kLabelType = GL_TEXTURE;
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};

/// Number of mip levels of a full chain for a size (1 for 1×1).
int mipLevelCount(int width, int height, int depth = 1);

class Texture : public Object<TextureKind> {
public:
  Texture() = default;
  /// Creates (no storage yet) a texture of `target`: GL_TEXTURE_2D, GL_TEXTURE_CUBE_MAP,
  /// GL_TEXTURE_2D_ARRAY or GL_TEXTURE_3D.
  Texture(GLenum target, std::string_view name = {});

  /// Allocates immutable storage. `levels` 0 = full mip chain. depth = layers for arrays.
  /// Cube maps: width must equal height (faces are square).
  void storage(GLenum internalFormat, int width, int height, int depth = 1, int levels = 1);
  /// Uploads into level `level`; for cube maps and arrays `layer` is the face/layer (z offset).
  void upload(int level, int width, int height, GLenum format, GLenum type, const void* pixels, int layer = 0,
              int depth = 1);
  void generateMipmap() const { glGenerateTextureMipmap(m_id); }
  void parameter(GLenum pname, GLint value) const { glTextureParameteri(m_id, pname, value); }
  void parameter(GLenum pname, GLfloat value) const { glTextureParameterf(m_id, pname, value); }
  /// Min/mag filter and wrap in one call.
  void filtering(GLenum minFilter, GLenum magFilter, GLenum wrap = GL_REPEAT) const;
  void bind(GLuint unit) const { glBindTextureUnit(unit, m_id); }
  /// Binds to `unit` with no sampler object there, so the texture's own parameters apply
  /// (and texelFetch, which ignores sampling state, reads a predictable unit).
  void bindUnsampled(GLuint unit) const {
    glBindTextureUnit(unit, m_id);
    glBindSampler(unit, 0);
  }
  /// glBindTexture(target(), ...) on the active texture unit: the fixed-function path's
  /// way, which glEnable(GL_TEXTURE_2D / CUBE_MAP) then reads. Prefer bind(unit).
  void bindToActiveUnit() const { glBindTexture(m_target, m_id); }
  /// Binds one level as an image for compute-shader loads and stores (glBindImageTexture).
  void bindImage(GLuint unit, GLenum access, GLenum format, int level = 0) const;
  /// Reads level `level` back (glGetTextureImage). With a buffer bound to
  /// GL_PIXEL_PACK_BUFFER, `out` is an offset into it and the read is asynchronous.
  void read(int level, GLenum format, GLenum type, std::size_t bytes, void* out) const;
  /// Sets every texel of level `level` to `value` (glClearTexImage; nullptr: zeros).
  void clear(int level, GLenum format, GLenum type, const void* value) const;
  /// Copies a rectangle of the read framebuffer into level 0 at (0, 0)
  /// (glCopyTextureSubImage2D: the VGP353 lecture's copy-to-texture).
  void copyFromReadFramebuffer(int x, int y, int width, int height) const;

  GLenum target() const { return m_target; }
  GLenum internalFormat() const { return m_format; }
  int width() const { return m_width; }
  int height() const { return m_height; }
  int depth() const { return m_depth; }
  int levels() const { return m_levels; }

private:
  GLenum m_target = 0;
  GLenum m_format = 0;
  int m_width = 0, m_height = 0, m_depth = 0, m_levels = 0;
};

// ---------------------------------------------------------------------------
struct SamplerKind {
  static constexpr GLenum kLabelType = GL_SAMPLER;
  static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};

class Sampler : public Object<SamplerKind> {
public:
  struct CreateTag {};
  Sampler() = default;
  explicit Sampler(CreateTag, std::string_view name = {});
  static Sampler create(std::string_view name = {}) { return Sampler(CreateTag{}, name); }
  void parameter(GLenum pname, GLint value) const { glSamplerParameteri(m_id, pname, value); }
  void parameter(GLenum pname, GLfloat value) const { glSamplerParameterf(m_id, pname, value); }
  void bind(GLuint unit) const { glBindSampler(unit, m_id); }
  static void unbind(GLuint unit) { glBindSampler(unit, 0); }
};

// ---------------------------------------------------------------------------
struct RenderbufferKind {
  static constexpr GLenum kLabelType = GL_RENDERBUFFER;
  static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};

class Renderbuffer : public Object<RenderbufferKind> {
public:
  Renderbuffer() = default;
  Renderbuffer(GLenum internalFormat, int width, int height, int samples = 0, std::string_view name = {});
  int width() const { return m_width; }
  int height() const { return m_height; }

private:
  int m_width = 0, m_height = 0;
};

// ---------------------------------------------------------------------------
struct FramebufferKind {
  static constexpr GLenum kLabelType = GL_FRAMEBUFFER;
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};

class Framebuffer : public Object<FramebufferKind> {
public:
  struct CreateTag {};
  Framebuffer() = default;
  explicit Framebuffer(CreateTag, std::string_view name = {});
  static Framebuffer create(std::string_view name = {}) { return Framebuffer(CreateTag{}, name); }
  /// A non-owning handle to the window's default framebuffer (name 0).
  static Framebuffer defaultFramebuffer() { return Framebuffer(0, false); }

  void attach(GLenum attachment, const Texture& texture, int level = 0);
  /// One face of a cube map or one layer of an array texture.
  void attachLayer(GLenum attachment, const Texture& texture, int layer, int level = 0);
  void attach(GLenum attachment, const Renderbuffer& renderbuffer);
  /// Selects colour attachments to draw into (default: GL_COLOR_ATTACHMENT0).
  void drawBuffers(std::span<const GLenum> buffers) const;
  /// Throws Error(Internal) naming the status and the failing attachment when incomplete.
  void checkComplete() const;
  bool isDefault() const { return m_id == 0; }
  /// Clears colour attachment `drawBuffer` (the index into drawBuffers) to `rgba`, whatever
  /// is bound (glClearNamedFramebufferfv). Honours the colour mask, as glClear does.
  void clearColor(int drawBuffer, const float rgba[4]) const;
  /// Clears depth and stencil at once (glClearNamedFramebufferfi); honours their masks.
  void clearDepthStencil(float depth, int stencil) const;
  /// Copies `from` (x0, y0, x1, y1) of this framebuffer's read buffer into `to` of
  /// `target` (glBlitNamedFramebuffer); to.y0 > to.y1 flips vertically.
  void blitTo(const Framebuffer& target, std::array<int, 4> from, std::array<int, 4> to, GLbitfield mask,
              GLenum filter = GL_NEAREST) const;
  void bind(GLenum target = GL_FRAMEBUFFER) const { glBindFramebuffer(target, m_id); }

private:
  Framebuffer(GLuint id, bool owned) : Object(id, owned) {}
};

// ---------------------------------------------------------------------------
struct QueryKind {
  static constexpr GLenum kLabelType = GL_QUERY;
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};

class Query : public Object<QueryKind> {
public:
  Query() = default;
  /// GL_TIME_ELAPSED, GL_TIMESTAMP, GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED, ...
  explicit Query(GLenum target, std::string_view name = {});
  void begin() const { glBeginQuery(m_target, m_id); }
  void end() const { glEndQuery(m_target); }
  bool available() const;
  /// Waits for the result.
  GLuint64 result() const;
  GLenum target() const { return m_target; }

private:
  GLenum m_target = 0;
};

}  // namespace glint::gl
