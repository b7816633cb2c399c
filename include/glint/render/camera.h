#pragma once
// glint/render/camera.h — a perspective camera as the matrices shaders need.
//
// A Camera is plain data: view and projection matrices and the eye position in world
// space. Build one with lookAt() or orbit() (both right-handed, GL clip space, depth
// [−1, 1] → window [0, 1]):
//
//   auto cam = render::Camera::orbit({0, 0, 0}, 4.5f, 0.0f, 0.15f, 45.0f, 16.0f / 9.0f);
//   program.set("uViewProj", cam.viewProjection());

#include "glint/core/math.h"

#include <cmath>

namespace glint::render {

struct Camera {
  mat4 view{1.0f};
  mat4 projection{1.0f};
  vec3 position{0.0f};  ///< eye in world space

  mat4 viewProjection() const { return projection * view; }
  /// World → eye rotation (the upper 3×3 of a rigid view matrix).
  mat3 rotation() const { return mat3(view); }

  /// Looks from `eye` at `target`; fovY in degrees.
  static Camera lookAt(vec3 eye, vec3 target, vec3 up, float fovYDegrees, float aspect, float nearPlane = 0.1f,
                       float farPlane = 100.0f) {
    return {glm::lookAt(eye, target, up), glm::perspective(glm::radians(fovYDegrees), aspect, nearPlane, farPlane), eye};
  }

  /// Circles `target` at `distance`: azimuth 0 puts the eye on the +Z side looking along −Z,
  /// positive azimuth moves it towards +X; elevation (radians) lifts it above the XZ plane.
  static Camera orbit(vec3 target, float distance, float azimuth, float elevation, float fovYDegrees, float aspect,
                      float nearPlane = 0.1f, float farPlane = 100.0f) {
    const vec3 offset{std::sin(azimuth) * std::cos(elevation), std::sin(elevation), std::cos(azimuth) * std::cos(elevation)};
    return lookAt(target + distance * offset, target, {0.0f, 1.0f, 0.0f}, fovYDegrees, aspect, nearPlane, farPlane);
  }
};

}  // namespace glint::render
