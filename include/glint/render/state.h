#pragma once
// glint/render/state.h — fixed-function state a pass needs, set all at once.
//
// Techniques never rely on what a previous pass left behind: each pass describes
// the state it draws with in a PipelineState and calls apply(). A default
// PipelineState is exactly OpenGL's initial state (depth test off, no culling, ...), the
// same defaults and field names as raster::State, the reference pipeline's description of
// the same state; a 3D pass says that it tests depth. Designated initialisers read like
// documentation:
//
/// ```cpp
/// using glint::render::PipelineState;
/// PipelineState{.depthTest = true, .depthFunc = GL_LEQUAL, .cull = true}.apply();
/// PipelineState{.depthTest = true, .depthWrite = false, .colorMask = {false, false, false, false},
///               .stencil = {.enabled = true, .front = {.dppass = GL_INVERT}}}.apply();
/// ```

#include "glint/core/math.h"

#include <epoxy/gl.h>

#include <array>
#include <string>
#include <vector>

namespace glint::render {

struct StencilFace {
  GLenum func = GL_ALWAYS;
  GLint ref = 0;
  GLuint valueMask = 0xFF;
  GLuint writeMask = 0xFF;
  GLenum sfail = GL_KEEP;   ///< stencil test fails
  GLenum dpfail = GL_KEEP;  ///< stencil passes, depth fails
  GLenum dppass = GL_KEEP;  ///< both pass
};

struct StencilState {
  bool enabled = false;
  StencilFace front;
  StencilFace back;
  bool separate = false;  ///< false: `front` is used for both faces
};

struct BlendState {
  bool enabled = false;
  GLenum src = GL_ONE;
  GLenum dst = GL_ZERO;
  GLenum srcAlpha = GL_ONE;  ///< used when separateAlpha
  GLenum dstAlpha = GL_ZERO;
  bool separateAlpha = false;
  GLenum equation = GL_FUNC_ADD;
};

struct PipelineState {
  bool depthTest = false;  ///< GL_DEPTH_TEST
  GLenum depthFunc = GL_LESS;
  bool depthWrite = true;
  bool depthClamp = false;
  std::array<bool, 4> colorMask{true, true, true, true};
  bool cull = false;          ///< GL_CULL_FACE
  GLenum cullFace = GL_BACK;  ///< glCullFace: which faces are culled
  GLenum frontFace = GL_CCW;
  bool polygonOffset = false;
  float offsetFactor = 0.0f;
  float offsetUnits = 0.0f;
  GLenum polygonMode = GL_FILL;
  StencilState stencil;
  BlendState blend;
  /// GL_TEXTURE_CUBE_MAP_SEAMLESS: cube maps filter across face edges instead of clamping at
  /// them (a visible seam). Off by default, as in GL; a pass that samples a cube map sets it.
  bool seamlessCubeMap = false;

  /// Sets every piece of state above on the current context.
  void apply() const;
};

/// Restores the defaults of everything PipelineState covers, turns the scissor test off
/// and unbinds program and vertex array. Front ends call it before every frame so no
/// scene inherits state from the one drawn before it.
void resetState();

/// The pieces of state that PipelineState does not cover and that a pass must therefore
/// restore (the scissor test, program point size, pixel-transfer buffers and alignment,
/// the active texture unit; with a compatibility profile the fixed-function enables and
/// client arrays), named where they are not at OpenGL's initial value. Empty when a pass
/// cleaned up after itself: the golden tests check it after every variant.
std::vector<std::string> stateLeftBehind();

/// Saves the draw and read framebuffer bindings and the viewport, and puts them back when it
/// goes out of scope. A pass that renders into a target of its own (a cube map's faces, a
/// simulation's state, a post effect's output) holds one, so the caller's target is what it
/// was afterwards, as Dear ImGui's backends leave what they found:
///
/// ```cpp
/// #include <glint/gl/objects.h>
/// const auto drawFace = [](const glint::gl::Framebuffer& faceTarget, int size) {
///   const glint::render::SavedTarget saved;  // the caller's framebuffer and viewport
///   faceTarget.bind();
///   glViewport(0, 0, size, size);
///   // ... draw ...
/// };                                          // put back here, on every way out
/// (void)drawFace;
/// ```
class SavedTarget {
public:
  SavedTarget();
  ~SavedTarget();
  SavedTarget(const SavedTarget&) = delete;
  SavedTarget& operator=(const SavedTarget&) = delete;

private:
  GLint m_draw = 0, m_read = 0;
  std::array<GLint, 4> m_viewport{};
};

/// glClear with every write mask enabled first. glClear honours glColorMask, glDepthMask
/// and glStencilMask — a classic trap when the previous pass turned depth writes off —
/// so clear through this. The masks stay enabled afterwards.
void clear(GLbitfield buffers, const float color[4] = nullptr, double depth = 1.0, int stencil = 0);
/// The same with a clear colour.
inline void clear(GLbitfield buffers, const vec4& color, double depth = 1.0, int stencil = 0) {
  clear(buffers, &color.r, depth, stencil);
}

}  // namespace glint::render
