// water/height, water/normals, water/shaded — the VGP353 lecture's wave simulation: a spring network
// stepped on the GPU between two framebuffer textures, drops drawn in periodically, the
// height field turned into a normal map every frame, and water shaded with that normal map
// and a cube-map reflection.
#include "glint/core/log.h"
#include "glint/image/heightfield.h"
#include "glint/render/bump/height_to_normal.h"
#include "glint/render/bump/textures.h"
#include "glint/render/env/reflection.h"
#include "glint/render/state.h"
#include "glint/render/water/field_view.h"
#include "glint/render/water/water_surface.h"
#include "glint/render/water/wave_simulation.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint::scenes {
namespace {
using render::water::FieldKind;

enum class Show {
  Height,   ///< the height field as gray levels
  Normals,  ///< its normal map
  Shaded    ///< the water
};

struct WaterVariant {
  const char* name;
  const char* description;
  Show show;
  bool rain = true;          // false: a single drop at t = 0, no more
  float cameraElevation = 0.8f;  // radians above the water
  float cameraDistance = 1.7f;
  vec3 lookAt{0.0f, -0.05f, 0.1f};
  float springConstant = 3600.0f;  // 60 texels/s
};

constexpr int kGrid = 256;

class WaterScene final : public Scene {
public:
  explicit WaterScene(const WaterVariant& v)
      : m_variant(v), m_waves({kGrid, kGrid}, {}, rainFor(v)), m_normalMap(GL_TEXTURE_2D, "water-normal-map") {
    m_params = m_waves.params();
    m_params.springConstant = v.springConstant;
    m_rainInterval = m_waves.rain().interval;
    m_normalMap.storage(GL_RGBA8, kGrid, kGrid, 1, 0);  // mipmapped: the surface is seen at grazing angles
    m_normalMap.filtering(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
    if (v.show == Show::Shaded) {
      m_sky = render::water::skyEnvironment();
      m_skybox.emplace();
      m_surface.emplace();
      m_floor = render::bump::uploadImage(makePoolTiles(256, 8),
                                          {.label = "pool-floor"});
    } else {
      m_view.emplace();
    }
  }

  std::vector<Option> options() override {
    return {{"spring-constant", "k between neighbouring columns; waves travel sqrt(k/m) texels/s", &m_params.springConstant,
             100.0f, 20000.0f},
            {"mass", "m of one water column", &m_params.mass, 0.2f, 5.0f},
            {"damping", "velocity decay rate per second (waves die out)", &m_params.damping, 0.0f, 3.0f},
            {"time-step", "Δt of one simulation step, seconds (clamped to 95% of the stability limit)",
             &m_params.timeStep, 0.001f, 0.02f},
            {"rain-interval", "seconds between drops (0 = no more drops)", &m_rainInterval, 0.0f, 3.0f},
            {"bumpiness", "height → normal scale: how steep the waves look", &m_bumpiness, 0.5f, 20.0f},
            {"gain", "gray levels per unit of height (water/height)", &m_gain, 0.2f, 5.0f},
            {"spin", "camera turn rate around the pool, radians per second (water/shaded)", &m_spin, -1.0f, 1.0f}};
  }

  void render(const FrameInput& frame) override {
    applyOptions();
    // Steps of Δt up to the frame's time: the viewer's real frame time, or --time headless.
    m_waves.advanceTo(frame.time);
    m_normals.run(m_waves.state(), m_normalMap, {.scale = m_bumpiness});
    frame.target.bind();
    if (m_view) {
      if (m_variant.show == Show::Height) m_view->draw(m_waves.state(), FieldKind::Height, frame.target.size, m_gain);
      else m_view->draw(m_normalMap, FieldKind::NormalMap, frame.target.size);
      return;
    }
    render::PipelineState{.depthTest = true}.apply();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const ivec2 size = frame.target.size;
    const auto camera = frame.camera(glint::Camera::orbit(m_variant.lookAt, m_variant.cameraDistance,
                                                           0.35f + m_spin * float(frame.time), m_variant.cameraElevation,
                                                           45.0f, float(size.x) / float(size.y)));
    m_skybox->draw(m_sky.cube, camera);
    m_surface->draw(camera, m_waves.state(), m_normalMap, m_sky.cube, m_floor);
  }

  std::string notes() const override {
    const float limit = sim::stabilityLimit(m_waves.params());
    std::string s = fmt::format(
        "{}×{} spring network on the GPU (RG32F ping-pong: R height, G velocity), Δt = {:.4f} s ({:.0f}% of the "
        "stability limit {:.4f} s), {} steps so far, waves at {:.0f} texels/s; a drop every {:.2f} s. The normal map is "
        "rebuilt from the heights every frame (bump/height_to_normal, scale {:.1f}).",
        kGrid, kGrid, m_waves.params().timeStep, 100.0f * m_waves.params().timeStep / limit, limit, m_waves.steps(),
        std::sqrt(m_waves.params().springConstant / m_waves.params().mass), m_waves.rain().interval, m_bumpiness);
    if (m_variant.show == Show::Shaded) s += " Reflection: " + m_sky.source + ".";
    if (m_clamped) s += " The chosen time step was unstable and is clamped.";
    s += " Repeated frames at one time step nothing, so frame timings here exclude the simulation: `glint bench "
         "water` measures it.";
    return s;
  }

private:
  static sim::RainOptions rainFor(const WaterVariant& v) {
    sim::RainOptions rain;
    if (!v.rain) {
      rain.interval = 1e6f;  // one drop at step 0, the next one never comes
      rain.centreFirst = true;
    }
    return rain;
  }

  // Options are plain floats the viewer edits; keep them valid before they reach the simulation.
  void applyOptions() {
    sim::WaveParams p = m_params;
    p.mass = std::max(p.mass, 1e-3f);
    p.springConstant = std::max(p.springConstant, 0.0f);
    p.damping = std::max(p.damping, 0.0f);
    const float limit = 0.95f * sim::stabilityLimit(p);
    m_clamped = p.timeStep > limit;
    p.timeStep = std::clamp(p.timeStep, 1e-4f, limit);
    m_waves.params() = p;
    if (m_variant.rain) m_waves.rain().interval = m_rainInterval <= 0.0f ? 1e6f : m_rainInterval;
  }

  WaterVariant m_variant;
  render::water::WaveSimulation m_waves;
  render::bump::HeightToNormalPass m_normals;
  gl::Texture m_normalMap;
  sim::WaveParams m_params;
  float m_rainInterval;
  float m_bumpiness = 8.0f;
  float m_gain = 3.0f;
  float m_spin = 0.0f;
  bool m_clamped = false;
  std::optional<render::water::FieldView> m_view;
  render::water::SkyEnvironment m_sky;
  std::optional<render::env::Skybox> m_skybox;
  std::optional<render::water::WaterSurface> m_surface;
  gl::Texture m_floor;
};

const WaterVariant kHeight[] = {
    {"rain", "the simulated heights as gray levels: drops fall periodically, rings spread and reflect off the walls",
     Show::Height},
    {"one-drop", "a single drop in the middle at t = 0, slower waves (30 texels/s): one ring spreading towards the walls",
     Show::Height, false, 0.8f, 1.7f, {0.0f, -0.05f, 0.1f}, 900.0f},
};
const WaterVariant kNormals[] = {
    {"rain", "the normal map made from the heights every frame on the GPU (n, s, e, w neighbours)", Show::Normals},
    {"one-drop", "the normal map of a single spreading ring", Show::Normals, false, 0.8f, 1.7f, {0.0f, -0.05f, 0.1f},
     900.0f},
};
const WaterVariant kShaded[] = {
    {"pool", "water shaded with the normal map: Fresnel mix of the cube-map sky and the refracted pool floor",
     Show::Shaded},
    {"grazing", "a low view across the pool: at grazing angles Fresnel makes the water a mirror of the sky",
     Show::Shaded, true, 0.12f, 2.2f, {0.0f, 0.25f, -0.6f}},
};

template <std::size_t N>
void addScene(Registry& registry, const char* name, const char* summary, const WaterVariant (&variants)[N]) {
  SceneDesc desc{.name = name, .summary = summary, .defaultTime = 4.0};
  for (const auto& v : variants) desc.variants.push_back({v.name, v.description});
  desc.create = [&variants](int variant) -> std::unique_ptr<Scene> { return std::make_unique<WaterScene>(variants[variant]); };
  registry.add(std::move(desc));
}

}  // namespace

void registerWaterScenes(Registry& registry) {
  addScene(registry, "water/height",
           "Wave simulation as a spring network on the GPU: height and velocity in a float texture, stepped by a "
           "fragment shader between two framebuffers (the VGP353 lecture).",
           kHeight);
  addScene(registry, "water/normals",
           "The wave heights turned into a normal map every frame by the height → normal pass (the VGP353 lecture).", kNormals);
  addScene(registry, "water/shaded",
           "Water shaded with the simulated normal map: cube-map reflection, refraction, Fresnel (the VGP353 lecture).", kShaded);
}

}  // namespace glint::scenes
