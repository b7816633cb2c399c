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

}  // namespace glint::render
