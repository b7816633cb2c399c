#pragma once
// glint/render/env/reflection.h — drawing with environment maps (shader paths).
//
// Contents
//   Skybox          the environment behind everything, from a cube map
//   Reflector       mirror objects: cube map by reflection vector (GL_REFLECTION_MAP) or
//                   sphere map (GL_SPHERE_MAP), per pixel or per vertex like texgen
//   Bubble          a wobbling soap bubble: Fresnel-weighted reflection over what is behind
//   CubeCrossView   a cube map's six faces unfolded as a cross
//   SphereMapView   a sphere map as an image, optionally with its hemispheres marked
//
// Each class owns its program and sets every piece of state it draws with (depth,
// blending, culling, GL_TEXTURE_CUBE_MAP_SEAMLESS); environment textures are bound to
// unit 0. Construct them with a context current. The reflection maths is that of
// shaders/env/texgen.glsl: eye-space reflection vector r = u − 2n(n·u), rotated into the
// environment's frame.
//
/// ```cpp
/// #include <glint/render/env/environment.h>
/// namespace env = glint::render::env;
/// const glint::gl::Texture cube = env::cubeFromEquirect(env::loadEquirect(env::findEnvironment("courtyard")));
/// const glint::render::GpuMesh sphereMesh(glint::makeUvSphere());
/// const auto camera = glint::Camera::orbit({0, 0, 0}, 3.0f, 0.0f, 0.2f, 45.0f, 16.0f / 9.0f);
/// const env::Skybox sky;
/// const env::Reflector mirror({.lookup = env::Lookup::CubeMap});
/// sky.draw(cube, camera);
/// mirror.draw(sphereMesh, glint::mat4(1.0f), camera, cube);
/// ```

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/core/camera.h"
#include "glint/render/gpu_mesh.h"

namespace glint::render::env {

class Skybox {
public:
  Skybox();
  /// Fills the viewport with `cube` seen from the camera's orientation (depth test and
  /// writes off: draw it first).
  void draw(const gl::Texture& cube, const Camera& camera) const;

private:
  FullscreenPass m_pass;
};

enum class Lookup {
  CubeMap,   ///< samplerCube by the world-space reflection vector
  SphereMap  ///< sampler2D by GL_SPHERE_MAP's (s, t) of r in the sphere map's frame
};

struct ReflectorOptions {
  Lookup lookup = Lookup::CubeMap;
  bool perVertex = false;  ///< generate coordinates per vertex and interpolate, as glTexGen does
};

class Reflector {
public:
  Reflector() : Reflector(ReflectorOptions{}) {}
  explicit Reflector(const ReflectorOptions& options);

  /// Draws `mesh` (positions + normals) transformed by `model` as a perfect mirror tinted
  /// by `tint`. CubeMap: `environment` is a world-space cube map. SphereMap: a 2D sphere
  /// map made for the frame `worldToSphereFrame` (SphereMapOptions::worldToFrame); pass the
  /// camera's rotation() to reproduce GL_SPHERE_MAP exactly (a map made for this view).
  void draw(const GpuMesh& mesh, const mat4& model, const Camera& camera, const gl::Texture& environment,
            const mat3& worldToSphereFrame = mat3(1.0f), vec3 tint = vec3(1.0f)) const;
  const ReflectorOptions& options() const { return m_options; }

private:
  ReflectorOptions m_options;
  gl::Program m_program;
};

struct BubbleOptions {
  bool fresnel = true;   ///< false: F = 1, an opaque mirror ball
  float f0 = 0.06f;      ///< reflectance at normal incidence (water 0.02, soap film a little more)
  float wobble = 0.03f;  ///< radial wobble amplitude, fraction of the radius
};

class Bubble {
public:
  Bubble() : Bubble(BubbleOptions{}) {}
  explicit Bubble(const BubbleOptions& options);
  /// Draws `sphere` (a unit sphere mesh) placed by `model` (uniform scale + translation),
  /// blended over what is already in the framebuffer, reflecting `cube` (world space,
  /// rendered from the bubble's centre). `time` drives the wobble.
  void draw(const GpuMesh& sphere, const mat4& model, const Camera& camera, const gl::Texture& cube,
            float time) const;
  BubbleOptions& options() { return m_options; }
  const BubbleOptions& options() const { return m_options; }

private:
  BubbleOptions m_options;
  gl::Program m_program;
};

class CubeCrossView {
public:
  CubeCrossView();
  /// Fills the viewport (of size `viewport`) with the faces unfolded as a cross: −X, −Z
  /// (front), +X, +Z in a row, +Y above and −Y below the front, level 0, edges marked.
  void draw(const gl::Texture& cube, ivec2 viewport) const;

private:
  FullscreenPass m_pass;
};

class SphereMapView {
public:
  /// hemispheres: tint the front half green, the back half red, hatch the wasted corners.
  explicit SphereMapView(bool hemispheres = false);
  /// Draws `sphereMap` centred in the viewport at the largest square that fits.
  void draw(const gl::Texture& sphereMap, ivec2 viewport) const;

private:
  FullscreenPass m_pass;
};

}  // namespace glint::render::env
