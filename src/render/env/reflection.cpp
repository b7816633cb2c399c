#include "glint/render/env/reflection.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <string>
#include <vector>

namespace glint::render::env {

Skybox::Skybox() : m_pass("env/skybox.frag") {}

void Skybox::draw(const gl::Texture& cube, const Camera& camera) const {
  // Rotation only: the sky is infinitely far away, so translation must not move it.
  const mat4 rotation = mat4(camera.rotation());
  m_pass.program().set("uInvViewProj", glm::inverse(camera.projection * rotation));
  PipelineState{.depthTest = false, .depthWrite = false, .seamlessCubeMap = true}.apply();
  cube.bind(0);
  m_pass.drawWithCurrentState();
  glBindTextureUnit(0, 0);
}

Reflector::Reflector(const ReflectorOptions& options) : m_options(options) {
  std::vector<std::string> defines;
  if (options.lookup == Lookup::SphereMap) defines.emplace_back("SPHERE_MAP");
  if (options.perVertex) defines.emplace_back("PER_VERTEX");
  m_program = gl::Program::fromFiles({"env/reflect.vert", "env/reflect.frag"}, defines);
}

void Reflector::draw(const GpuMesh& mesh, const mat4& model, const Camera& camera, const gl::Texture& environment,
                     const mat3& worldToSphereFrame, vec3 tint) const {
  const bool sphere = m_options.lookup == Lookup::SphereMap;
  if (sphere != (environment.target() == GL_TEXTURE_2D)) {
    fail(ErrorKind::Internal, "Reflector: a {} lookup needs a {} texture", sphere ? "sphere-map" : "cube-map",
         sphere ? "2D" : "cube");
  }
  // Eye → environment frame. A cube map lives in world space: undo the view rotation
  // (the classic path's texture matrix). A sphere map lives in its own frame.
  const mat3 eyeToWorld = glm::transpose(camera.rotation());
  const mat3 eyeToEnv = sphere ? worldToSphereFrame * eyeToWorld : eyeToWorld;
  m_program.set("uModel", model);
  m_program.set("uNormalMatrix", glm::transpose(glm::inverse(mat3(model))));
  m_program.set("uView", camera.view);
  m_program.set("uProj", camera.projection);
  m_program.set("uEyeToEnv", eyeToEnv);
  m_program.set("uTint", tint);
  PipelineState{.depthTest = true, .cull = true, .seamlessCubeMap = true}.apply();
  environment.bind(0);
  m_program.use();
  mesh.draw();
  glBindTextureUnit(0, 0);
}

Bubble::Bubble(const BubbleOptions& options)
    : m_options(options),
      m_program(gl::Program::fromFiles({"env/bubble.vert", "env/bubble.frag"},
                                       options.fresnel ? std::vector<std::string>{} : std::vector<std::string>{"MIRROR"})) {}

void Bubble::draw(const GpuMesh& sphere, const mat4& model, const Camera& camera, const gl::Texture& cube,
                  float time) const {
  m_program.set("uModel", model);
  m_program.set("uViewProj", camera.viewProjection());
  m_program.set("uEye", camera.position);
  m_program.set("uTime", time);
  m_program.set("uWobble", m_options.wobble);
  m_program.set("uF0", m_options.f0);
  // Premultiplied "over": the film adds F·reflection and lets (1 − F) of the background
  // through. Depth is tested but not written, so nothing behind is lost.
  PipelineState{.depthTest = true, .depthWrite = false,
                .cull = true,
                .blend = {.enabled = true, .src = GL_ONE, .dst = GL_ONE_MINUS_SRC_ALPHA},
                .seamlessCubeMap = true}
      .apply();
  cube.bind(0);
  m_program.use();
  sphere.draw();
  glBindTextureUnit(0, 0);
  PipelineState{.depthTest = true}.apply();
}

CubeCrossView::CubeCrossView() : m_pass("env/faces_cross.frag") {}

void CubeCrossView::draw(const gl::Texture& cube, ivec2 viewport) const {
  m_pass.program().set("uAspect", float(viewport.x) / float(viewport.y));
  cube.bind(0);
  m_pass.draw();
  glBindTextureUnit(0, 0);
}

SphereMapView::SphereMapView(bool hemispheres)
    : m_pass("env/sphere_map_view.frag", hemispheres ? std::vector<std::string>{"HEMISPHERES"} : std::vector<std::string>{}) {}

void SphereMapView::draw(const gl::Texture& sphereMap, ivec2 viewport) const {
  m_pass.program().set("uAspect", float(viewport.x) / float(viewport.y));
  sphereMap.bind(0);
  m_pass.draw();
  glBindTextureUnit(0, 0);
}

}  // namespace glint::render::env
