// env/bubble — a dynamic cube map: the bubble with local scenery (the WWDC 2001 talk: "the NVIDIA
// Bubble demo, modified with local scenery"). Every frame the small animated scene around
// the bubble is rendered into the six faces of a cube map through a framebuffer object,
// then the bubble reflects it with a Fresnel-weighted blend.
#include "env_common.h"

#include "glint/gl/shader.h"
#include "glint/render/env/dynamic_cube.h"
#include "glint/render/env/reflection.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace glint::scenes {
namespace {
using namespace env;

constexpr int kDynamicSize = 128;  // per face: the bubble is small on screen
constexpr float kBubbleRadius = 1.0f;

struct LocalObject {
  Mesh mesh;
  vec3 color;
  float orbitRadius, orbitSpeed, phase, height, spin;
  float stripes;
};

std::vector<LocalObject> localScenery() {
  return {
      {makeTorus(0.38f, 0.13f, 48, 24), {0.95f, 0.25f, 0.2f}, 2.2f, 0.6f, 2.2f, 0.35f, 1.3f, 8.0f},
      {makeCube(0.55f), {0.25f, 0.8f, 0.3f}, 2.5f, 0.6f, 3.8f, -0.3f, 0.9f, 2.0f},
      {makeUvSphere(0.32f, 32, 16), {0.25f, 0.45f, 0.95f}, 2.3f, 0.6f, 5.3f, 0.6f, 0.0f, 6.0f},
      {makeCube(0.45f), {0.95f, 0.8f, 0.2f}, 2.6f, 0.6f, 0.9f, -0.1f, -1.1f, 2.0f},
      // A slowly turning ring below the bubble, so the bottom of the reflection has scenery too.
      {makeTorus(2.0f, 0.08f, 96, 12), {0.85f, 0.85f, 0.9f}, 0.0f, 0.0f, 0.0f, -1.35f, 0.25f, 24.0f},
  };
}

class BubbleScene final : public Scene {
public:
  enum class Show { Fresnel, Mirror, Faces };
  explicit BubbleScene(Show show)
      : m_show(show),
        m_environment(loadEnvironmentCube()),
        m_local(kDynamicSize, "bubble-local-cube"),
        m_bubble({.fresnel = show != Show::Mirror}),
        m_sphere(makeUvSphere(1.0f, 96, 48), {}, "bubble"),
        m_program(gl::Program::fromFiles({"env/local.vert", "env/local.frag"})),
        m_objects(localScenery()) {
    for (const auto& o : m_objects) m_meshes.emplace_back(o.mesh, std::span<const vec4>{}, "local-scenery");
  }

  std::vector<Option> options() override {
    return {{"f0", "Fresnel reflectance at normal incidence", &m_bubble.options().f0, 0.0f, 1.0f},
            {"wobble", "bubble wobble amplitude (fraction of the radius)", &m_bubble.options().wobble, 0.0f, 0.2f}};
  }

  void render(const FrameInput& frame) override {
    const float t = float(frame.time);
    // 1. The local scenery seen from the bubble's centre, into the six faces.
    m_local.render(vec3(0.0f), [&](const glint::Camera& face) { drawSurroundings(face, t); });
    // 2. The frame: the same surroundings, then the bubble reflecting them.
    frame.target.bind();
    render::PipelineState{.depthTest = true}.apply();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    if (m_show == Show::Faces) {
      m_cross.draw(m_local.texture(), frame.target.size);
      return;
    }
    const ivec2 size = frame.target.size;
    const auto camera = frame.camera(glint::Camera::orbit(vec3(0.0f), 5.0f, 0.35f + 0.1f * t, 0.2f, 45.0f,
                                                           float(size.x) / float(size.y)));
    drawSurroundings(camera, t);
    m_bubble.draw(m_sphere, glm::scale(mat4(1.0f), vec3(kBubbleRadius)), camera, m_local.texture(), t);
  }

  std::string notes() const override {
    return fmt::format(
        "Each frame the scenery is drawn six times into a {0}² cube map (one framebuffer-object pass per face, "
        "shared depth renderbuffer, then glGenerateMipmap), from the bubble's centre. {1}",
        kDynamicSize,
        m_show == Show::Fresnel
            ? fmt::format("Fresnel blend (Schlick, F0 = {:.2f}): faint face-on, mirror-bright at the rim.",
                          m_bubble.options().f0)
            : m_show == Show::Mirror ? "F = 1: an opaque mirror ball, to show the cube map's content."
                                     : "The six dynamic faces as a cross (layout as env/faces).");
  }

private:
  void drawSurroundings(const glint::Camera& camera, float t) {
    m_sky.draw(m_environment, camera);
    render::PipelineState{.depthTest = true, .cull = true}.apply();
    m_program.use();
    m_program.set("uViewProj", camera.viewProjection());
    for (std::size_t i = 0; i < m_objects.size(); ++i) {
      const LocalObject& o = m_objects[i];
      const float a = o.phase + o.orbitSpeed * t;
      const vec3 position{o.orbitRadius * std::sin(a), o.height + 0.15f * std::sin(1.7f * t + o.phase),
                          o.orbitRadius * std::cos(a)};
      mat4 model = glm::translate(mat4(1.0f), position);
      model = glm::rotate(model, o.spin * t + o.phase, glm::normalize(vec3(0.3f, 1.0f, 0.2f)));
      m_program.set("uModel", model);
      m_program.set("uNormalMatrix", glm::transpose(glm::inverse(mat3(model))));
      m_program.set("uColor", o.color);
      m_program.set("uStripes", o.stripes);
      m_meshes[i].draw();
    }
  }

  Show m_show;
  gl::Texture m_environment;
  render::env::DynamicCubeMap m_local;
  render::env::Skybox m_sky;
  render::env::Bubble m_bubble;
  render::env::CubeCrossView m_cross;
  render::GpuMesh m_sphere;
  gl::Program m_program;
  std::vector<LocalObject> m_objects;
  std::vector<render::GpuMesh> m_meshes;
};

}  // namespace

void registerEnvBubble(Registry& registry) {
  registry.add({.name = "env/bubble",
                .summary = "Dynamic cube map: local scenery rendered into a cube map every frame through a "
                           "framebuffer object and reflected by a bubble (the WWDC 2001 talk's bubble demo).",
                .variants = {{"fresnel", "a soap bubble: Fresnel-weighted reflection over what lies behind it"},
                             {"mirror", "the same bubble as an opaque mirror, to read the reflection plainly"},
                             {"faces", "this frame's six dynamic cube faces, unfolded as a cross"}},
                .defaultTime = 1.0,
                .create = [](int variant) -> std::unique_ptr<Scene> {
                  return std::make_unique<BubbleScene>(BubbleScene::Show(variant));
                }});
}

}  // namespace glint::scenes
