#pragma once
// Shared by the post/* scenes (private to src/scenes/post): the photograph, options that
// edit an effect chain's parameters, the before/after split.
#include "glint/image/image.h"
#include "glint/render/post/effects.h"
#include "glint/scenes/scene.h"

#include <string>
#include <vector>

namespace glint::scenes::post {

/// The "real photograph": a view of the courtyard HDR photograph (data/env/courtyard.exr,
/// Debian's blender-data, CC0) through a pinhole camera, display-encoded to 8 bits, at
/// `size` pixels. Cached per size (the EXR is read once per process).
const Image& photograph(ivec2 size);

/// Options for the parameters of the effects in `effects` (pointers into it), from the
/// effect table (render/post/effects.h): named as the parameter ("scale"), or
/// "effect.param" where two effects of the chain share a name; the sliders' ranges are the
/// table's.
std::vector<Option> effectOptions(std::vector<render::post::Effect>& effects);

/// WWDC 2003 session 212's before/after demo: the original left of a divider, the result right of it.
struct BeforeAfter {
  bool on = false;
  float divider = 0.5f;
  /// "before-after" [B] and "divider".
  std::vector<Option> options();
  /// The split to hand to FrameView::draw (0 when off).
  float split() const { return on ? divider : 0.0f; }
};

/// "sepia", "sobel:output=horizontal", ... → effects (the variants' chains).
std::vector<render::post::Effect> chainOf(const std::vector<std::string>& specs);

}  // namespace glint::scenes::post
