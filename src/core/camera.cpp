// The orbit control's math (include/glint/core/camera.h).
#include "glint/core/camera.h"

#include <algorithm>
#include <utility>

namespace glint {

namespace {

/// The world-space right axis of a view: the first row of its rotation.
vec3 rightAxis(const Camera& camera) { return glm::transpose(camera.rotation())[0]; }

/// The pitch range that keeps the eye within ±kMaxElevation of the target's horizontal
/// plane, always including 0 (a camera defined beyond the limit keeps its own view).
std::pair<float, float> pitchRange(const Camera& defined) {
  const vec3 offset = defined.position - defined.target;
  const float distance = glm::length(offset);
  const float elevation = distance > 0.0f ? std::asin(std::clamp(offset.y / distance, -1.0f, 1.0f)) : 0.0f;
  return {std::min(0.0f, -OrbitControl::kMaxElevation - elevation), std::max(0.0f, OrbitControl::kMaxElevation - elevation)};
}

}  // namespace

Camera OrbitControl::apply(const Camera& defined) const {
  if (isIdentity()) return defined;
  const auto [lo, hi] = pitchRange(defined);
  // Rotating about the right axis by +θ tilts the view direction up and so lowers the
  // eye: a positive pitch (eye up) is a rotation by −pitch.
  const mat3 turn = mat3(glm::rotate(mat4(1.0f), yaw, vec3(0.0f, 1.0f, 0.0f))) *
                    mat3(glm::rotate(mat4(1.0f), -std::clamp(pitch, lo, hi), rightAxis(defined)));
  const vec3 target = defined.target + pan;
  const vec3 eye = target + turn * (zoom * (defined.position - defined.target));
  // The camera's frame turns with the eye: world → eye is the defined rotation after
  // undoing the turn, so the target stays where it was in the picture.
  const mat3 rotation = defined.rotation() * glm::transpose(turn);
  mat4 view(rotation);
  view[3] = vec4(-(rotation * eye), 1.0f);
  return {view, defined.projection, eye, target};
}

void OrbitControl::orbitBy(float dYaw, float dPitch, const Camera& defined) {
  const auto [lo, hi] = pitchRange(defined);
  yaw = std::remainder(yaw + dYaw, 2.0f * kPi);  // bounded: no precision lost after many turns
  pitch = std::clamp(pitch + dPitch, lo, hi);
}

void OrbitControl::zoomBy(float factor) { zoom = std::clamp(zoom * factor, kMinZoom, kMaxZoom); }

void OrbitControl::panBy(vec2 fraction, const Camera& defined) {
  const Camera current = apply(defined);
  const mat3 axes = glm::transpose(current.rotation());  // columns: right, up, backwards
  // A perspective projection's [1][1] is 1/tan(fovY/2): the view is 2·d·tan(fovY/2) high at distance d.
  const float height = 2.0f * glm::length(current.position - current.target) / defined.projection[1][1];
  pan += height * (fraction.x * axes[0] + fraction.y * axes[1]);
}

}  // namespace glint
