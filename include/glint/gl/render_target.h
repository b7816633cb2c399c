#pragma once
// glint/gl/render_target.h — where a frame is drawn, and reading it back.
//
// Contents
//   Target           what a scene draws into: a framebuffer (maybe the window's) and its size,
//                    or a rectangle of one (split-screen panels: region(), column())
//   RenderTarget     an owned offscreen framebuffer: RGBA8 colour texture + depth24/stencil8
//   readColor        colour attachment → Image (RGBA8, top row first)
//   readDepth        depth → float Image (window z, 0 near .. 1 far)
//   readStencil      stencil → U8 Image
//   readTexture      one level (and layer) of a texture → Image
//
// Readback flips rows: GL's origin is the lower left, glint::Image's the upper left.

#include "glint/gl/objects.h"
#include "glint/image/image.h"

#include <string_view>

namespace glint::gl {

/// A framebuffer to draw into and its size. Scenes receive one per frame; they must
/// bind `framebuffer` themselves when they return to it after rendering elsewhere.
///
/// A Target can also be a rectangle of a framebuffer (a panel of a split screen): bind()
/// then sets the viewport to the rectangle and scissors to it, so draws *and clears* stay
/// inside; binding a whole target turns the scissor test off again.
///
/// ```cpp
/// const glint::gl::RenderTarget frame({1280, 720});
/// const glint::gl::Target whole = frame.target();
/// const glint::gl::Target left = whole.column(0, 2), right = whole.column(1, 2);
/// left.bind();  // viewport + scissor: the left half
/// glClearColor(0.2f, 0.3f, 0.8f, 1.0f);
/// glClear(GL_COLOR_BUFFER_BIT);  // clears the left half only
/// right.bind();
/// glClearColor(0.8f, 0.3f, 0.2f, 1.0f);
/// glClear(GL_COLOR_BUFFER_BIT);
/// whole.bind();  // the whole frame, scissor off
/// const glint::Image pixels = glint::gl::readColor(*whole.framebuffer, whole.size);
/// ```
struct Target {
  const Framebuffer* framebuffer = nullptr;  ///< never null in a frame
  ivec2 size{0};    ///< the size of what is drawn: the whole framebuffer, or the rectangle
  ivec2 origin{0};  ///< the rectangle's lower-left corner in the framebuffer (GL's origin)
  bool clipped = false;  ///< a rectangle of a larger framebuffer: bind() scissors to it

  /// Binds the framebuffer, sets the viewport to this target and the scissor test to
  /// match (on for a rectangle, off for a whole framebuffer).
  void bind() const;
  /// The rectangle at `corner` (lower left, relative to this target) of `extent` pixels,
  /// clamped to this target.
  Target region(ivec2 corner, ivec2 extent) const;
  /// Column `i` of `n` equal columns, left to right (the last takes the rounding remainder).
  Target column(int i, int n) const;
  /// Cell (`column`, `row`) of a grid of `columns` × `rows` equal cells, row 0 at the TOP
  /// (reading order), each inset by `gap` pixels on every side.
  Target cell(int column, int row, int columns, int rows, int gap = 0) const;
  /// Width / height, for a camera's aspect ratio.
  float aspect() const { return size.y > 0 ? float(size.x) / float(size.y) : 1.0f; }
};

class RenderTarget {
public:
  RenderTarget() = default;
  /// Colour texture `colorFormat` (GL_RGBA8 by default, GL_RGBA16F for HDR) and a
  /// GL_DEPTH24_STENCIL8 texture, so the stencil buffer is always there.
  RenderTarget(ivec2 size, GLenum colorFormat = GL_RGBA8, std::string_view name = "render-target");

  Target target() const { return {&m_framebuffer, m_size}; }
  const Framebuffer& framebuffer() const { return m_framebuffer; }
  const Texture& color() const { return m_color; }
  const Texture& depthStencil() const { return m_depthStencil; }
  ivec2 size() const { return m_size; }

private:
  ivec2 m_size{0};
  Texture m_color;
  Texture m_depthStencil;
  Framebuffer m_framebuffer;
};

Image readColor(const Framebuffer& framebuffer, ivec2 size, GLenum attachment = GL_COLOR_ATTACHMENT0);
Image readDepth(const Framebuffer& framebuffer, ivec2 size);
Image readStencil(const Framebuffer& framebuffer, ivec2 size);
/// Reads level `level` of a 2D texture, or one face/layer of a cube/array texture, as
/// `channels` channels of `type` (U8 or F32).
Image readTexture(const Texture& texture, int level = 0, int layer = 0, int channels = 4,
                  PixelType type = PixelType::U8);

}  // namespace glint::gl
