// bake/result — the normal mapper's result (WWDC 2003 session 212, ATI's car-paint demo split screen):
// a studded torus of 262k triangles baked onto a 1,152-triangle torus. Four panels:
//   top left      the low poly with its own vertex normals
//   top right     the low poly with the baked tangent-space map (render::bump::NormalMapping)
//   bottom left   the high poly, its own normals
//   bottom right  the baked map itself
// The map is baked on the CPU (glint_bake, Embree) when the scene is created, so what is
// shown is exactly what `glint bake` would write for these meshes.
#include "glint/bake/baker.h"
#include "glint/bake/samples.h"
#include "glint/render/bump/textures.h"
#include "glint/core/camera.h"
#include "glint/render/bump/normal_mapping.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace glint::scenes {
namespace {

const vec4 kBackground{0.16f, 0.17f, 0.2f, 1.0f};

class BakeResultScene final : public Scene {
public:
  explicit BakeResultScene(bool detail)
      : m_vertexNormals({.normal = render::bump::ShadingNormal::Vertex}),
        m_mapped({.normal = render::bump::ShadingNormal::TangentMap}) {
    const Mesh low = makeTorus(1.0f, 0.35f, 48, 12);
    const Mesh high = bake::makeStuddedTorus({.segments = 512, .sides = 256});
    bake::BakeOptions options;
    options.width = 768;
    options.height = 384;
    options.samples = 4;
    options.progress = false;
    if (detail) options.detail = bake::HeightDetail{bake::makeScratchesAndPores(256), 6.0f};
    const auto start = std::chrono::steady_clock::now();
    const bake::BakeResult baked = bake::bake(low, high, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m_notes = fmt::format("{} → {} triangles; {}×{} map, {} samples per texel, {} rays, hit ratio {:.4f}, baked in "
                          "{:.2f} s", high.triangleCount(), low.triangleCount(), options.width, options.height,
                          options.samples, baked.stats.rays, baked.stats.hitRatio(), seconds);
    m_low = render::GpuMesh(baked.low, {}, "bake-low");
    m_high = render::GpuMesh(high, {}, "bake-high");
    m_map = render::bump::uploadImage(baked.normal, {.label = "baked-normal-map"});
  }

  std::vector<Option> options() override {
    return {{"spin", "turns per minute", &m_spin, 0.0f, 20.0f}, {"elevation", "camera elevation (radians)", &m_elevation, -1.2f, 1.2f}};
  }

  std::string notes() const override { return m_notes; }

  void render(const FrameInput& frame) override {
    frame.target.bind();
    render::PipelineState{.depthTest = true}.apply();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.05f, 0.05f, 0.06f, 1.0f));
    const int gap = std::max(1, frame.target.size.x / 320);
    // Four panels in reading order: low poly, low poly + map / high poly, the map.
    const auto panel = [&](int column, int row) {
      const gl::Target cell = frame.target.cell(column, row, 2, 2, gap);
      cell.bind();
      render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, kBackground);
      return cell;
    };
    const auto camera = frame.camera(glint::Camera::orbit(vec3(0.0f), 3.1f, 0.0f, m_elevation, 38.0f, frame.target.cell(0, 0, 2, 2, gap).aspect()));
    const float angle = float(frame.time) * m_spin / 60.0f * 2.0f * kPi + 0.4f;
    const mat4 model = glm::rotate(glm::rotate(mat4(1.0f), 0.35f, vec3(1, 0, 0)), angle, vec3(0, 1, 0));
    const render::bump::DirectionalLight lights[] = {{.direction = {0.5f, 0.8f, 0.6f}, .color = vec3(0.9f, 0.88f, 0.82f)},
                                               {.direction = {-0.8f, 0.1f, -0.3f}, .color = vec3(0.15f, 0.2f, 0.3f)}};
    const render::bump::NormalMappingMaterial material{.albedo = vec3(0.75f, 0.72f, 0.68f), .specular = 0.35f, .shininess = 40.0f};

    panel(0, 0);
    m_vertexNormals.draw(m_low, model, camera, lights, material);
    panel(1, 0);
    m_mapped.draw(m_low, model, camera, lights, material, &m_map);
    panel(0, 1);
    m_vertexNormals.draw(m_high, model, camera, lights, material);
    panel(1, 1);
    m_view.draw(m_map);
    frame.target.bind();
    render::PipelineState{.depthTest = true}.apply();
  }

private:
  render::bump::NormalMapping m_vertexNormals;
  render::bump::NormalMapping m_mapped;
  render::bump::NormalMapView m_view;
  render::GpuMesh m_low;
  render::GpuMesh m_high;
  gl::Texture m_map;
  std::string m_notes;
  float m_spin = 4.0f;
  float m_elevation = 0.45f;
};

}  // namespace

void registerBakeResult(Registry& registry) {
  registry.add({.name = "bake/result",
                .summary = "The normal mapper (WWDC 2003 session 212): a 262k-triangle studded torus baked onto a 1,152-triangle "
                           "one. Top: low poly without / with the baked map; bottom: high poly / the map.",
                .variants = {{"studs", "studs and a groove from the high poly alone: the smooth ray-cast shape"},
                             {"detail", "plus painted micro detail (pores, scratches) combined from a height map"}},
                .defaultSize = {960, 540},
                .defaultTime = 1.0,
                .create = [](int variant) -> std::unique_ptr<Scene> {
                  return std::make_unique<BakeResultScene>(variant == 1);
                }});
}

}  // namespace glint::scenes
