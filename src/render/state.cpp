#include "glint/render/state.h"

namespace glint::render {

namespace {
void enable(GLenum cap, bool on) { on ? glEnable(cap) : glDisable(cap); }

void applyStencilFace(GLenum face, const StencilFace& s) {
  glStencilFuncSeparate(face, s.func, s.ref, s.valueMask);
  glStencilMaskSeparate(face, s.writeMask);
  glStencilOpSeparate(face, s.sfail, s.dpfail, s.dppass);
}
}  // namespace

void PipelineState::apply() const {
  enable(GL_DEPTH_TEST, depthTest);
  glDepthFunc(depthFunc);
  glDepthMask(depthWrite ? GL_TRUE : GL_FALSE);
  enable(GL_DEPTH_CLAMP, depthClamp);
  glColorMask(colorMask[0], colorMask[1], colorMask[2], colorMask[3]);
  enable(GL_CULL_FACE, cull);
  glCullFace(cullFace);
  glFrontFace(frontFace);
  enable(GL_POLYGON_OFFSET_FILL, polygonOffset);
  enable(GL_POLYGON_OFFSET_LINE, polygonOffset);
  glPolygonOffset(offsetFactor, offsetUnits);
  glPolygonMode(GL_FRONT_AND_BACK, polygonMode);

  enable(GL_STENCIL_TEST, stencil.enabled);
  applyStencilFace(GL_FRONT, stencil.front);
  applyStencilFace(GL_BACK, stencil.separate ? stencil.back : stencil.front);

  enable(GL_BLEND, blend.enabled);
  glBlendEquation(blend.equation);
  if (blend.separateAlpha) {
    glBlendFuncSeparate(blend.src, blend.dst, blend.srcAlpha, blend.dstAlpha);
  } else {
    glBlendFunc(blend.src, blend.dst);
  }
  enable(GL_TEXTURE_CUBE_MAP_SEAMLESS, seamlessCubeMap);
}

SavedTarget::SavedTarget() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &m_draw);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &m_read);
  glGetIntegerv(GL_VIEWPORT, m_viewport.data());
}

SavedTarget::~SavedTarget() {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(m_draw));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(m_read));
  glViewport(m_viewport[0], m_viewport[1], m_viewport[2], m_viewport[3]);
}

void resetState() {
  PipelineState{}.apply();
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(0);
  glBindVertexArray(0);
}

std::vector<std::string> stateLeftBehind() {
  std::vector<std::string> left;
  const auto offByDefault = [&](GLenum cap, const char* name) {
    if (glIsEnabled(cap)) left.emplace_back(name);
  };
  const auto integer = [](GLenum pname) {
    GLint value = 0;
    glGetIntegerv(pname, &value);
    return value;
  };
  offByDefault(GL_SCISSOR_TEST, "GL_SCISSOR_TEST");
  offByDefault(GL_PROGRAM_POINT_SIZE, "GL_PROGRAM_POINT_SIZE");
  offByDefault(GL_RASTERIZER_DISCARD, "GL_RASTERIZER_DISCARD");
  offByDefault(GL_PRIMITIVE_RESTART, "GL_PRIMITIVE_RESTART");
  offByDefault(GL_COLOR_LOGIC_OP, "GL_COLOR_LOGIC_OP");
  offByDefault(GL_SAMPLE_ALPHA_TO_COVERAGE, "GL_SAMPLE_ALPHA_TO_COVERAGE");
  if (integer(GL_PIXEL_PACK_BUFFER_BINDING) != 0) left.emplace_back("GL_PIXEL_PACK_BUFFER bound");
  if (integer(GL_PIXEL_UNPACK_BUFFER_BINDING) != 0) left.emplace_back("GL_PIXEL_UNPACK_BUFFER bound");
  if (integer(GL_PACK_ALIGNMENT) != 4) left.emplace_back("GL_PACK_ALIGNMENT");
  if (integer(GL_UNPACK_ALIGNMENT) != 4) left.emplace_back("GL_UNPACK_ALIGNMENT");
  if (integer(GL_ACTIVE_TEXTURE) != GL_TEXTURE0) left.emplace_back("GL_ACTIVE_TEXTURE");
  if (integer(GL_CONTEXT_PROFILE_MASK) & GL_CONTEXT_COMPATIBILITY_PROFILE_BIT) {
    offByDefault(GL_TEXTURE_2D, "GL_TEXTURE_2D");
    offByDefault(GL_TEXTURE_CUBE_MAP, "GL_TEXTURE_CUBE_MAP");
    offByDefault(GL_NORMALIZE, "GL_NORMALIZE");
    offByDefault(GL_LIGHTING, "GL_LIGHTING");
    offByDefault(GL_TEXTURE_GEN_S, "GL_TEXTURE_GEN_S");
    offByDefault(GL_TEXTURE_GEN_T, "GL_TEXTURE_GEN_T");
    offByDefault(GL_TEXTURE_GEN_R, "GL_TEXTURE_GEN_R");
    offByDefault(GL_VERTEX_ARRAY, "GL_VERTEX_ARRAY");
    offByDefault(GL_NORMAL_ARRAY, "GL_NORMAL_ARRAY");
    offByDefault(GL_COLOR_ARRAY, "GL_COLOR_ARRAY");
    offByDefault(GL_TEXTURE_COORD_ARRAY, "GL_TEXTURE_COORD_ARRAY");
  }
  return left;
}

void clear(GLbitfield buffers, const float color[4], double depth, int stencil) {
  if (buffers & GL_COLOR_BUFFER_BIT) {
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (color) glClearColor(color[0], color[1], color[2], color[3]);
  }
  if (buffers & GL_DEPTH_BUFFER_BIT) {
    glDepthMask(GL_TRUE);
    glClearDepth(depth);
  }
  if (buffers & GL_STENCIL_BUFFER_BIT) {
    glStencilMask(0xFF);
    glClearStencil(stencil);
  }
  glClear(buffers);
}

}  // namespace glint::render
