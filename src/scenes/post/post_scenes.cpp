// post/photo, post/scene, post/pattern — WWDC 2003 session 212's post-processing effects on a real
// photograph, on a frame rendered by another glint scene, and the FFT on the classic test
// patterns (spatial domain left, frequency domain right, as WWDC 2003 session 212's slide showed them).
#include "post_common.h"

#include "glint/core/locations.h"
#include "glint/gl/render_target.h"
#include "glint/image/envmap.h"
#include "glint/image/pattern.h"
#include "glint/render/post/chain.h"
#include "glint/render/state.h"

#include <fmt/format.h>

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint::scenes {
namespace post {

using render::post::Chain;
using render::post::Effect;
using render::post::FrameView;

const Image& photograph(ivec2 size) {
  static std::mutex mutex;
  static std::optional<Image> equirect;
  static std::map<std::pair<int, int>, Image> views;
  std::lock_guard lock(mutex);
  if (!equirect) equirect = loadImage(findDataFile("env/courtyard.exr", "environment 'courtyard'"));
  auto it = views.find({size.x, size.y});
  if (it == views.end()) {
    // Across the courtyard at the garage: palms against the sky, brick paving, hard
    // shadows — edges and textures of every scale. 70° vertically (the HDR photograph has
    // only 1024 × 512 texels: a narrower view would be visibly soft); exposure 0.5 keeps
    // the sunlit walls from clipping.
    it = views.emplace(std::pair{size.x, size.y}, perspectiveView(*equirect, size, 0.0f, 0.05f, 70.0f, 0.5f)).first;
  }
  return it->second;
}

std::vector<Option> BeforeAfter::options() {
  return {{"before-after", "split the picture: the original left of the divider, the result right", &on, 0, 1, 'B'},
          {"divider", "where the split is, as a fraction of the width", &divider, 0.05f, 0.95f}};
}

std::vector<Effect> chainOf(const std::vector<std::string>& specs) { return render::post::parseEffects(specs); }

namespace {
// "0 magnitude, 1 horizontal, ...": a choice's slider positions.
std::string choiceList(const render::post::EffectParam& p) {
  std::string s;
  for (std::size_t i = 0; i < p.choices.size(); ++i) s += fmt::format("{}{} {}", i ? ", " : "", i, p.choices[i]);
  return s;
}
}  // namespace

std::vector<Option> effectOptions(std::vector<Effect>& effects) {
  // A parameter's option is named after it ("scale"), or "effect.param" when two effects of
  // the chain share the name (glint post's --set spelling).
  std::map<std::string, int> uses;
  for (const auto& e : effects)
    for (const auto& p : e.def->params) ++uses[p.name];
  std::vector<Option> out;
  for (auto& e : effects) {
    for (std::size_t i = 0; i < e.def->params.size(); ++i) {
      const render::post::EffectParam& p = e.def->params[i];
      Option o{.name = uses[p.name] > 1 ? fmt::format("{}.{}", e.name(), p.name) : std::string(p.name),
               .description = p.type == render::post::ParamType::Choice
                                  ? fmt::format("{}: {} ({})", e.name(), p.help, choiceList(p))
                                  : fmt::format("{}: {}", e.name(), p.help),
               .value = {},
               .min = p.sliderMin,
               .max = p.sliderMax};
      if (auto* f = std::get_if<float>(&e.values[i])) o.value = f;
      else o.value = &std::get<int>(e.values[i]);
      out.push_back(std::move(o));
    }
  }
  return out;
}

}  // namespace post

namespace {
using render::post::Chain;
using render::post::Effect;

// The frame of a post scene: an image-orientation RGBA8 texture, the chain, the view.
class Processed {
public:
  explicit Processed(std::vector<std::string> specs) : m_effects(post::chainOf(specs)) {}

  std::vector<Option> options() {
    auto o = m_compare.options();
    for (auto& e : post::effectOptions(m_effects)) o.push_back(e);
    return o;
  }

  /// Runs the chain on `input` and draws the result (with the before/after split) into `target`.
  void show(const gl::Texture& input, const gl::Target& target) {
    const ivec2 size(input.width(), input.height());
    if (!m_chain || m_chain->size() != size) m_chain.emplace(size, m_effects);
    m_chain->setEffects(m_effects);  // the options edit m_effects
    const gl::Texture& result = m_chain->run(input);
    m_view.draw(target, result, &input, m_compare.split());
  }

  std::string describe() const {
    std::string s;
    for (const auto& e : m_effects) s += (s.empty() ? "" : " → ") + e.describe();
    return s.empty() ? "the original (no effect)" : s;
  }

private:
  std::vector<Effect> m_effects;
  post::BeforeAfter m_compare;
  std::optional<Chain> m_chain;
  render::post::FrameView m_view;
};

struct EffectVariant {
  const char* name;
  const char* description;
  std::vector<std::string> specs;
};

const std::vector<EffectVariant>& photoVariants() {
  static const std::vector<EffectVariant> v = {
      {"original", "the photograph, no effect (a view of the courtyard HDR photograph)", {}},
      {"sepia", "WWDC 2003 session 212's sepia: Y kept, I = 0.2 and Q = 0 hard-coded, back to RGB — a dot product and an add", {"sepia"}},
      {"sobel-horizontal", "horizontal edges: the Sobel kernel on the rows above and below (|Gy|)", {"sobel:output=horizontal"}},
      {"sobel-vertical", "vertical edges: the kernel on the columns left and right (|Gx|)", {"sobel:output=vertical"}},
      {"sobel", "both: the gradient magnitude √(Gx² + Gy²)", {"sobel"}},
      {"kuwahara", "the two-pass Kuwahara filter: mean of the calmest of four overlapping 3×3 quadrants", {"kuwahara"}},
      {"posterize", "WWDC 2003 session 212's posterize: Kuwahara with the Sobel edges composited on top", {"posterize"}},
      {"spectrum", "log magnitude of the luma's 2D DFT (GPU FFT, mixed radix), DC in the middle", {"spectrum"}},
      {"lowpass", "a Butterworth low-pass in the frequency domain (cutoff 0.05 cycles/pixel)", {"lowpass"}},
      {"highpass", "the matching high-pass, around mid-gray: what the low-pass removed", {"highpass"}},
      {"bandpass", "a band-pass (0.03 to 0.12 cycles/pixel): the mid-scale structure", {"bandpass"}},
      {"blur", "a Gaussian blur (σ = 4) as a convolution through the FFT", {"blur"}},
      {"bokeh", "a disk blur (radius 6), a lens's out-of-focus look, through the FFT", {"bokeh"}}};
  return v;
}

// ---------------------------------------------------------------------------
class PhotoScene final : public Scene {
public:
  explicit PhotoScene(const EffectVariant& v) : m_processed(v.specs) {}
  std::vector<Option> options() override { return m_processed.options(); }

  void render(const FrameInput& frame) override {
    const ivec2 size = frame.target.size;
    if (!m_photo || m_photo.width() != size.x || m_photo.height() != size.y) {
      m_photo = render::post::uploadFrame(post::photograph(size), "post-photograph");
    }
    m_processed.show(m_photo, frame.target);
  }

  std::string notes() const override {
    return fmt::format("{} on a {}x{} view of the courtyard HDR photograph (8-bit, sRGB-encoded, as a camera gives it). "
                       "The cost is per pixel, independent of what the picture shows. `glint post` runs the same chain "
                       "on images, videos and cameras; `glint bench post` times it.",
                       m_processed.describe(), m_photo.width(), m_photo.height());
  }

private:
  Processed m_processed;
  gl::Texture m_photo;
};

// ---------------------------------------------------------------------------
// A frame rendered by another registered scene, then post-processed: "whether you rendered
// one polygon or two million, the same overhead".
constexpr const char* kRenderedScene = "shadows/bunny/closed";

class RenderedScene final : public Scene {
public:
  explicit RenderedScene(const EffectVariant& v)
      : m_processed(v.specs), m_source(Registry::builtin().resolve(kRenderedScene)),
        m_scene(m_source.scene->create(m_source.variant)), m_flip(gl::Framebuffer::create("post-scene-flip")) {}
  std::vector<Option> options() override { return m_processed.options(); }

  void render(const FrameInput& frame) override {
    const ivec2 size = frame.target.size;
    if (!m_target || m_target->size() != size) {
      m_target.emplace(size, GL_RGBA8, "post-scene-render");
      m_frame = gl::Texture(GL_TEXTURE_2D, "post-scene-frame");
      m_frame.storage(GL_RGBA8, size.x, size.y);
      m_flip.attach(GL_COLOR_ATTACHMENT0, m_frame);
      m_flip.checkComplete();
    }
    render::resetState();
    m_scene->render({.target = m_target->target(), .time = m_source.scene->defaultTime + frame.time});
    render::resetState();
    // GL's rows go up, a frame's go down (render/post's convention): flip while copying.
    m_target->framebuffer().blitTo(m_flip, {0, 0, size.x, size.y}, {0, size.y, size.x, 0}, GL_COLOR_BUFFER_BIT);
    m_processed.show(m_frame, frame.target);
  }

  std::string notes() const override {
    return fmt::format("{} on a frame of {} (rendered into a texture first, then post-processed).",
                       m_processed.describe(), kRenderedScene);
  }

private:
  Processed m_processed;
  VariantRef m_source;
  std::unique_ptr<Scene> m_scene;
  std::optional<gl::RenderTarget> m_target;
  gl::Texture m_frame;
  gl::Framebuffer m_flip;
};

// ---------------------------------------------------------------------------
// The FFT's classic test patterns: the pattern left, its spectrum or a filtered version right.
struct PatternVariant {
  const char* name;
  const char* description;
  bool zonePlate;
  std::vector<std::string> specs;  // what the right half shows
};

constexpr int kPatternSize = 256;

class PatternScene final : public Scene {
public:
  explicit PatternScene(const PatternVariant& v)
      : m_variant(v), m_processed(v.specs),
        m_pattern(render::post::uploadFrame(v.zonePlate ? makeZonePlate(kPatternSize) : makeRectangle(kPatternSize),
                                            "post-pattern")) {}
  std::vector<Option> options() override { return m_processed.options(); }

  void render(const FrameInput& frame) override {
    frame.target.bind();
    render::clear(GL_COLOR_BUFFER_BIT, vec4(0.3f, 0.3f, 0.32f, 1.0f));  // a frame around the two panels
    m_view.draw(frame.target.cell(0, 0, 2, 1, 8), m_pattern);
    m_processed.show(m_pattern, frame.target.cell(1, 0, 2, 1, 8));
    frame.target.bind();
  }

  std::string notes() const override {
    return fmt::format("Left: the {} ({}²). Right: {}.", m_variant.zonePlate ? "zone plate" : "rectangle", kPatternSize,
                       m_processed.describe());
  }

private:
  const PatternVariant& m_variant;
  Processed m_processed;
  gl::Texture m_pattern;
  render::post::FrameView m_view;
};

const std::vector<PatternVariant>& patternVariants() {
  static const std::vector<PatternVariant> v = {
      {"rectangle", "a white rectangle and its spectrum: two sinc functions multiplied, a cross of lobes", false, {"spectrum"}},
      {"zone-plate", "the zone plate (a radial chirp up to Nyquist) and its spectrum", true, {"spectrum"}},
      {"zone-plate-lowpass", "the zone plate through a Butterworth low-pass: the outer, high-frequency rings fade to gray",
       true, {"lowpass:cutoff=0.2,order=4"}},
      {"rectangle-ideal-lowpass", "the rectangle through an ideal (brick-wall) low-pass: ringing around its edges (Gibbs)",
       false, {"lowpass:cutoff=0.08,order=0"}}};
  return v;
}

template <typename Variant>
std::vector<VariantDesc> describe(const std::vector<Variant>& variants) {
  std::vector<VariantDesc> out;
  for (const auto& v : variants) out.push_back({v.name, v.description});
  return out;
}

const std::vector<EffectVariant>& renderedVariants() {
  static const std::vector<EffectVariant> v = [] {
    std::vector<EffectVariant> out;
    for (const auto& p : photoVariants()) {
      const std::string n = p.name;
      if (n == "original") out.push_back({p.name, "the rendered frame, no effect (shadows/bunny/closed)", p.specs});
      if (n == "sepia" || n == "sobel" || n == "posterize" || n == "spectrum" || n == "bokeh") out.push_back(p);
    }
    return out;
  }();
  return v;
}

}  // namespace

void registerPostScenes(Registry& registry) {
  registry.add({.name = "post/photo",
                .summary = "WWDC 2003 session 212's post-processing on a real photograph: sepia via YIQ, Sobel, Kuwahara "
                           "posterize, GPU FFT filters (docs/post.md)",
                .variants = describe(photoVariants()),
                .defaultSize = {640, 360},
                .create = [](int v) { return std::make_unique<PhotoScene>(photoVariants()[std::size_t(v)]); }});
  registry.add({.name = "post/scene",
                .summary = std::string("the same effects on a frame rendered by glint (") + kRenderedScene +
                           "): image space, the same cost whatever was drawn",
                .variants = describe(renderedVariants()),
                .defaultSize = {640, 360},
                .create = [](int v) { return std::make_unique<RenderedScene>(renderedVariants()[std::size_t(v)]); }});
  registry.add({.name = "post/pattern",
                .summary = "the FFT on its classic test patterns: spatial domain left, frequency domain (or a filtered "
                           "result) right",
                .variants = describe(patternVariants()),
                // Two square 304² panels (cells of 320², 8-pixel gaps): the square patterns fill them, no bars.
                .defaultSize = {640, 320},
                .create = [](int v) { return std::make_unique<PatternScene>(patternVariants()[std::size_t(v)]); }});
}

}  // namespace glint::scenes
