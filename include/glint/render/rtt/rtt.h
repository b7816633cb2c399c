#pragma once
// glint/render/rtt/rtt.h — render to texture, both ways of the VGP353 lecture.
//
// Contents
//   CopyToTexture        (a) draw into the window's framebuffer, then glCopyTextureSubImage2D
//   FramebufferTexture   (b) draw straight into a texture: a framebuffer object with the
//                        texture as colour attachment and a depth-stencil renderbuffer
//   RttContent           the small animated scene both methods render (scene, tests, bench)
//
// Both end with glGenerateMipmap (the slides: "you cannot use GL_GENERATE_MIPMAP with
// FBO-rendered textures ... use glGenerateMipmap"), so a texture made either way is
// complete and can be minified. Given the same drawing they produce the same texels.
//
// The copy method's costs are the VGP353 lecture's list: an extra copy, extra clears (the window
// is cleared for the texture's content and again for the frame), and "the window must be
// at least as large as the desired texture" — CopyToTexture::render throws Error(Usage)
// saying so instead of copying garbage. A headless context has no window: "the window" is
// the frame's target framebuffer (FrameInput::target).
//
/// ```cpp
/// namespace rtt = glint::render::rtt;
/// const rtt::RttContent content;  // with a current GL context
/// const float time = 1.5f;
/// rtt::FramebufferTexture fbo(256);
/// fbo.render([&](glint::ivec2 size) { content.draw(size, time); });
/// fbo.texture().bind(0);  // sample it, mipmaps included
/// ```

#include "glint/gl/objects.h"
#include "glint/gl/render_target.h"
#include "glint/gl/shader.h"
#include "glint/render/gpu_mesh.h"

#include <functional>
#include <string_view>

namespace glint::render::rtt {

/// Draws the texture's content into the bound framebuffer; the viewport is already
/// set to the texture's size and colour/depth are cleared.
using DrawFn = std::function<void(ivec2 size)>;

class CopyToTexture {
public:
  CopyToTexture() = default;
  /// An RGBA8 texture of size × size with a full mip chain.
  explicit CopyToTexture(int size, std::string_view label = "copy-texture");
  /// Clears the lower-left size × size of `window`, draws there, copies it into level 0
  /// (glCopyTextureSubImage2D), then glGenerateMipmap. Error(Usage) when the window is
  /// smaller than the texture in either direction. Leaves `window` bound.
  void render(const gl::Target& window, const DrawFn& draw, vec4 clear = vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const gl::Texture& texture() const { return m_texture; }
  int size() const { return m_size; }

private:
  int m_size = 0;
  gl::Texture m_texture;
};

class FramebufferTexture {
public:
  FramebufferTexture() = default;
  /// An RGBA8 texture (full mip chain) as GL_COLOR_ATTACHMENT0 and a GL_DEPTH24_STENCIL8
  /// renderbuffer (never sampled, so not a texture) of the same size; completeness checked.
  explicit FramebufferTexture(int size, std::string_view label = "fbo-texture");
  /// Binds the framebuffer object, clears, draws, glGenerateMipmap; the caller's framebuffer
  /// binding and viewport are put back (render::SavedTarget).
  void render(const DrawFn& draw, vec4 clear = vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const gl::Texture& texture() const { return m_texture; }
  int size() const { return m_size; }

private:
  int m_size = 0;
  gl::Texture m_texture;
  gl::Renderbuffer m_depthStencil;
  gl::Framebuffer m_framebuffer;
};

/// A torus and a cube spinning over a checkered floor, coloured by their normals: enough
/// depth complexity that a missing depth buffer would show.
class RttContent {
public:
  RttContent();
  /// Draws the content at `time` seconds into the bound framebuffer (viewport `size`).
  void draw(ivec2 size, float time) const;

private:
  gl::Program m_program;
  GpuMesh m_torus;
  GpuMesh m_cube;
  GpuMesh m_floor;
};

}  // namespace glint::render::rtt
