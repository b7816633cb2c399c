#pragma once
// glint/render/water/field_view.h — a simulation texture shown as a picture: the wave
// heights as gray levels (the VGP353 lecture: "the resulting texture can be used as a gray-scale
// texture") or a normal map as its colours, centred in the viewport at the largest square
// that fits, texel for texel crisp (nearest filtering).

#include "glint/gl/objects.h"
#include "glint/render/gpu_mesh.h"

namespace glint::render::water {

enum class FieldKind {
  Height,    ///< .r as gray: 0.5 + gain · h (rest level mid-gray, crests light, troughs dark)
  NormalMap  ///< .rgb as it is: the (n + 1)/2 colours (flat = (0.5, 0.5, 1), lilac-blue)
};

class FieldView {
public:
  FieldView();
  /// Clears the viewport (size `viewport`) to a dark border and draws `field` in the centred square.
  void draw(const gl::Texture& field, FieldKind kind, ivec2 viewport, float gain = 1.0f) const;

private:
  FullscreenPass m_pass;
};

}  // namespace glint::render::water
