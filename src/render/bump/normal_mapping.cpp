#include "glint/render/bump/normal_mapping.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <string>
#include <vector>

namespace glint::render::bump {

NormalMapping::NormalMapping(const NormalMappingOptions& options) : m_options(options) {
  const int source = options.normal == ShadingNormal::TangentMap ? 1 : options.normal == ShadingNormal::ObjectMap ? 2 : 0;
  std::vector<std::string> defines{"NORMAL_SOURCE " + std::to_string(source)};
  if (options.directX) defines.emplace_back("DIRECTX");
  if (options.output == NormalMappingOutput::WorldNormal) defines.emplace_back("OUTPUT_NORMAL");
  m_program = gl::Program::fromFiles({"bump/normal_map.vert", "bump/normal_map.frag"}, defines);
  m_program.label("normal-mapping");
}

void NormalMapping::draw(const GpuMesh& mesh, const mat4& model, const Camera& camera,
                         std::span<const DirectionalLight> lights, const NormalMappingMaterial& material,
                         const gl::Texture* normalMap) const {
  draw(mesh, model, camera, lights, {}, material, normalMap);
}

void NormalMapping::draw(const GpuMesh& mesh, const mat4& model, const Camera& camera,
                         std::span<const DirectionalLight> lights, std::span<const PointLight> pointLights,
                         const NormalMappingMaterial& material, const gl::Texture* normalMap) const {
  const bool usesMap = m_options.normal != ShadingNormal::Vertex;
  if (usesMap && !normalMap) fail(ErrorKind::Internal, "NormalMapping: this variant needs a normal map");
  if (lights.size() > std::size_t(kMaxLights) || pointLights.size() > std::size_t(kMaxLights)) {
    fail(ErrorKind::Internal, "NormalMapping: {} + {} point lights, at most {} of each", lights.size(),
         pointLights.size(), kMaxLights);
  }
  const mat3 linear(model);
  m_program.set("uModel", model);
  m_program.set("uNormalMatrix", glm::transpose(glm::inverse(linear)));
  m_program.set("uViewProj", camera.viewProjection());
  m_program.set("uMirror", glm::determinant(linear) < 0.0f ? -1.0f : 1.0f);
  m_program.set("uEye", camera.position);
  m_program.set("uLightCount", int(lights.size()));
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const float len = glm::length(lights[i].direction);
    m_program.set("uLightDirection[" + std::to_string(i) + "]", len > 0.0f ? lights[i].direction / len : vec3(0.0f));
    m_program.set("uLightColor[" + std::to_string(i) + "]", lights[i].color);
  }
  m_program.set("uPointCount", int(pointLights.size()));
  for (std::size_t i = 0; i < pointLights.size(); ++i) {
    const std::string index = "[" + std::to_string(i) + "]";
    m_program.set("uPointPosition" + index, pointLights[i].position);
    m_program.set("uPointColor" + index, pointLights[i].color);
    m_program.set("uPointRange" + index, pointLights[i].range);
  }
  m_program.set("uHasAlbedoMap", material.albedoMap != nullptr);
  if (material.albedoMap) {
    gl::Sampler::unbind(1);
    material.albedoMap->bind(1);
  }
  m_program.set("uAlbedo", material.albedo);
  m_program.set("uAmbient", material.ambient);
  m_program.set("uSpecular", material.specular);
  m_program.set("uShininess", material.shininess);

  PipelineState{.depthTest = true, .cull = true}.apply();
  if (usesMap) {
    gl::Sampler::unbind(0);
    normalMap->bind(0);
  }
  m_program.use();
  mesh.draw();
  if (usesMap) glBindTextureUnit(0, 0);
  if (material.albedoMap) glBindTextureUnit(1, 0);
}

NormalMapView::NormalMapView() : m_pass("bump/show_map.frag") {}

void NormalMapView::draw(const gl::Texture& map) const {
  gl::Sampler::unbind(0);
  map.bind(0);
  m_pass.draw();
  glBindTextureUnit(0, 0);
}

}  // namespace glint::render::bump
