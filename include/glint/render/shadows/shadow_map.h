#pragma once
// glint/render/shadows/shadow_map.h — shadow maps: the light's view depth (the OpenGL III lecture,
// the VGP353 lecture's second method).
//
// Contents
//   ShadowMapView      the lecture's set of pictures: without/with shadows, light's view,
//                      light's view depth, projected shadow map; and a visibility mask
//   ShadowMapOptions   map size, PCF, hardware comparison filter, polygon-offset and receiver-plane bias
//   ShadowMap          the technique: depth from the light via an FBO, then the scene
//
// How it works: the scene's depth is drawn from the light into a depth texture (an
// FBO with only a depth attachment). Drawing the scene from the camera, each pixel is
// transformed into the light's clip space and its depth compared with the stored one
// by the texture unit (sampler2DShadow, GL_COMPARE_REF_TO_TEXTURE): nearer than what
// the light saw → lit. With GL_LINEAR the hardware blends the 2×2 nearest comparisons
// (a free 2×2 PCF); pcfRadius adds (2r+1)² taps for softer, less aliased edges.
//
// Bias: a surface compared against its own depth map is lit or shadowed by rounding
// ("shadow acne"). glPolygonOffset while drawing the map pushes stored depths back by
// offsetFactor × the surface's depth slope seen from the light (slope-scaled: grazing
// surfaces need more) + offsetUnits × the smallest depth step. That is sized for one
// tap, whose 2×2 texels lie within a texel of the pixel; the PCF taps further out are
// not biased more but compared with the receiver's own plane at each tap ("receiver
// plane depth bias", shaders/shadows/shadow_map.glsl), so a wider kernel needs no more
// offset and casts no more acne. Too much offset detaches shadows from their casters
// ("peter panning"); the map-pcf variants show both ends.

#include "glint/gl/objects.h"
#include "glint/gl/render_target.h"
#include "glint/render/depth_view.h"
#include "glint/render/shadows/world_renderer.h"

#include <string>

namespace glint::render::shadows {

enum class ShadowMapView {
  WithShadows,     ///< the scene lit through the shadow map
  WithoutShadows,  ///< the same scene without the shadow term
  LightView,       ///< the scene in colour from the light's position
  LightDepth,      ///< the shadow map itself: depth from the light, near black, far white (linearised)
  Projected,       ///< the map's depth projected onto the scene from the light, like a slide projector
  Visibility       ///< the shadow term as gray: white lit, black shadowed (tests)
};

struct ShadowMapOptions {
  int size = 2048;              ///< map width and height in texels
  int pcfRadius = 1;            ///< 0: one tap; r: (2r+1)² taps, each hardware-filtered
  bool hardwareFilter = true;   ///< GL_LINEAR comparison (2×2 PCF per tap) vs GL_NEAREST
  float offsetFactor = 2.0f;    ///< slope-scaled bias (glPolygonOffset factor)
  float offsetUnits = 2.0f;     ///< constant bias in depth steps (glPolygonOffset units)
  bool receiverPlaneBias = true;  ///< PCF taps compare with the receiver's plane at the tap (false: with
                                  ///< the pixel's own depth, which shows acne as the radius grows)
  ShadowMapView view = ShadowMapView::WithShadows;
};

class ShadowMap {
public:
  /// Creates the depth texture and FBO and compiles the passes. The light's frustum is
  /// fitted to `world`'s bounds (lightCamera()).
  ShadowMap(const glint::shadows::World& world, const ShadowMapOptions& options);

  /// Draws the map, then the options' view into `target`.
  void render(const glint::shadows::World& world, const Camera& camera, const gl::Target& target);
  /// Draws the light's view depth into the map (the first pass).
  void renderMap(const glint::shadows::World& world);

  const gl::Texture& depthTexture() const { return m_depth; }
  /// The light's camera of the last renderMap().
  const Camera& lightView() const { return m_light; }
  ShadowMapOptions& options() { return m_options; }
  const ShadowMapOptions& options() const { return m_options; }
  std::string describe() const;

private:
  ShadowMapOptions m_options;
  Bounds m_focus;
  Camera m_light;
  float m_lightNear = 0.1f, m_lightFar = 100.0f;
  gl::Texture m_depth;
  gl::Framebuffer m_fbo;
  gl::Sampler m_compare;  // sampler2DShadow
  gl::Sampler m_raw;      // plain depth reads (projected view)
  gl::Program m_depthProgram;
  WorldRenderer m_scene;            // meshes, and the plain program (no shadows, light's view)
  gl::Program m_shadowedProgram;    // scene.frag with SHADOW_MAP
  gl::Program m_projectedProgram;   // scene.frag with SHADOW_MAP and PROJECTED_MAP
  DepthView m_depthView;
};

}  // namespace glint::render::shadows
