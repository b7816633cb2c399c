// filtering/checker, filtering/text — texture filtering on a ground plane receding to the
// horizon (the WWDC 2001 talk: bilinear "sparkling", trilinear "blurred", anisotropic "sharp even
// when it's viewed at a bleak angle"). Each variant is measured against a 16×16
// supersampled ground truth; the numbers are in the notes (gallery text).
#include "glint/gl/context.h"
#include "glint/image/pattern.h"
#include "glint/render/filtering/filtering.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <vector>

namespace glint::scenes {
namespace {
namespace flt = render::filtering;

enum class Pattern { Checker, Text };

std::string filterName(GLenum f) {
  switch (f) {
    case GL_NEAREST: return "GL_NEAREST";
    case GL_LINEAR: return "GL_LINEAR";
    case GL_LINEAR_MIPMAP_NEAREST: return "GL_LINEAR_MIPMAP_NEAREST";
    case GL_LINEAR_MIPMAP_LINEAR: return "GL_LINEAR_MIPMAP_LINEAR";
    default: return fmt::format("0x{:x}", f);
  }
}

class FilteringScene final : public Scene {
public:
  FilteringScene(Pattern pattern, const flt::FilterMode& mode)
      : m_ground(pattern == Pattern::Checker ? makeCheckerboard(512, 8) : makeTestChart(1024),
                 pattern == Pattern::Checker ? 4.0f : 6.0f, pattern == Pattern::Checker ? "checker" : "test-chart"),
        m_requested(mode.anisotropy),
        m_mode(flt::clampedToDevice(mode)),
        m_maxAnisotropy(flt::maxAnisotropy()),
        m_software(gl::queryContextInfo().software) {}

  std::vector<Option> options() override {
    return {{"anisotropy", "GL_TEXTURE_MAX_ANISOTROPY (1 to this GPU's maximum)", &m_mode.anisotropy, 1.0f, 16.0f},
            {"lod-bias", "GL_TEXTURE_LOD_BIAS in mip levels", &m_mode.lodBias, -4.0f, 4.0f},
            {"speed", "camera speed along the plane, units per second (watch the sparkle)", &m_speed, 0.0f, 4.0f},
            {"measure", "measure against the supersampled truth (gallery numbers)", &m_measure}};
  }

  void render(const FrameInput& frame) override {
    if (m_measure && (!m_quality || m_measuredAniso != m_mode.anisotropy || m_measuredBias != m_mode.lodBias)) {
      m_quality = flt::measureFiltering(m_ground, m_mode);
      m_measuredAniso = m_mode.anisotropy;
      m_measuredBias = m_mode.lodBias;
    }
    frame.target.bind();
    m_ground.draw(frame.camera(flt::GroundPlane::camera(frame.target.size, m_speed * float(frame.time))), m_mode);
  }

  std::string notes() const override {
    std::string text = fmt::format("GL_MAX_TEXTURE_MAX_ANISOTROPY = {:g}. Min filter {}, anisotropy {:g}", m_maxAnisotropy,
                                   filterName(m_mode.minFilter), m_mode.anisotropy);
    if (m_requested > m_mode.anisotropy) text += fmt::format(" (asked for {:g}: clamped to the maximum)", m_requested);
    if (m_software && m_mode.anisotropy > 1.0f) text += " (llvmpipe has one anisotropic filter for every level above 1)";
    if (m_mode.lodBias != 0.0f) text += fmt::format(", LOD bias {:+g}", m_mode.lodBias);
    text += ".";
    if (m_quality) {
      const flt::MeasureOptions o;
      text += fmt::format(
          " Against a {0}×{0}-supersampled truth at {1}×{2}: RMS error {3:.4f}; sharpness {4:.2f}× the truth's in the "
          "oblique half of the ground; flicker {5:.4f} over a {6}-frame camera move.",
          o.supersample, o.size.x, o.size.y, m_quality->rmsError, m_quality->sharpnessRatio(), m_quality->flicker,
          o.frames);
    }
    return text;
  }

private:
  flt::GroundPlane m_ground;
  float m_requested;
  flt::FilterMode m_mode;
  float m_maxAnisotropy;
  bool m_software;
  float m_speed = 0.0f;
  bool m_measure = true;
  std::optional<flt::FilterQuality> m_quality;
  float m_measuredAniso = 0.0f, m_measuredBias = 0.0f;
};

void registerPattern(Registry& registry, Pattern pattern) {
  SceneDesc desc{
      .name = pattern == Pattern::Checker ? "filtering/checker" : "filtering/text",
      .summary = pattern == Pattern::Checker
                     ? "Texture filtering on a checkerboard ground plane receding to the horizon (the WWDC 2001 talk: bilinear, "
                       "trilinear, anisotropic), measured against a 16×16 supersampled truth."
                     : "Texture filtering on a test chart with text, receding to the horizon (the WWDC 2001 talk's \"test "
                       "image\"), measured against a 16×16 supersampled truth.",
  };
  // Anisotropic filtering's samples are the implementation's to place (GL 4.6 §8.14.3.1):
  // those variants' pictures differ between GLs where GL lets them (scene.h).
  for (const auto& m : flt::standardModes())
    desc.variants.push_back({.name = m.name, .description = m.description, .implementationDefined = m.anisotropy > 1.0f});
  desc.create = [pattern](int variant) -> std::unique_ptr<Scene> {
    return std::make_unique<FilteringScene>(pattern, flt::standardModes()[std::size_t(variant)]);
  };
  registry.add(std::move(desc));
}

}  // namespace

void registerFilteringScenes(Registry& registry) {
  registerPattern(registry, Pattern::Checker);
  registerPattern(registry, Pattern::Text);
}

}  // namespace glint::scenes
