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

  /// The part of this camera's picture that falls into a rectangle of the frame (`corner`
  /// = its lower-left pixel, `extent` its size, in a frame of `frameSize` pixels): drawn into
  /// that rectangle (gl::Target::region), rectangles drawn this way tile the same picture
  /// the whole camera draws into the whole frame — a split screen of one view.
  Camera cropped(ivec2 frameSize, ivec2 corner, ivec2 extent) const {
    // Region NDC x' = a·x + b, with a = W/w and b = (W − 2·x0 − w)/w (likewise y); applied
    // in clip space, the offset scales with w_clip.
    const vec2 full(frameSize), size(extent), lo(corner);
    const vec2 a = full / size, b = (full - 2.0f * lo - size) / size;
    mat4 pick(1.0f);
    pick[0][0] = a.x;
    pick[1][1] = a.y;
    pick[3][0] = b.x;
    pick[3][1] = b.y;
    return {view, pick * projection, position};
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
