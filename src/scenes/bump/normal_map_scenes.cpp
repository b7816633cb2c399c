// bump/normal-map, bump/object-space — modern normal mapping, what DOT3 bump mapping grew
// into: per-pixel tangent frames (MikkTSpace, the one tangent space of glint), diffuse and
// specular light from point lights, on real meshes with real normal maps — one made by
// `glint normalmap` from a height field, one baked by `glint bake` from a high-poly mesh —
// and the object-space alternative.
//
// The technique is render::bump::NormalMapping (render/bump/normal_mapping.h), shared with the baker's
// scenes; tangents come from mesh/tangents.h's generateTangents.
#include "bump_common.h"

#include "glint/bake/baker.h"
#include "glint/bake/samples.h"
#include "glint/mesh/tangents.h"
#include "glint/render/bump/light_marker.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/bump/normal_mapping.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint::scenes {
namespace {
using namespace bump;

enum class Model {
  Bricks,         ///< a torus with the brick normal map of `glint normalmap` and a brick albedo
  Baked,          ///< the low-poly torus with a map baked from the studded high poly
  VertexNormals,  ///< the same low poly with its own normals: what the map adds
  Maps            ///< the tangent-space and object-space maps themselves
};

struct NormalMapVariant {
  const char* name;
  const char* description;
  Model model;
  render::bump::ShadingNormal normal = render::bump::ShadingNormal::TangentMap;
};

// The baker's demo pair (as in bake/result, smaller map): bakes once per process and space.
const bake::BakeResult& bakedTorus(NormalSpace space) {
  static std::map<NormalSpace, bake::BakeResult> cache;
  auto it = cache.find(space);
  if (it == cache.end()) {
    bake::BakeOptions options;
    options.width = 512;
    options.height = 256;
    options.samples = 1;
    options.space = space;
    options.progress = false;
    it = cache.emplace(space, bake::bake(makeTorus(1.0f, 0.35f, 48, 12), bake::makeStuddedTorus({.segments = 384, .sides = 192}),
                                         options)).first;
  }
  return it->second;
}

// A torus with bricks: UVs scaled so bricks keep their shape around both circles, then
// MikkTSpace tangents for the scaled mapping.
Mesh brickTorus() {
  Mesh torus = makeTorus(1.0f, 0.42f, 96, 48);
  for (vec2& uv : torus.uvs) uv *= vec2(6.0f, 2.5f);
  generateTangents(torus);
  return torus;
}

constexpr std::array<vec3, 2> kLightColors{vec3(1.0f, 0.86f, 0.68f), vec3(0.45f, 0.6f, 1.0f)};

class NormalMapScene final : public Scene {
public:
  explicit NormalMapScene(const NormalMapVariant& v)
      : m_variant(v),
        m_shader({.normal = v.model == Model::VertexNormals ? render::bump::ShadingNormal::Vertex : v.normal}) {
    if (v.model == Model::Bricks) {
      m_mesh = render::GpuMesh(brickTorus(), {}, "brick-torus");
      m_map = render::bump::uploadImage(heightToNormalMap(makeBrickHeight(512), {.scale = kBrickBumpiness, .wrap = true}),
                                        {.label = "brick-normal-map"});
      m_albedo = render::bump::uploadImage(makeBrickAlbedo(512), {.label = "brick-albedo"});
      m_source = "normal map made by image/normalmap.h (as `glint normalmap bricks.png --scale 10 --wrap`) from a "
                 "procedural brick height field, 512²; torus of " + std::to_string(m_mesh.triangleCount()) + " triangles";
    } else {
      const bool object = v.normal == render::bump::ShadingNormal::ObjectMap;
      const bake::BakeResult& baked = bakedTorus(object ? NormalSpace::Object : NormalSpace::Tangent);
      m_mesh = render::GpuMesh(baked.low, {}, "baked-low");
      m_map = render::bump::uploadImage(baked.normal, {.label = "baked-normal-map"});
      if (v.model == Model::Maps) {
        m_otherMap = render::bump::uploadImage(bakedTorus(NormalSpace::Object).normal, {.label = "object-map"});
        m_map = render::bump::uploadImage(bakedTorus(NormalSpace::Tangent).normal, {.label = "tangent-map"});
      }
      m_source = fmt::format("{} map baked by glint's baker (`glint bake`) from the studded torus onto a {}-triangle "
                             "torus, 512×256", object ? "object-space" : "tangent-space", baked.low.triangleCount());
    }
  }

  std::vector<Option> options() override {
    return {{"light-speed", "radians per second of the lights around the model", &m_lightSpeed, -3.0f, 3.0f},
            {"specular", "Blinn-Phong highlight strength", &m_specular, 0.0f, 2.0f},
            {"shininess", "Blinn-Phong exponent", &m_shininess, 2.0f, 256.0f},
            {"spin", "model turns per minute", &m_spin, -20.0f, 20.0f},
            {"show-lights", "draw markers where the point lights are", &m_showLights}};
  }

  void render(const FrameInput& frame) override {
    frame.target.bind();
    render::PipelineState{.depthTest = true}.apply();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.05f, 0.06f, 0.08f, 1.0f));
    const ivec2 size = frame.target.size;
    if (m_variant.model == Model::Maps) {
      // Left: tangent space (mostly blue: normals near the surface's own); right: object
      // space (the colour follows the direction the surface faces).
      frame.target.column(0, 2).bind();
      m_view.draw(m_map);
      frame.target.column(1, 2).bind();
      m_view.draw(*m_otherMap);
      frame.target.bind();
      return;
    }
    const auto camera = frame.camera(glint::Camera::orbit({0.0f, 0.0f, 0.0f}, 3.3f, 0.0f, 0.55f, 40.0f, float(size.x) / float(size.y)));
    const float turn = 2.0f * kPi / 60.0f * m_spin * float(frame.time);
    const mat4 model = glm::rotate(glm::rotate(mat4(1.0f), turn, vec3(0, 1, 0)), glm::radians(25.0f), vec3(1, 0, 0));
    std::array<render::bump::PointLight, 2> lights;
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const float a = m_lightSpeed * float(frame.time) + float(i) * kPi;
      lights[i] = {.position = {2.0f * std::cos(a), i == 0 ? 1.3f : -0.4f, 2.0f * std::sin(a)},
                   .color = kLightColors[i] * (i == 0 ? 1.1f : 0.7f),
                   .range = 3.0f};
    }
    const render::bump::NormalMappingMaterial material{
        .albedo = m_albedo ? vec3(1.0f) : vec3(0.78f, 0.74f, 0.7f),
        .albedoMap = m_albedo ? &m_albedo : nullptr,
        .ambient = vec3(0.05f),
        .specular = m_specular,
        .shininess = m_shininess};
    m_shader.draw(m_mesh, model, camera, {}, lights, material, &m_map);
    if (m_showLights)
      for (std::size_t i = 0; i < lights.size(); ++i) m_marker.draw(camera, lights[i].position, kLightColors[i]);
  }

  std::string notes() const override {
    const char* how = m_variant.model == Model::VertexNormals ? "Vertex normals only (no map)"
                      : m_variant.normal == render::bump::ShadingNormal::ObjectMap
                          ? "Object-space normal map: n = normalize(normalMatrix · texel), no tangents needed"
                          : "Tangent-space normal map, MikkTSpace frame per pixel";
    return fmt::format("{}; {}. Two point lights (warm, cool), Lambert + Blinn-Phong.", how, m_source);
  }

private:
  NormalMapVariant m_variant;
  render::bump::NormalMapping m_shader;
  render::GpuMesh m_mesh;
  gl::Texture m_map;
  gl::Texture m_albedo;
  std::optional<gl::Texture> m_otherMap;
  render::bump::NormalMapView m_view;
  render::bump::LightMarker m_marker;
  std::string m_source;
  float m_lightSpeed = 0.6f, m_specular = 0.35f, m_shininess = 40.0f, m_spin = 0.0f;
  bool m_showLights = true;
};

const NormalMapVariant kTangent[] = {
    {"bricks", "a brick normal map from `glint normalmap` with its albedo on a torus: bevels and mortar catch both lights",
     Model::Bricks},
    {"baked", "the low-poly torus with a tangent-space map baked from the studded high poly: studs and groove from "
              "1,152 triangles",
     Model::Baked},
    {"vertex-normals", "the same low poly with its own vertex normals: the detail the map adds is gone",
     Model::VertexNormals},
};
const NormalMapVariant kObject[] = {
    {"baked", "the studded torus baked into an object-space map: the same picture as bump/normal-map/baked, no tangents",
     Model::Baked, render::bump::ShadingNormal::ObjectMap},
    {"maps", "the two baked maps: tangent space (left, mostly blue) and object space (right, colour = facing)",
     Model::Maps},
};

template <std::size_t N>
void addScene(Registry& registry, const char* name, const char* summary, const NormalMapVariant (&variants)[N]) {
  SceneDesc desc{.name = name, .summary = summary, .defaultTime = 2.0};
  for (const auto& v : variants) desc.variants.push_back({v.name, v.description});
  desc.create = [&variants](int variant) -> std::unique_ptr<Scene> { return std::make_unique<NormalMapScene>(variants[variant]); };
  registry.add(std::move(desc));
}

}  // namespace

void registerBumpNormalMap(Registry& registry) {
  addScene(registry, "bump/normal-map",
           "Tangent-space normal mapping (MikkTSpace tangents) with point lights, diffuse + specular, on real meshes "
           "with maps from `glint normalmap` and `glint bake` — DOT3 bump mapping grown up.",
           kTangent);
  addScene(registry, "bump/object-space",
           "Object-space normal mapping: the map stores normals in the model's frame, no tangent frame per pixel.",
           kObject);
}

}  // namespace glint::scenes
