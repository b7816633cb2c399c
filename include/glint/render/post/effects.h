#pragma once
// glint/render/post/effects.h — the GPU side of post's effect table (post/effects.h): each
// effect's pass, registered under the effect's name in one list (src/render/post/effects.cpp),
// which the chain (render/post/chain.h) runs. The table itself, its parsing and the CPU
// backend are GL-free (glint::post); this header brings their vocabulary into
// glint::render::post for the GPU code.
//
/// ```cpp
/// #include <glint/render/post/effects.h>
/// const std::vector<std::string> specs = {"kuwahara", "edges:scale=3"};
/// const std::vector<glint::render::post::Effect> effects = glint::render::post::parseEffects(specs);
/// const bool onGpu = glint::render::post::gpuHas(*effects[0].def);  // true: every effect has a pass
/// ```
#include "glint/gl/objects.h"
#include "glint/post/effects.h"

#include <memory>

namespace glint::render::post {

// The table's vocabulary, as the GPU code speaks it.
using glint::post::Effect;
using glint::post::EffectDef;
using glint::post::EffectParam;
using glint::post::effectHelp;
using glint::post::effectNames;
using glint::post::effectTable;
using glint::post::findEffect;
using glint::post::makeEffect;
using glint::post::ParamType;
using glint::post::parseEffects;
using glint::post::validateEffect;

/// An effect's GPU work, built once per chain stage and run per frame with the effect's
/// current parameters (a stage keeps its GL objects while only parameters change).
class EffectStage {
public:
  virtual ~EffectStage() = default;
  virtual void run(const gl::Texture& input, const gl::Texture& output, const Effect& effect) = 0;
};

/// The GPU pass of the table's entry `def` (not an alias). Error(Internal) when the GPU has
/// none registered under its name.
std::unique_ptr<EffectStage> gpuStage(const EffectDef& def);
/// Whether the GPU has a pass for `def` (every effect of the table today).
bool gpuHas(const EffectDef& def);

}  // namespace glint::render::post
