// Shadow maps: depth from the light into a texture, compared per pixel.
#include "glint/render/shadows/shadow_map.h"

#include "glint/render/state.h"

#include <fmt/format.h>

#include <algorithm>
#include <span>
#include <string>

namespace glint::render::shadows {

namespace {
Bounds focusOf(const glint::shadows::World& world) { return shadowFocus(world); }
}  // namespace

ShadowMap::ShadowMap(const glint::shadows::World& world, const ShadowMapOptions& options)
    : m_options(options),
      m_focus(focusOf(world)),
      m_light(lightCamera(world, m_focus)),
      m_depth(GL_TEXTURE_2D, "shadow-map"),
      m_fbo(gl::Framebuffer::create("shadow-map")),
      m_compare(gl::Sampler::create("shadow-compare")),
      m_raw(gl::Sampler::create("shadow-raw")),
      m_depthProgram(gl::Program::fromFiles({"shadows/depth.vert", "shadows/depth.frag"})),
      m_scene(world),
      m_shadowedProgram(gl::Program::fromFiles({"shadows/scene.vert", "shadows/scene.frag"}, {"SHADOW_MAP"})),
      m_projectedProgram(
          gl::Program::fromFiles({"shadows/scene.vert", "shadows/scene.frag"}, {"SHADOW_MAP", "PROJECTED_MAP"})) {
  // 24-bit depth like the window's: the map stores what the light's depth test kept.
  m_depth.storage(GL_DEPTH_COMPONENT24, options.size, options.size);
  m_fbo.attach(GL_DEPTH_ATTACHMENT, m_depth);
  const GLenum none = GL_NONE;
  m_fbo.drawBuffers(std::span<const GLenum>(&none, 1));
  m_fbo.checkComplete();

  const GLint filter = options.hardwareFilter ? GL_LINEAR : GL_NEAREST;
  m_compare.parameter(GL_TEXTURE_MIN_FILTER, filter);
  m_compare.parameter(GL_TEXTURE_MAG_FILTER, filter);
  m_compare.parameter(GL_TEXTURE_WRAP_S, GLint(GL_CLAMP_TO_EDGE));
  m_compare.parameter(GL_TEXTURE_WRAP_T, GLint(GL_CLAMP_TO_EDGE));
  // Lit when the pixel's depth from the light ≤ the stored depth.
  m_compare.parameter(GL_TEXTURE_COMPARE_MODE, GLint(GL_COMPARE_REF_TO_TEXTURE));
  m_compare.parameter(GL_TEXTURE_COMPARE_FUNC, GLint(GL_LEQUAL));
  m_raw.parameter(GL_TEXTURE_MIN_FILTER, GLint(GL_NEAREST));
  m_raw.parameter(GL_TEXTURE_MAG_FILTER, GLint(GL_NEAREST));
  m_raw.parameter(GL_TEXTURE_COMPARE_MODE, GLint(GL_NONE));

  const float d = glm::length(world.lightPosition - m_focus.center()), r = 0.5f * m_focus.diagonal();
  m_lightNear = std::max(0.05f, d - r);
  m_lightFar = d + r;
  m_depthView = DepthView(true, m_lightNear, m_lightFar);
}

void ShadowMap::renderMap(const glint::shadows::World& world) {
  // Refit to where casters and their shadows are now (the demo sphere moves).
  m_focus = focusOf(world);
  m_light = lightCamera(world, m_focus);
  m_fbo.bind();
  glViewport(0, 0, m_options.size, m_options.size);
  PipelineState{.depthTest = true, .colorMask = {false, false, false, false},
                .polygonOffset = m_options.offsetFactor != 0.0f || m_options.offsetUnits != 0.0f,
                .offsetFactor = m_options.offsetFactor,
                .offsetUnits = m_options.offsetUnits}
      .apply();
  render::clear(GL_DEPTH_BUFFER_BIT);
  m_scene.drawGeometry(world, m_light.viewProjection(), m_depthProgram);
}

void ShadowMap::render(const glint::shadows::World& world, const Camera& camera, const gl::Target& target) {
  renderMap(world);
  target.bind();
  PipelineState{.depthTest = true}.apply();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.52f, 0.6f, 0.7f, 1.0f));
  const float aspect = float(target.size.x) / float(target.size.y);
  switch (m_options.view) {
    case ShadowMapView::WithoutShadows: m_scene.draw(world, camera, LightTerms::Full); break;
    case ShadowMapView::LightView: {
      // Same position and field of view as the map, at the picture's aspect.
      const Camera light = lightCamera(world, m_focus, aspect);
      m_scene.draw(world, light, LightTerms::Full);
      break;
    }
    case ShadowMapView::LightDepth: {
      // The map is square: show it square, centred.
      const int side = std::min(target.size.x, target.size.y);
      glViewport((target.size.x - side) / 2, (target.size.y - side) / 2, side, side);
      m_depthView.draw(m_depth);
      glViewport(0, 0, target.size.x, target.size.y);
      break;
    }
    case ShadowMapView::WithShadows:
    case ShadowMapView::Projected:
    case ShadowMapView::Visibility: {
      const bool projected = m_options.view == ShadowMapView::Projected;
      const gl::Program& program = projected ? m_projectedProgram : m_shadowedProgram;
      program.set("uLightViewProj", m_light.viewProjection());
      program.set("uPcfRadius", m_options.pcfRadius);
      program.set("uReceiverPlane", m_options.receiverPlaneBias);
      program.set("uLightNearFar", vec2(m_lightNear, m_lightFar));
      m_depth.bind(0);
      m_compare.bind(0);
      m_depth.bind(2);
      m_raw.bind(2);
      m_scene.draw(world, camera, m_options.view == ShadowMapView::Visibility ? LightTerms::Visibility : LightTerms::Full,
                   program);
      gl::Sampler::unbind(0);
      gl::Sampler::unbind(2);
      break;
    }
  }
  PipelineState{.depthTest = true}.apply();
}

std::string ShadowMap::describe() const {
  const int taps = (2 * m_options.pcfRadius + 1) * (2 * m_options.pcfRadius + 1);
  return fmt::format("shadow map {0}x{0} (DEPTH_COMPONENT24), {1} tap{2} of {3} comparison, bias: slope factor {4}, "
                     "units {5}{6}; light frustum near {7:.2f}, far {8:.2f}",
                     m_options.size, taps, taps > 1 ? "s" : "", m_options.hardwareFilter ? "2×2 linear" : "nearest",
                     m_options.offsetFactor, m_options.offsetUnits,
                     taps > 1 && m_options.receiverPlaneBias ? ", receiver plane per tap" : "", m_lightNear, m_lightFar);
}

}  // namespace glint::render::shadows
