// shadows/map, shadows/map-pcf, shadows/planar — the two image-space shadow methods
// of the VGP353 lecture and the OpenGL III lecture on the WWDC 2001 talk's demo world.
#include "common.h"

#include "glint/render/shadows/planar.h"
#include "glint/render/shadows/shadow_map.h"

#include <memory>
#include <string>
#include <vector>

namespace glint::scenes {
namespace shadows {
namespace {

using sh::ShadowMapOptions;
using sh::ShadowMapView;

struct MapVariant {
  const char* name;
  const char* description;
  ShadowMapOptions options;
};

class MapScene final : public Scene {
public:
  explicit MapScene(const MapVariant& v) : m_world(glint::shadows::makeDemoWorld()), m_map(m_world, v.options) {
    m_light.position = m_world.lightPosition;
  }
  void render(const FrameInput& frame) override {
    glint::shadows::animateDemoWorld(m_world, frame.time);
    m_world.lightPosition = m_light.position;
    const glint::Camera eye = glint::shadows::sceneCamera(SceneView::Demo, aspectOf(frame));
    // The light's own views (light-view, light-depth) do not look through the eye: no camera to move.
    const sh::ShadowMapView view = m_map.options().view;
    const bool fromLight = view == sh::ShadowMapView::LightView || view == sh::ShadowMapView::LightDepth;
    m_map.render(m_world, fromLight ? eye : frame.camera(eye), frame.target);
  }
  std::vector<Option> options() override {
    std::vector<Option> out;
    m_light.add(out);
    auto& o = m_map.options();
    out.push_back({"pcf-radius", "PCF taps: (2r+1)² hardware-filtered comparisons", &o.pcfRadius, 0.0f, 4.0f});
    out.push_back({"slope-bias", "slope-scaled depth bias (polygon offset factor) of the map pass", &o.offsetFactor, 0.0f, 8.0f});
    out.push_back({"constant-bias", "constant depth bias (polygon offset units) of the map pass", &o.offsetUnits, 0.0f,
                   2000000.0f});
    out.push_back({"receiver-plane", "PCF taps compare with the receiver's plane at each tap (0: acne as the radius "
                   "grows)", &o.receiverPlaneBias});
    return out;
  }
  std::string notes() const override { return m_map.describe(); }

private:
  glint::shadows::World m_world;
  sh::ShadowMap m_map;
  LightOptions m_light;
};

void addMaps(Registry& registry, const char* name, const char* summary, std::vector<MapVariant> variants) {
  SceneDesc desc{.name = name, .summary = summary};
  for (const auto& v : variants) desc.variants.push_back({v.name, v.description});
  desc.create = [variants](int i) -> std::unique_ptr<Scene> { return std::make_unique<MapScene>(variants[std::size_t(i)]); };
  registry.add(std::move(desc));
}

class PlanarScene final : public Scene {
public:
  explicit PlanarScene(sh::PlanarView view) : m_world(glint::shadows::makeDemoWorld()), m_planar(m_world, {.view = view}) {
    m_light.position = m_world.lightPosition;
  }
  void render(const FrameInput& frame) override {
    glint::shadows::animateDemoWorld(m_world, frame.time);
    m_world.lightPosition = m_light.position;
    const glint::Camera eye = glint::shadows::sceneCamera(SceneView::Demo, aspectOf(frame));
    const bool texture = m_planar.options().view == sh::PlanarView::Texture;  // the texture alone: a 2D view
    m_planar.render(m_world, texture ? eye : frame.camera(eye), frame.target);
  }
  std::vector<Option> options() override {
    std::vector<Option> out;
    m_light.add(out);
    return out;
  }
  std::string notes() const override { return m_planar.describe(); }

private:
  glint::shadows::World m_world;
  sh::PlanarShadow m_planar;
  LightOptions m_light;
};

}  // namespace
}  // namespace shadows

void registerShadowMaps(Registry& registry) {
  using namespace shadows;
  addMaps(registry, "shadows/map",
          "Shadow maps (the OpenGL III lecture, \"Depth buffers also useful for shadow generation\"): the scene's depth seen "
          "from the light, in a depth texture through an FBO, compared per pixel — the lecture's five pictures.",
          {
              {"without", "Without shadows: the scene lit by the point light, no visibility term.",
               {.view = ShadowMapView::WithoutShadows}},
              {"light-view", "Light's view: the scene from the light's position, the frustum the map is drawn with.",
               {.view = ShadowMapView::LightView}},
              {"light-depth", "Light's view depth: the shadow map itself (linearised; near black, far white).",
               {.view = ShadowMapView::LightDepth}},
              {"projected", "Projected shadow map: the stored depths cast onto the scene from the light like a "
                            "slide; where a surface is farther than its texel says, it is in shadow.",
               {.view = ShadowMapView::Projected}},
              {"with", "With shadows: each pixel's light-space depth compared with the map (sampler2DShadow, "
                       "3×3 hardware-filtered PCF, slope-scaled and receiver-plane bias).",
               {.view = ShadowMapView::WithShadows}},
          });
  addMaps(registry, "shadows/map-pcf",
          "Shadow-map filtering and bias: hardware comparison, percentage-closer filtering, and the acne / "
          "peter-panning trade-off of depth bias.",
          {
              {"nearest", "One tap, GL_NEAREST comparison: hard, stair-stepped texel edges.",
               {.size = 512, .pcfRadius = 0, .hardwareFilter = false}},
              {"hardware", "One tap, GL_LINEAR comparison: the hardware blends 2×2 comparisons (bilinear PCF).",
               {.size = 512, .pcfRadius = 0}},
              {"pcf5x5", "5×5 hardware-filtered taps, each compared with the receiver's plane where it reads "
                         "(receiver-plane bias): soft, smooth edges and clean lit surfaces.",
               {.size = 512, .pcfRadius = 2}},
              {"no-bias", "No bias: surfaces shadow themselves in moiré bands (shadow acne).",
               {.pcfRadius = 0, .offsetFactor = 0.0f, .offsetUnits = 0.0f}},
              {"constant-bias", "A large constant bias only (polygon offset units 1,000,000: about 0.7 units along "
                                "the light's rays at the sphere): the acne is gone, but every stored depth moves "
                                "back alike, so the sphere's shadow shrinks to a spot detached from it (peter "
                                "panning).",
               {.pcfRadius = 0, .offsetFactor = 0.0f, .offsetUnits = 1000000.0f}},
              {"slope-bias", "Slope-scaled bias (glPolygonOffset factor 2, units 2): bias only where the surface is "
                             "steep to the light — no acne, shadows stay attached.",
               {.pcfRadius = 0}},
          });
  SceneDesc planar{
      .name = "shadows/planar",
      .summary = "Planar projected shadows rendered into a texture (the VGP353 lecture's first method): casters flattened "
                 "onto the ground from the light into an FBO texture, which the ground looks up.",
      .variants = {{"applied", "The ground darkened through the shadow texture; casters do not shadow each other "
                               "(the sphere is lit under the slab)."},
                   {"texture", "The shadow texture itself: the ground from above, casters' projections in black."}},
  };
  planar.create = [](int variant) -> std::unique_ptr<Scene> {
    return std::make_unique<PlanarScene>(variant == 0 ? sh::PlanarView::Applied : sh::PlanarView::Texture);
  };
  registry.add(std::move(planar));
}

}  // namespace glint::scenes
