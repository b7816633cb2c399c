// Planar projected shadows rendered into a texture, applied to the ground.
#include "glint/render/shadows/planar.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>

namespace glint::render::shadows {

mat4 planarShadowMatrix(vec4 plane, vec3 light) {
  const vec4 l(light, 1.0f);
  const float d = glm::dot(plane, l);
  // M = d·I − l·planeᵀ; GLM is column-major: m[col][row] = d·δ − l[row]·plane[col].
  mat4 m(0.0f);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m[c][r] = (c == r ? d : 0.0f) - l[r] * plane[c];
  return m;
}

PlanarShadow::PlanarShadow(const glint::shadows::World& world, const PlanarShadowOptions& options)
    : m_options(options),
      m_texture(GL_TEXTURE_2D, "planar-shadow"),
      m_fbo(gl::Framebuffer::create("planar-shadow")),
      m_sampler(gl::Sampler::create("planar-shadow")),
      m_projectProgram(gl::Program::fromFiles({"shadows/planar_project.vert", "shadows/planar_shadow.frag"})),
      m_sceneProgram(gl::Program::fromFiles({"shadows/scene.vert", "shadows/scene.frag"}, {"PLANAR_SHADOW"})),
      m_scene(world),
      m_show("shadows/show_texture.frag") {
  std::size_t groundIndex = world.objects.size();
  for (std::size_t i = 0; i < world.objects.size() && groundIndex == world.objects.size(); ++i)
    if (world.objects[i].ground) groundIndex = i;
  if (groundIndex == world.objects.size()) fail(ErrorKind::Usage, "planar shadows need a ground object in the world");
  const Bounds g = world.worldMesh(groundIndex).bounds();
  const vec2 centre{g.center().x, g.center().z};
  const float half = 0.5f * std::max(g.extent().x, g.extent().z);
  // Ground point (x, y, z) → clip (x', z') of the texture pass, seen from above.
  m_groundClip = mat4(0.0f);
  m_groundClip[0][0] = 1.0f / half;
  m_groundClip[2][1] = 1.0f / half;
  m_groundClip[3][0] = -centre.x / half;
  m_groundClip[3][1] = -centre.y / half;
  m_groundClip[3][3] = 1.0f;
  m_textureMatrix = glm::translate(mat4(1.0f), {0.5f, 0.5f, 0.0f}) * glm::scale(mat4(1.0f), {0.5f, 0.5f, 1.0f}) * m_groundClip;

  m_texture.storage(GL_RGBA8, options.size, options.size);
  m_fbo.attach(GL_COLOR_ATTACHMENT0, m_texture);
  m_fbo.checkComplete();
  // Bilinear filtering softens the texel staircase on the ground a little.
  m_sampler.parameter(GL_TEXTURE_MIN_FILTER, GLint(GL_LINEAR));
  m_sampler.parameter(GL_TEXTURE_MAG_FILTER, GLint(GL_LINEAR));
  m_sampler.parameter(GL_TEXTURE_WRAP_S, GLint(GL_CLAMP_TO_EDGE));
  m_sampler.parameter(GL_TEXTURE_WRAP_T, GLint(GL_CLAMP_TO_EDGE));
}

void PlanarShadow::renderTexture(const glint::shadows::World& world) {
  m_fbo.bind();
  glViewport(0, 0, m_options.size, m_options.size);
  // Flattened casters overlap and may be wound either way: no depth test, no culling.
  PipelineState{.depthTest = false, .depthWrite = false}.apply();
  render::clear(GL_COLOR_BUFFER_BIT, vec4(1.0f, 1.0f, 1.0f, 1.0f));
  m_projectProgram.set("uShadowMatrix", planarShadowMatrix({0.0f, 1.0f, 0.0f, -world.groundHeight}, world.lightPosition));
  m_projectProgram.set("uGroundClip", m_groundClip);
  m_scene.drawGeometry(world, mat4(1.0f), m_projectProgram, [](const glint::shadows::WorldObject& o) { return o.castsShadow && !o.ground; });
}

void PlanarShadow::render(const glint::shadows::World& world, const Camera& camera, const gl::Target& target) {
  renderTexture(world);
  target.bind();
  PipelineState{.depthTest = true}.apply();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.52f, 0.6f, 0.7f, 1.0f));
  m_texture.bind(m_options.view == PlanarView::Texture ? 0 : 1);
  m_sampler.bind(m_options.view == PlanarView::Texture ? 0 : 1);
  if (m_options.view == PlanarView::Texture) {
    m_show.draw();
  } else {
    m_sceneProgram.set("uPlanarTexMatrix", m_textureMatrix);
    m_scene.draw(world, camera, m_options.view == PlanarView::Visibility ? LightTerms::Visibility : LightTerms::Full,
                 m_sceneProgram);
  }
  gl::Sampler::unbind(0);
  gl::Sampler::unbind(1);
  PipelineState{.depthTest = true}.apply();
}

std::string PlanarShadow::describe() const {
  return fmt::format("planar shadow texture {0}x{0} (RGBA8) over the ground, casters flattened by the planar "
                     "projection matrix",
                     m_options.size);
}

}  // namespace glint::render::shadows
