#include "glint/render/bump/height_to_normal.h"

#include "glint/core/error.h"
#include "glint/gl/render_target.h"
#include "glint/render/bump/textures.h"
#include "glint/render/state.h"

namespace glint::render::bump {

HeightToNormalPass::HeightToNormalPass()
    : m_pass("bump/height_to_normal.frag"), m_framebuffer(gl::Framebuffer::create("height-to-normal")) {}

void HeightToNormalPass::run(const gl::Texture& height, const gl::Texture& normalMap, const NormalMapOptions& options) {
  if (height.width() != normalMap.width() || height.height() != normalMap.height()) {
    fail(ErrorKind::Usage, "height map {}x{} and normal map {}x{} must have the same size", height.width(),
         height.height(), normalMap.width(), normalMap.height());
  }
  const SavedTarget saved;  // the caller's framebuffer and viewport, put back on return
  m_framebuffer.attach(GL_COLOR_ATTACHMENT0, normalMap);
  m_framebuffer.checkComplete();
  m_framebuffer.bind();
  glViewport(0, 0, normalMap.width(), normalMap.height());
  const auto& program = m_pass.program();
  height.bind(0);
  gl::Sampler::unbind(0);  // texelFetch ignores sampling state, but keep unit 0 predictable
  program.set("uHeight", 0);
  program.set("uScale", options.scale);
  program.set("uWrap", options.wrap);
  program.set("uSlide", options.formula == NormalFormula::Slide);
  PipelineState{.depthTest = false, .depthWrite = false}.apply();
  m_pass.drawWithCurrentState();
  if (normalMap.levels() > 1) normalMap.generateMipmap();
}

Image heightToNormalMapGpu(const Image& input, const NormalMapOptions& options) {
  const Image height = heightFromImage(input);
  const gl::Texture heightTexture = uploadImage(height, {.mipmaps = false, .nearest = true, .label = "height-map"});
  gl::Texture normals(GL_TEXTURE_2D, "normal-map");
  normals.storage(GL_RGBA8, height.width(), height.height());
  HeightToNormalPass().run(heightTexture, normals, options);
  return gl::readTexture(normals);
}

}  // namespace glint::render::bump
