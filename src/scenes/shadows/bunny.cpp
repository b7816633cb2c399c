// shadows/bunny — shadow volumes on real meshes: the Stanford bunny (the npm package
// `bunny`, fetched by scripts/setup), closed as shipped or with its base cut open
// like the original scan, beside a non-manifold "pinwheel" of three fins.
#include "common.h"

#include "glint/mesh/adjacency.h"
#include "glint/render/shadows/shadow_map.h"
#include "glint/render/shadows/stencil_shadows.h"

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint::scenes {
namespace shadows {
namespace {

using glint::shadows::CasterMode;
using sh::StencilCounting;
using sh::VolumeConstruction;

struct BunnyVariant {
  const char* name;
  const char* description;
  bool openBase;
  sh::StencilShadowOptions options;
  bool shadowMap = false;
};

const BunnyVariant kVariants[] = {
    {"closed", "The bunny as the npm package ships it (a closed 2-manifold): z-fail, CPU silhouettes.", false,
     {.counting = StencilCounting::TwoSidedZFail}},
    {"open", "The base cut open (holes, like the scan) and the non-manifold pinwheel: robust two-sided casters "
             "(every triangle occludes, silhouettes by edge multiplicity) — no leaks, no streaks.",
     true, {.counting = StencilCounting::TwoSidedZFail}},
    {"open-gpu", "The same open meshes with GPU extrusion: a closed thin shell (each face and its reversed copy) "
                 "joined along open and non-manifold edges.",
     true, {.counting = StencilCounting::TwoSidedZFail, .construction = VolumeConstruction::Gpu}},
    {"naive", "What goes wrong: textbook silhouettes (manifold edges between lit and unlit faces only) on the "
              "open meshes leave the volume unclosed, and shadows leak and streak.",
     true, {.counting = StencilCounting::TwoSidedZFail, .casters = CasterMode::Naive}},
    {"wireframe", "The open bunny's volume (two-sided casters) as wireframe.", true,
     {.counting = StencilCounting::TwoSidedZFail, .view = sh::VolumeView::Wireframe}},
    {"map", "The open bunny with a shadow map (3×3 PCF) for comparison: holes do not matter to depth maps.", true,
     {}, true},
};

class BunnyScene final : public Scene {
public:
  explicit BunnyScene(const BunnyVariant& v) : m_world(glint::shadows::makeBunnyWorld(glint::shadows::loadBunny(), v.openBase)) {
    if (v.shadowMap) m_map.emplace(m_world, sh::ShadowMapOptions{});
    else m_volumes.emplace(m_world, v.options);
    m_light.position = m_world.lightPosition;
    const EdgeMap edges = EdgeMap::build(m_world.objects[1].mesh);
    m_topology = fmt::format("bunny: {} triangles, {} open edges in {} holes, {} non-manifold",
                             m_world.objects[1].mesh.triangleCount(), edges.count(EdgeKind::Open), edges.borderLoops(),
                             edges.count(EdgeKind::NonManifold));
  }
  void render(const FrameInput& frame) override {
    m_world.lightPosition = m_light.position;
    glint::Camera camera = frame.camera(glint::shadows::sceneCamera(SceneView::Bunny, aspectOf(frame)));
    if (m_map) {
      m_map->render(m_world, camera, frame.target);
      return;
    }
    if (sh::StencilShadows::needsInfiniteFar(m_volumes->options()))
      camera.projection = sh::infiniteFarProjection(camera.projection);
    m_volumes->render(m_world, camera, frame.target);
  }
  std::vector<Option> options() override {
    std::vector<Option> out;
    m_light.add(out);
    return out;
  }
  std::string notes() const override {
    return m_topology + "; " + (m_map ? m_map->describe() : m_volumes->describe());
  }

private:
  glint::shadows::World m_world;
  std::optional<sh::StencilShadows> m_volumes;
  std::optional<sh::ShadowMap> m_map;
  LightOptions m_light;
  std::string m_topology;
};

}  // namespace
}  // namespace shadows

void registerShadowBunny(Registry& registry) {
  using namespace shadows;
  SceneDesc desc{.name = "shadows/bunny",
                 .summary = "Stencil shadow volumes on real, imperfect meshes: the Stanford bunny (closed, and cut "
                            "open) and a non-manifold pinwheel, with the robust two-sided method vs the naive one.",
                 .defaultSize = {640, 400}};
  for (const auto& v : kVariants) desc.variants.push_back({v.name, v.description});
  desc.create = [](int i) -> std::unique_ptr<Scene> { return std::make_unique<BunnyScene>(kVariants[i]); };
  registry.add(std::move(desc));
}

}  // namespace glint::scenes
