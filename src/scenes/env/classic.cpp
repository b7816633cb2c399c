// env/classic — the env/cube and env/sphere pictures drawn with the 2001 fixed-function
// API that the WWDC 2001 talk shows: glTexGen(GL_REFLECTION_MAP) with GL_TEXTURE_CUBE_MAP, and
// glTexGen(GL_SPHERE_MAP). Needs a compatibility-profile context.
#include "env_common.h"

#include "glint/render/env/classic.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <memory>
#include <string>
#include <vector>

namespace glint::scenes {
namespace {
using namespace env;

struct ClassicVariant {
  const char* name;
  bool sphere;
  float azimuth;
  const char* description;
};

const ClassicVariant kVariants[] = {
    {"cube", false, 0.0f, "glTexGen(GL_REFLECTION_MAP) on S, T, R + GL_TEXTURE_CUBE_MAP; matches env/cube/front"},
    {"sphere", true, 0.0f, "glTexGen(GL_SPHERE_MAP) on S, T with the generated sphere map; matches env/sphere/front"},
    {"cube-back", false, kPi, "the cube map from behind: the texture matrix turns the reflection back to world space"},
    {"sphere-back", true, kPi,
     "GL_SPHERE_MAP from behind with the front view's map: texgen works in eye space, so the mirror still shows the "
     "front view's surroundings (a sphere map must be regenerated for each view)"},
};

class ClassicScene final : public Scene {
public:
  explicit ClassicScene(const ClassicVariant& v) : m_variant(v), m_cube(loadEnvironmentCube()) {
    for (auto& o : mirrorPair()) {
      m_meshes.emplace_back(o.mesh);
      m_models.push_back(o.model);
    }
    if (v.sphere) {
      m_sphereMap = render::env::sphereMapFromCube(m_cube, {.size = kSphereMapSize, .worldToFrame = sphereMapFrame({1, 1})});
    }
  }

  void render(const FrameInput& frame) override {
    frame.target.bind();
    render::PipelineState{.depthTest = true}.apply();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const glint::Camera camera = frame.camera(viewCamera(m_variant.azimuth, frame.target.size));
    m_classic.drawSkybox(m_cube, camera);
    for (std::size_t i = 0; i < m_meshes.size(); ++i) {
      if (m_variant.sphere) m_classic.drawSphereMapped(m_meshes[i], m_models[i], camera, m_sphereMap);
      else m_classic.drawCubeMapped(m_meshes[i], m_models[i], camera, m_cube);
    }
  }

  std::string notes() const override {
    return "Fixed-function texgen in a compatibility-profile context: per-vertex coordinates, interpolated. "
           "tests/env/classic_test compares it with the shader path.";
  }

private:
  ClassicVariant m_variant;
  render::env::ClassicEnvironment m_classic;
  gl::Texture m_cube;
  gl::Texture m_sphereMap;
  std::vector<render::env::ClassicMesh> m_meshes;
  std::vector<mat4> m_models;
};

}  // namespace

void registerEnvClassic(Registry& registry) {
  SceneDesc desc{.name = "env/classic",
                 .summary = "Cube and sphere environment maps with the 2001 fixed-function API of the WWDC 2001 talk "
                            "(glTexGen, GL_TEXTURE_CUBE_MAP), in a compatibility-profile context.",
                 .profile = gl::Profile::Compatibility};
  for (const auto& v : kVariants) desc.variants.push_back({v.name, v.description});
  desc.create = [](int variant) -> std::unique_ptr<Scene> { return std::make_unique<ClassicScene>(kVariants[variant]); };
  registry.add(std::move(desc));
}

}  // namespace glint::scenes
