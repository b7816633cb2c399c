#pragma once
// glint/render/shadows/world_renderer.h — a World on the GPU, drawn lit by its light.
//
// Contents
//   LightTerms      which lighting terms a pass writes (full, ambient, direct, visibility, dim alpha)
//   WorldRenderer   uploads every object once; draws them with the shared lighting shader
//   shadowCamera    a camera through which a frustum of the light sees the whole world
//
// Every shadow technique draws its scene through one WorldRenderer, so the lighting is
// the same everywhere and only the visibility term differs (shaders/shadows/scene.frag).
// Objects keep their own transforms (World::objects[i].transform), read at draw time,
// so an animated World needs no re-upload.
//
/// ```cpp
/// #include <glint/render/state.h>
/// namespace rs = glint::render::shadows;
/// glint::shadows::World world = glint::shadows::makeDemoWorld();  // GL-free (shadows/world.h)
/// const rs::WorldRenderer scene(world);  // with a current GL context
/// const glint::Camera camera = glint::shadows::sceneCamera(glint::shadows::SceneView::Demo, 16.0f / 9.0f);
/// glint::shadows::animateDemoWorld(world, 1.5);  // moves objects: no re-upload
/// glint::render::PipelineState{.depthTest = true}.apply();
/// scene.draw(world, camera, rs::LightTerms::Full);
/// ```

#include "glint/gl/shader.h"
#include "glint/core/camera.h"
#include "glint/render/gpu_mesh.h"
#include "glint/shadows/world.h"

#include <functional>
#include <string>
#include <vector>

namespace glint::render::shadows {

enum class LightTerms {
  Full,        ///< ambient + diffuse + specular, times the technique's visibility
  Ambient,     ///< ambient only: what a shadowed pixel keeps (first pass of the multi-pass method)
  Direct,      ///< diffuse + specular only, to be added on top where lit
  Visibility,  ///< the technique's visibility as gray (1 lit, 0 shadowed): masks for tests
  DimAlpha     ///< Full colour, and in alpha the factor ambient/full a shadow multiplies by (WWDC 2003 session 212)
};

class WorldRenderer {
public:
  WorldRenderer() = default;
  /// Uploads the objects of `world` (their meshes; transforms are read at draw time) and
  /// compiles shaders/shadows/scene.{vert,frag} with `defines` (SHADOW_MAP, PLANAR_SHADOW).
  explicit WorldRenderer(const glint::shadows::World& world, const std::vector<std::string>& defines = {});

  /// Draws every object with the current pipeline state and the renderer's program.
  void draw(const glint::shadows::World& world, const Camera& camera, LightTerms terms) const;
  /// The same with another program built from shaders/shadows/scene.vert (techniques that
  /// add a visibility term compile their own and set its extra uniforms first).
  void draw(const glint::shadows::World& world, const Camera& camera, LightTerms terms, const gl::Program& program) const;
  /// Positions only, with a caller's program that has uModel and uViewProj (depth passes,
  /// flat-coloured projections). `filter` picks objects (all when empty).
  void drawGeometry(const glint::shadows::World& world, const mat4& viewProj, const gl::Program& program,
                    const std::function<bool(const glint::shadows::WorldObject&)>& filter = {}) const;

  const GpuMesh& mesh(std::size_t object) const { return m_meshes.at(object); }
  const gl::Program& program() const { return m_program; }

private:
  std::vector<GpuMesh> m_meshes;
  gl::Program m_program;
};

/// What a light frustum must see for shadows: every caster and where its shadow falls
/// on the ground (its bounding box corners projected from the light onto y = groundHeight). Tighter
/// than World::bounds() when the ground is large, so shadow-map texels are smaller.
Bounds shadowFocus(const glint::shadows::World& world);

/// A perspective camera at the world's light looking at the centre of `focus`, with a
/// field of view just enclosing focus' bounding sphere (for shadow maps and the light's view).
Camera lightCamera(const glint::shadows::World& world, const Bounds& focus, float aspect = 1.0f);

/// `projection` with its far plane moved to infinity (Everitt & Kilgard's "tweaked"
/// infinite projection): points at infinity (w = 0) land at window depth 1 − ε/2, just in
/// front of a cleared 1.0, so z-fail's far caps are never clipped. `projection` must come
/// from glm::perspective.
mat4 infiniteFarProjection(const mat4& projection, float epsilon = 2.0e-6f);

}  // namespace glint::render::shadows
