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
}

void resetState() {
  PipelineState{}.apply();
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(0);
  glBindVertexArray(0);
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
