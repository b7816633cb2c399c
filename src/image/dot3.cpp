#include "glint/image/dot3.h"

#include <algorithm>
#include <cmath>

namespace glint {

vec3 localLightVector(const quat& rotation, vec3 translation, vec3 localVertex, vec3 lightWorld) {
  const vec3 worldVertex = rotation * localVertex + translation;
  const vec3 l = glm::conjugate(rotation) * (lightWorld - worldVertex);  // inverse rotation of a unit quaternion
  const float length = glm::length(l);
  return length > 0.0f ? l / length : vec3(0.0f, 0.0f, 1.0f);
}

u8vec3 encodeLightVector(vec3 v) {
  u8vec3 c;
  for (int k = 0; k < 3; ++k) c[k] = std::uint8_t(std::lround((std::clamp(v[k], -1.0f, 1.0f) + 1.0f) * 0.5f * 255.0f));
  return c;
}

vec3 decodeLightVector(u8vec3 c) { return vec3(c) / 255.0f * 2.0f - 1.0f; }

float combineDot3Rgb(vec3 a, vec3 b) {
  const vec3 p = (a - 0.5f) * (b - 0.5f);
  return std::clamp(4.0f * (p.x + p.y + p.z), 0.0f, 1.0f);
}

}  // namespace glint
