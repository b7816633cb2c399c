#pragma once
// glint/core/camera.h — a perspective camera as the matrices shaders need (no GL: the
// renderers, the CPU pipeline, the shadow worlds and the viewer share it).
//
// A Camera is plain data: view and projection matrices, the eye position in world space
// and the point it looks at. Build one with lookAt() or orbit() (both right-handed, GL
// clip space, depth [−1, 1] → window [0, 1]):
//
/// ```cpp
/// #include <glint/gl/shader.h>
/// const auto cam = glint::Camera::orbit({0, 0, 0}, 4.5f, 0.0f, 0.15f, 45.0f, 16.0f / 9.0f);
/// const auto program = glint::gl::Program::fromFiles({"filtering/ground.vert", "filtering/ground.frag"});
/// program.set("uViewProj", cam.viewProjection());
/// ```
//
// An OrbitControl is a user's change to a camera — what `glint view` makes of mouse drags:
// it turns the eye around the camera's target, moves it nearer or further, and moves eye
// and target together. The identity control changes nothing, bit for bit:
//
/// ```cpp run
/// const auto cam = glint::Camera::orbit({0, 0, 0}, 4.5f, 0.0f, 0.15f, 45.0f, 16.0f / 9.0f);
/// glint::OrbitControl view;       // identity
/// view.orbitBy(0.3f, 0.1f, cam);  // 0.3 rad around world up, eye 0.1 rad higher
/// view.zoomBy(0.5f);              // half the distance to the target
/// const glint::Camera moved = view.apply(cam);
/// ```

#include "glint/core/math.h"

#include <cmath>

namespace glint {

struct Camera {
  mat4 view{1.0f};
  mat4 projection{1.0f};
  vec3 position{0.0f};  ///< eye in world space
  vec3 target{0.0f};    ///< the point the camera looks at (lookAt's target): what OrbitControl turns around

  mat4 viewProjection() const { return projection * view; }
  /// World → eye rotation (the upper 3×3 of a rigid view matrix).
  mat3 rotation() const { return mat3(view); }

  /// Looks from `eye` at `target`; fovY in degrees.
  static Camera lookAt(vec3 eye, vec3 target, vec3 up, float fovYDegrees, float aspect, float nearPlane = 0.1f,
                       float farPlane = 100.0f) {
    return {glm::lookAt(eye, target, up), glm::perspective(glm::radians(fovYDegrees), aspect, nearPlane, farPlane), eye,
            target};
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
    return {view, pick * projection, position, target};
  }

  /// Circles `target` at `distance`: azimuth 0 puts the eye on the +Z side looking along −Z,
  /// positive azimuth moves it towards +X; elevation (radians) lifts it above the XZ plane.
  static Camera orbit(vec3 target, float distance, float azimuth, float elevation, float fovYDegrees, float aspect,
                      float nearPlane = 0.1f, float farPlane = 100.0f) {
    const vec3 offset{std::sin(azimuth) * std::cos(elevation), std::sin(elevation), std::cos(azimuth) * std::cos(elevation)};
    return lookAt(target + distance * offset, target, {0.0f, 1.0f, 0.0f}, fovYDegrees, aspect, nearPlane, farPlane);
  }
};

/// A user's change to a camera, as plain data: yaw and pitch turn the eye around the
/// camera's target, zoom scales the distance between them, pan moves both. Applied to
/// whatever camera a scene defines (even an animated one), so the user's view follows
/// the scene. A default-constructed control is the identity: apply() returns the defined
/// camera unchanged, bit for bit — headless renders and reference images never move.
/// Meant for perspective cameras whose up is world +Y (every scene camera in glint).
struct OrbitControl {
  /// Highest elevation of the eye above (or below) the target's horizontal plane: short of
  /// the poles, where "around world up" has no meaning and the picture would spin.
  static constexpr float kMaxElevation = 85.0f * kPi / 180.0f;
  static constexpr float kMinZoom = 0.05f;  ///< nearest: 1/20 of the defined distance
  static constexpr float kMaxZoom = 20.0f;  ///< furthest: 20 times the defined distance

  float yaw = 0.0f;    ///< radians around world +Y through the target; positive moves the eye from +Z towards +X
  float pitch = 0.0f;  ///< radians about the view's right axis; positive raises the eye (kept short of the poles)
  float zoom = 1.0f;   ///< factor on the eye's distance to the target: 0.5 is twice as close
  vec3 pan{0.0f};      ///< world-space offset added to both eye and target

  /// True when apply() returns the defined camera as it is.
  bool isIdentity() const { return yaw == 0.0f && pitch == 0.0f && zoom == 1.0f && pan == vec3(0.0f); }

  /// The defined camera moved by this control: the eye turned by `pitch` about the view's
  /// right axis and by `yaw` about world up, both through `defined.target`, its distance
  /// times `zoom`, then eye and target moved by `pan`. The orientation turns with the
  /// eye (the target stays in the middle of the picture); the projection is kept, so
  /// apply before Camera::cropped. Pitch is limited here as orbitBy() limits it.
  Camera apply(const Camera& defined) const;

  /// Turns by (dYaw, dPitch) radians, keeping the eye's elevation within ±kMaxElevation for
  /// `defined` (a camera defined beyond that may keep its own elevation but not go further).
  void orbitBy(float dYaw, float dPitch, const Camera& defined);
  /// Scales the distance by `factor` (0.9: 10% closer), within [kMinZoom, kMaxZoom].
  void zoomBy(float factor);
  /// Moves eye and target by `fraction` of the current view's height at the target, along
  /// the current view's right (x) and up (y) axes: a drag of the mouse over h pixels in a
  /// window h pixels high is a fraction of 1, and the point under the target follows it.
  void panBy(vec2 fraction, const Camera& defined);
};

}  // namespace glint
