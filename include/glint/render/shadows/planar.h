#pragma once
// glint/render/shadows/planar.h — planar projected shadows rendered into a texture
// (the VGP353 lecture's first method: "render planar shadows to a texture").
//
// Contents
//   planarShadowMatrix   the 4×4 matrix that flattens geometry onto a plane from a point light
//   PlanarView           the result on the ground, or the shadow texture itself
//   PlanarShadowOptions, PlanarShadow   the technique
//
// Every caster is drawn through planarShadowMatrix — squashed onto the ground plane
// along the light's rays — into an FBO colour texture that covers the ground seen
// from above: white where lit, black where some caster's projection lands. The ground
// then looks its texel up (world → texture coordinates) as its visibility.
// Overlapping casters simply draw black twice (no double darkening, unlike blending
// projected geometry straight into the frame), the texture can be filtered, and it is
// redrawn only when something moves. Only the ground receives these shadows; casters
// do not shadow each other (shadow maps and volumes do). Casters above the light would
// project "anti-shadows": they must lie between the light and the plane.

#include "glint/gl/objects.h"
#include "glint/gl/render_target.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/shadows/world_renderer.h"

#include <string>

namespace glint::render::shadows {

/// Projects points onto the plane dot(plane.xyz, p) + plane.w = 0 along rays from the
/// point light `light`: M = dot(plane, L)·I − L·planeᵀ with L = (light, 1).
mat4 planarShadowMatrix(vec4 plane, vec3 light);

enum class PlanarView {
  Applied,  ///< the scene, the ground darkened through the shadow texture
  Texture,    ///< the shadow texture itself, filling the picture (white lit, black shadow)
  Visibility  ///< the ground's visibility as gray (1 lit, 0 shadowed; other objects white) for tests
};

struct PlanarShadowOptions {
  int size = 1024;           ///< shadow texture width and height
  PlanarView view = PlanarView::Applied;
};

class PlanarShadow {
public:
  /// The texture covers the first ground object's bounds (World::objects with ground set).
  PlanarShadow(const glint::shadows::World& world, const PlanarShadowOptions& options);
  /// Draws the casters into the shadow texture, then the options' view into `target`.
  void render(const glint::shadows::World& world, const Camera& camera, const gl::Target& target);
  /// Only the first pass: the shadow texture.
  void renderTexture(const glint::shadows::World& world);
  const gl::Texture& texture() const { return m_texture; }
  /// World → shadow-texture coordinates (xy) for points on the ground.
  const mat4& textureMatrix() const { return m_textureMatrix; }
  PlanarShadowOptions& options() { return m_options; }
  std::string describe() const;

private:
  PlanarShadowOptions m_options;
  mat4 m_groundClip{1.0f};     // ground point → clip space of the texture pass
  mat4 m_textureMatrix{1.0f};  // ground point → texture coordinates
  gl::Texture m_texture;
  gl::Framebuffer m_fbo;
  gl::Sampler m_sampler;
  gl::Program m_projectProgram;
  gl::Program m_sceneProgram;  // scene.frag with PLANAR_SHADOW
  WorldRenderer m_scene;
  FullscreenPass m_show;
};

}  // namespace glint::render::shadows
