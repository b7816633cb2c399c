// env/cube, env/sphere, env/compare, env/faces, env/spheremap — cube vs sphere
// environment maps (the WWDC 2001 talk: "cube environment maps", the sphere map "generated from
// these six images", its wasted area and its back-side singularity).
#include "env_common.h"

#include "glint/gl/render_target.h"
#include "glint/image/metrics.h"
#include "glint/render/env/reflection.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace glint::scenes {
namespace {
using namespace env;
using render::env::Lookup;

const View kViews[] = {
    {"front", 0.0f, "from the front: the view the sphere map was made for"},
    {"back", kPi, "from behind: the cube map is as good as ever"},
};

enum class Mode { Cube, Sphere, Compare };

void clearTarget(const FrameInput& frame) {
  frame.target.bind();
  render::PipelineState{.depthTest = true}.apply();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

class MirrorScene final : public Scene {
public:
  MirrorScene(Mode mode, const View& view) : m_mode(mode), m_view(view), m_cube(loadEnvironmentCube()) {
    for (auto& o : mode == Mode::Compare ? mirrorBall() : mirrorPair()) {
      m_meshes.emplace_back(o.mesh, std::span<const vec4>{}, "mirror");
      m_models.push_back(o.model);
    }
    if (mode != Mode::Cube) {
      m_sphereMap = render::env::sphereMapFromCube(
          m_cube, {.size = kSphereMapSize, .worldToFrame = sphereMapFrame({1, 1})});
    }
  }

  std::vector<Option> options() override {
    return {{"per-vertex", "generate the lookup per vertex and interpolate, exactly like glTexGen", &m_perVertex},
            {"spin", "camera turn rate around the objects, radians per second", &m_spin, -2.0f, 2.0f}};
  }

  void render(const FrameInput& frame) override {
    if (m_mode == Mode::Compare && !m_quality) m_quality = measureQuality();
    clearTarget(frame);
    const ivec2 size = frame.target.size;
    const glint::Camera camera = frame.camera(viewCamera(m_view.azimuth + m_spin * float(frame.time), size));
    if (m_mode == Mode::Compare) {
      // Split screen like the WWDC 2001 talk's demo: cube map on the left, sphere map on the right,
      // one camera over the whole frame (each half shows its half of the same view), and
      // a 2-pixel divider.
      const gl::Target left = frame.target.column(0, 2), right = frame.target.column(1, 2);
      left.bind();
      drawHalf(camera.cropped(size, left.origin, left.size), Lookup::CubeMap);
      right.bind();
      drawHalf(camera.cropped(size, right.origin, right.size), Lookup::SphereMap);
      frame.target.region({size.x / 2 - 1, 0}, {2, size.y}).bind();
      render::clear(GL_COLOR_BUFFER_BIT, vec4(0.9f, 0.9f, 0.9f, 1.0f));
      frame.target.bind();
    } else {
      drawHalf(camera, m_mode == Mode::Cube ? Lookup::CubeMap : Lookup::SphereMap);
    }
  }

  std::string notes() const override {
    const std::string source = fmt::format(
        "Environment: {}.exr (CC0, Blender's studio lights) converted on the GPU into a {}² cube map, one "
        "framebuffer-object pass per face, mipmapped. Lookup per {}.",
        kEnvironment, kFaceSize, m_perVertex ? "vertex (as glTexGen)" : "pixel");
    if (m_mode == Mode::Cube) return source;
    std::string quality;
    if (m_quality) {
      quality = fmt::format(" Measured on the ball ({}x{}, this view) against a {}² cube-map reference: RMS error "
                            "{:.4f} for the cube map, {:.4f} for the sphere map.",
                            kQualitySize.x, kQualitySize.y, 2 * kFaceSize, m_quality->first, m_quality->second);
    }
    return source + quality + " " + sphereMapFigures();
  }

private:
  static constexpr ivec2 kQualitySize{320, 180};

  // RMS error (luminance) of the ball's pixels with the cube map and with the sphere map,
  // against a cube map twice as fine made from the same panorama: "the quality is different".
  std::pair<double, double> measureQuality() {
    const gl::Texture reference = loadEnvironmentCube(2 * kFaceSize);
    gl::RenderTarget target(kQualitySize, GL_RGBA8, "env-quality");
    const glint::Camera camera = viewCamera(m_view.azimuth, kQualitySize);
    const auto ball = [&](Lookup lookup, const gl::Texture& environment) {
      target.target().bind();
      render::PipelineState{.depthTest = true}.apply();
      render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, vec4(0.0f, 0.0f, 0.0f, 0.0f));
      reflector(lookup).draw(m_meshes[0], m_models[0], camera, environment, sphereMapFrame({1, 1}));
      return gl::readColor(target.framebuffer(), kQualitySize);
    };
    const Image truth = ball(Lookup::CubeMap, reference);
    const Image cube = ball(Lookup::CubeMap, m_cube);
    const Image sphere = ball(Lookup::SphereMap, m_sphereMap);
    double cubeSum = 0, sphereSum = 0;
    std::size_t n = 0;
    for (int y = 0; y < truth.height(); ++y)
      for (int x = 0; x < truth.width(); ++x) {
        if (truth.at(x, y, 3) < 0.5f) continue;  // not the ball (alpha 0 where cleared)
        const double t = luminance(truth, x, y);
        cubeSum += std::pow(luminance(cube, x, y) - t, 2.0);
        sphereSum += std::pow(luminance(sphere, x, y) - t, 2.0);
        ++n;
      }
    return {std::sqrt(cubeSum / double(std::max<std::size_t>(n, 1))), std::sqrt(sphereSum / double(std::max<std::size_t>(n, 1)))};
  }

  void drawHalf(const glint::Camera& camera, Lookup lookup) {
    m_sky.draw(m_cube, camera);
    const render::env::Reflector& mirror = reflector(lookup);
    for (std::size_t i = 0; i < m_meshes.size(); ++i) {
      if (lookup == Lookup::CubeMap) mirror.draw(m_meshes[i], m_models[i], camera, m_cube);
      else mirror.draw(m_meshes[i], m_models[i], camera, m_sphereMap, sphereMapFrame({1, 1}));
    }
  }

  const render::env::Reflector& reflector(Lookup lookup) {
    auto& slot = m_reflectors[lookup == Lookup::SphereMap][m_perVertex];
    if (!slot) slot.emplace(render::env::ReflectorOptions{.lookup = lookup, .perVertex = m_perVertex});
    return *slot;
  }

  Mode m_mode;
  View m_view;
  gl::Texture m_cube;
  gl::Texture m_sphereMap;
  render::env::Skybox m_sky;
  std::vector<render::GpuMesh> m_meshes;
  std::vector<mat4> m_models;
  std::optional<render::env::Reflector> m_reflectors[2][2];
  bool m_perVertex = false;
  float m_spin = 0.0f;
  std::optional<std::pair<double, double>> m_quality;
};

class FacesScene final : public Scene {
public:
  FacesScene() : m_cube(loadEnvironmentCube()) {}
  void render(const FrameInput& frame) override {
    clearTarget(frame);
    m_view.draw(m_cube, frame.target.size);
  }
  std::string notes() const override {
    return fmt::format("The six {}² faces of the cube map made from {}.exr, unfolded around the viewer: −X, −Z "
                       "(front), +X, +Z in the middle row, +Y above and −Y below the front. Each face is a 90° "
                       "view; together they form a contiguous panorama, edges marked.",
                       kFaceSize, kEnvironment);
  }

private:
  gl::Texture m_cube;
  render::env::CubeCrossView m_view;
};

class SphereMapImageScene final : public Scene {
public:
  explicit SphereMapImageScene(bool hemispheres)
      : m_view(hemispheres),
        m_map(render::env::sphereMapFromCube(loadEnvironmentCube(),
                                             {.size = kSphereMapSize, .worldToFrame = sphereMapFrame({1, 1})})) {
    // Count the wasted texels the GPU actually wrote (alpha 0), to set beside the analysis.
    const Image texels = gl::readTexture(m_map);
    std::size_t wasted = 0;
    for (int y = 0; y < texels.height(); ++y)
      for (int x = 0; x < texels.width(); ++x) wasted += texels.at(x, y, 3) < 0.5f;
    m_measuredWasted = double(wasted) / double(texels.pixelCount());
  }
  void render(const FrameInput& frame) override {
    clearTarget(frame);
    m_view.draw(m_map, frame.target.size);
  }
  std::string notes() const override {
    return fmt::format("Generated from the {}² cube map for the front view. Measured on the GPU's texels: {:.2f}% "
                       "wasted. ",
                       kFaceSize, 100.0 * m_measuredWasted) +
           sphereMapFigures();
  }

private:
  render::env::SphereMapView m_view;
  gl::Texture m_map;
  double m_measuredWasted = 0;
};

}  // namespace

void registerEnvScenes(Registry& registry) {
  const struct {
    const char* name;
    Mode mode;
    const char* summary;
    const char* what;
  } mirrors[] = {
      {"env/cube", Mode::Cube,
       "Cube-map environment mapping (the WWDC 2001 talk): reflection-vector lookup (GL_REFLECTION_MAP's shader "
       "equivalent) on mirror objects, skybox behind.",
       "cube map"},
      {"env/sphere", Mode::Sphere,
       "Sphere-map environment mapping (the WWDC 2001 talk): GL_SPHERE_MAP's lookup into a sphere map generated from the "
       "cube map for the front view.",
       "sphere map"},
      {"env/compare", Mode::Compare,
       "Cube map (left) vs sphere map (right), split screen like the WWDC 2001 talk's demo.", "split screen"},
  };
  for (const auto& m : mirrors) {
    SceneDesc desc{.name = m.name, .summary = m.summary};
    for (const auto& v : kViews) {
      std::string line = fmt::format("{}, {}", m.what, v.description);
      if (m.mode != Mode::Cube && std::string(v.name) == "back")
        line = fmt::format("{}, from behind: the sphere map's back-side singularity smears the middle of the "
                           "reflection", m.what);
      desc.variants.push_back({v.name, line});
    }
    const Mode mode = m.mode;
    desc.create = [mode](int variant) -> std::unique_ptr<Scene> {
      return std::make_unique<MirrorScene>(mode, kViews[variant]);
    };
    registry.add(std::move(desc));
  }
  registry.add({.name = "env/faces",
                .summary = "The cube map's six faces laid out as a cross (the WWDC 2001 talk: \"the six texture images\").",
                .variants = {{"cross", "the faces as a contiguous panorama seen from the object"}},
                .defaultSize = {640, 480},
                .create = [](int) -> std::unique_ptr<Scene> { return std::make_unique<FacesScene>(); }});
  registry.add({.name = "env/spheremap",
                .summary = "The sphere map generated from the cube map, with its wasted corners (the WWDC 2001 talk: \"about "
                           "20% of the spherical map\").",
                .variants = {{"image", "the sphere map as generated; black corners are wasted"},
                             {"hemispheres", "front half green (disk of radius 1/√2), back half red (the ring), "
                                             "wasted corners hatched: ≈ 40 / 40 / 20 %"}},
                .defaultSize = {480, 480},
                .create = [](int variant) -> std::unique_ptr<Scene> {
                  return std::make_unique<SphereMapImageScene>(variant == 1);
                }});
}

}  // namespace glint::scenes
