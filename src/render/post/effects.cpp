// The GPU passes of post's effects, registered by name (render/post/effects.h). Adding an
// effect's pass: a pass class (passes.h, fft.h) and one line below.
#include "glint/render/post/effects.h"

#include "glint/core/error.h"
#include "glint/image/post.h"
#include "glint/render/post/fft.h"
#include "glint/render/post/passes.h"

#include <functional>
#include <string_view>

namespace glint::render::post {

namespace {

// A stage around one pass: `Pass` built once, run with the options `options(effect)` gives.
template <typename Pass, typename Options>
std::unique_ptr<EffectStage> passStage(Options (*options)(const Effect&)) {
  struct Stage final : EffectStage {
    Options (*options)(const Effect&);
    Pass pass;
    explicit Stage(Options (*o)(const Effect&)) : options(o) {}
    void run(const gl::Texture& in, const gl::Texture& out, const Effect& e) override { pass.run(in, out, options(e)); }
  };
  return std::make_unique<Stage>(options);
}

struct Registered {
  const char* name;
  std::unique_ptr<EffectStage> (*make)(const EffectDef&);
};

// Every effect's pass. The FFT filters share one: the entry's FrequencyFilter (EffectDef::filter).
const Registered kPasses[] = {
    {"sepia",
     [](const EffectDef&) {
       return passStage<SepiaPass>(+[](const Effect& e) { return SepiaOptions{.i = e.value("i"), .q = e.value("q")}; });
     }},
    {"sobel",
     [](const EffectDef&) {
       return passStage<SobelPass>(+[](const Effect& e) {
         constexpr SobelOutput outputs[] = {SobelOutput::Magnitude, SobelOutput::Horizontal, SobelOutput::Vertical,
                                            SobelOutput::SignedX, SobelOutput::SignedY};
         return SobelOptions{.output = outputs[int(e.value("output"))], .scale = e.value("scale")};
       });
     }},
    {"edges",
     [](const EffectDef&) {
       return passStage<EdgesPass>(
           +[](const Effect& e) { return EdgesOptions{.scale = e.value("scale"), .threshold = e.value("threshold")}; });
     }},
    {"kuwahara",
     [](const EffectDef&) {
       return passStage<KuwaharaPass>(+[](const Effect& e) { return KuwaharaOptions{.size = int(e.value("size"))}; });
     }},
    {"spectrum",
     [](const EffectDef&) -> std::unique_ptr<EffectStage> {
       struct Stage final : EffectStage {
         SpectrumPass pass;
         void run(const gl::Texture& in, const gl::Texture& out, const Effect&) override { pass.run(in, out); }
       };
       return std::make_unique<Stage>();
     }},
};

std::unique_ptr<EffectStage> filterStage(const EffectDef& def) {
  struct Stage final : EffectStage {
    FrequencyFilter (*filter)(const Effect&);
    FrequencyFilterPass pass;
    explicit Stage(FrequencyFilter (*f)(const Effect&)) : filter(f) {}
    void run(const gl::Texture& in, const gl::Texture& out, const Effect& e) override { pass.run(in, out, filter(e)); }
  };
  return std::make_unique<Stage>(def.filter);
}

}  // namespace

bool gpuHas(const EffectDef& def) {
  if (def.filter) return true;
  for (const Registered& r : kPasses)
    if (std::string_view(def.name) == r.name) return true;
  return false;
}

std::unique_ptr<EffectStage> gpuStage(const EffectDef& def) {
  if (def.filter) return filterStage(def);
  for (const Registered& r : kPasses)
    if (std::string_view(def.name) == r.name) return r.make(def);
  fail(ErrorKind::Internal, "post: no GPU pass is registered for '{}'", def.name);
}

}  // namespace glint::render::post
