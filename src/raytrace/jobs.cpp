// The turns of the hemisphere sets (raytrace/jobs.h).
#include "glint/raytrace/jobs.h"

#include <cmath>

namespace glint::raytrace {

float radicalInverse(std::uint32_t i) {
  i = (i << 16u) | (i >> 16u);
  i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
  i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
  i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
  i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
  return float(i) * 2.3283064365386963e-10f;
}

const HemisphereTurns& hemisphereTurns() {
  static const HemisphereTurns turns = [] {
    HemisphereTurns t;
    for (std::uint32_t i = 0; i < HemisphereTurns::kCount; ++i) {
      const float phi = 2.0f * kPi * radicalInverse(i);
      t.cosine[i] = std::cos(phi);
      t.sine[i] = std::sin(phi);
    }
    return t;
  }();
  return turns;
}

}  // namespace glint::raytrace
