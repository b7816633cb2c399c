// bump/dot3-classic, bump/dot3-shader, bump/light-vectors, bump/dot-product, bump/normalize —
// DOT3 bump mapping with texture combiners as the WWDC 2001 talk demonstrates it: "a positional light
// source circling the source texture" over "a simple four-vertex polygon", the encoded light
// vectors shown as colours, the grayscale dot product, the final modulated image, and the
// interpolation artifact ("there are issues about keeping the vectors normalized").
#include "bump_common.h"

#include "glint/render/bump/dot3.h"
#include "glint/render/bump/light_marker.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint::scenes {
namespace {
using namespace bump;
using render::bump::Dot3Stage;

enum class Normalization {
  Interpolated,  ///< the colours as interpolated (the 2001 result)
  PerPixel,      ///< decoded, normalized and re-encoded per pixel (the fix)
  SideBySide     ///< two polygons: interpolated on the left, normalized on the right
};

struct Dot3Variant {
  const char* name;
  const char* description;
  Dot3Stage stage = Dot3Stage::Modulated;
  Relief relief = Relief::Bricks;
  Normalization normalization = Normalization::Interpolated;
  int subdivisions = 1;       // 1 = the WWDC 2001 talk's four-vertex polygon
  float lightRadius = 0.8f;  // polygon half-sizes
  float lightHeight = 0.75f;
};

// The polygon leans back 30°, like the tablet in the WWDC 2001 talk's demo seen from a little above.
const quat kPolygonRotation = glm::angleAxis(glm::radians(-30.0f), vec3(1.0f, 0.0f, 0.0f));
constexpr float kLightSpeed = 0.8f;  // radians per second around the polygon

class Dot3Scene final : public Scene {
public:
  Dot3Scene(const Dot3Variant& v, bool classic)
      : m_variant(v), m_classicPath(classic), m_textures(makeDemoTextures(v.relief)), m_subdivisions(v.subdivisions),
        m_lightRadius(v.lightRadius), m_lightHeight(v.lightHeight), m_normalize(v.normalization == Normalization::PerPixel) {
    if (classic) m_classic.emplace();
  }

  std::vector<Option> options() override {
    std::vector<Option> o = {
        {"light-radius", "radius of the light's circle, in polygon half-sizes", &m_lightRadius, 0.0f, 3.0f},
        {"light-height", "height of the light above the polygon, in polygon half-sizes", &m_lightHeight, 0.05f, 3.0f},
        {"light-speed", "radians per second around the polygon", &m_lightSpeed, -3.0f, 3.0f},
        {"subdivisions", "cells per side of the polygon (1 = the WWDC 2001 talk's four vertices)", &m_subdivisions, 1, 32},
        {"show-light", "draw a marker where the light is", &m_showLight}};
    if (!m_classicPath && m_variant.normalization != Normalization::SideBySide)
      o.push_back({"normalize", "normalize the interpolated light vector per pixel (the fix)", &m_normalize});
    return o;
  }

  void render(const FrameInput& frame) override {
    rebuildIfNeeded();
    frame.target.bind();
    render::PipelineState{.depthTest = true}.apply();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.05f, 0.06f, 0.08f, 1.0f));
    const bool twoUp = m_variant.normalization == Normalization::SideBySide;
    const glint::Camera camera = frame.camera(dot3Camera(frame.target.size, twoUp ? 4.4f : 2.9f));
    const vec3 lightLocal = circlingLight(frame.time, m_lightRadius, m_lightHeight, m_lightSpeed);
    for (std::size_t i = 0; i < m_polygons.size(); ++i) {
      const render::bump::Dot3Polygon& polygon = m_polygons[i];
      // The light circles each polygon in its own frame; in the world it is rotated with it.
      const vec3 lightWorld = polygon.rotation() * lightLocal + polygon.translation();
      const std::vector<u8vec3> colors = polygon.lightColors(lightWorld);
      if (m_classic) m_classic->draw(polygon, colors, camera, m_textures.normalMap, m_textures.base, m_variant.stage);
      else m_shaders[i].draw(colors, polygon.model(), camera, m_textures.normalMap, m_textures.base, m_variant.stage);
      if (m_showLight) m_marker.draw(camera, lightWorld);
      m_lastLight = lightLocal;
    }
  }

  std::string notes() const override {
    std::string s = m_classicPath
                        ? "Fixed-function path (compatibility profile): glTexEnv GL_COMBINE, stage 1 GL_DOT3_RGB of "
                          "GL_PRIMARY_COLOR and the normal map in unit 0, stage 2 GL_MODULATE of GL_PREVIOUS and the "
                          "base texture in unit 1; vertices with glColor3ub / glMultiTexCoord2f / glVertex3f."
                        : "Shader path: the same unsigned-byte colours, and a fragment shader with the combiners' "
                          "arithmetic 4·Σ(a−½)(b−½), clamped. tests/bump/dot3_gl_test: equal to the spec formula and to "
                          "the fixed-function path within 1/255.";
    s += fmt::format(" Light in the polygon's frame: ({:.2f}, {:.2f}, {:.2f}); polygon of {} vertices.", m_lastLight.x,
                     m_lastLight.y, m_lastLight.z, (m_subdivisions + 1) * (m_subdivisions + 1));
    if (m_variant.normalization == Normalization::SideBySide)
      s += " Left: colours interpolated as they are (short vectors between the corners: a dark hole right under the "
           "light). Right: the interpolated vector normalized per pixel (the fix).";
    return s;
  }

private:
  void rebuildIfNeeded() {
    const bool normalizeNow = m_variant.normalization == Normalization::SideBySide ? false : m_normalize;
    if (!m_polygons.empty() && m_builtSubdivisions == m_subdivisions && m_builtNormalize == normalizeNow) return;
    m_subdivisions = std::clamp(m_subdivisions, 1, 256);
    m_polygons.clear();
    m_shaders.clear();
    const bool twoUp = m_variant.normalization == Normalization::SideBySide;
    for (int i = 0; i < (twoUp ? 2 : 1); ++i) {
      render::bump::Dot3Polygon polygon({.subdivisions = m_subdivisions, .uvScale = 2.0f});
      polygon.place(kPolygonRotation, twoUp ? vec3(i == 0 ? -1.12f : 1.12f, 0.0f, 0.0f) : vec3(0.0f));
      if (!m_classic) m_shaders.emplace_back(polygon, render::bump::Dot3ShaderOptions{.normalizePerPixel = twoUp ? i == 1 : normalizeNow});
      m_polygons.push_back(std::move(polygon));
    }
    m_builtSubdivisions = m_subdivisions;
    m_builtNormalize = normalizeNow;
  }

  Dot3Variant m_variant;
  bool m_classicPath;
  DemoTextures m_textures;
  std::optional<render::bump::Dot3Classic> m_classic;
  std::vector<render::bump::Dot3Polygon> m_polygons;
  std::vector<render::bump::Dot3Shader> m_shaders;
  render::bump::LightMarker m_marker;
  int m_subdivisions;
  int m_builtSubdivisions = 0;
  bool m_builtNormalize = false;
  float m_lightRadius, m_lightHeight, m_lightSpeed = kLightSpeed;
  bool m_normalize;
  bool m_showLight = true;
  vec3 m_lastLight{0.0f};
};

// The variants. Scenes at t = 3 s: the light has gone 2.4 rad (137°) round, to the upper left.
const Dot3Variant kFinal[] = {
    {"bricks", "N·L × base texture on a brick wall: the final image of the WWDC 2001 talk's demo, one four-vertex polygon"},
    {"bumps", "round bumps and dents (even/odd cells): bumps lit on the light's side, dents on the far side",
     Dot3Stage::Modulated, Relief::Bumps},
};
const Dot3Variant kLightVectors[] = {
    {"quad", "the encoded local light vectors (glColor3ub) of the four corners, interpolated across the polygon",
     Dot3Stage::LightVectors},
    {"grid", "the same on an 8×8 grid: each vertex gets its own light vector, so the colours bend around the light",
     Dot3Stage::LightVectors, Relief::Bricks, Normalization::Interpolated, 8},
};
const Dot3Variant kDotProduct[] = {
    {"bricks", "combiner stage 1 alone: the grayscale dot product N·L (\"duplicate the scalar to make a light map\")",
     Dot3Stage::DotProduct},
    {"bumps", "stage 1 on the bumps map: a clear check of the lighting's direction", Dot3Stage::DotProduct, Relief::Bumps},
};
const Dot3Variant kNormalize[] = {
    {"side-by-side", "light low over the middle: interpolated light vectors (left, dark under the light) vs "
                     "normalized per pixel (right)",
     Dot3Stage::DotProduct, Relief::Bricks, Normalization::SideBySide, 1, 0.25f, 0.3f},
    {"interpolated", "the artifact alone: vectors from far-apart corners average to short ones, N·L drops",
     Dot3Stage::Modulated, Relief::Bricks, Normalization::Interpolated, 1, 0.25f, 0.3f},
    {"normalized", "the fix alone: the interpolated vector restored to unit length per pixel", Dot3Stage::Modulated,
     Relief::Bricks, Normalization::PerPixel, 1, 0.25f, 0.3f},
};

template <std::size_t N>
void addScene(Registry& registry, const char* name, const char* summary, const Dot3Variant (&variants)[N], bool classic) {
  SceneDesc desc{.name = name, .summary = summary, .profile = classic ? gl::Profile::Compatibility : gl::Profile::Core,
                 .defaultTime = 3.0};
  for (const auto& v : variants) desc.variants.push_back({v.name, v.description});
  desc.create = [&variants, classic](int variant) -> std::unique_ptr<Scene> {
    return std::make_unique<Dot3Scene>(variants[variant], classic);
  };
  registry.add(std::move(desc));
}

}  // namespace

void registerBumpDot3(Registry& registry) {
  addScene(registry, "bump/dot3-classic",
           "DOT3 bump mapping with the 2001 texture combiners (GL_COMBINE, GL_DOT3_RGB then GL_MODULATE) in a "
           "compatibility-profile context, light circling the polygon (the WWDC 2001 talk).",
           kFinal, true);
  addScene(registry, "bump/dot3-shader",
           "DOT3 bump mapping in GLSL with the combiners' exact arithmetic; equal to bump/dot3-classic (the WWDC 2001 talk).",
           kFinal, false);
  addScene(registry, "bump/light-vectors",
           "The per-vertex light vectors in the polygon's local space, encoded as unsigned-byte colours (v + 1)/2·255 "
           "(the WWDC 2001 talk).",
           kLightVectors, false);
  addScene(registry, "bump/dot-product",
           "Combiner stage 1 alone: DOT3_RGB of the light-vector colour and the normal map, a grayscale light map "
           "(the WWDC 2001 talk).",
           kDotProduct, false);
  addScene(registry, "bump/normalize",
           "Interpolating unnormalized light vectors darkens the polygon under a close light; normalizing per pixel "
           "fixes it (the WWDC 2001 talk: \"issues about keeping the vectors normalized\").",
           kNormalize, false);
}

}  // namespace glint::scenes
