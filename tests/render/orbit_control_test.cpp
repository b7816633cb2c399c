// glint::OrbitControl, the viewer's mouse camera, against geometry computed here: the
// identity leaves a camera bit for bit, yaw turns about world up keeping the distance,
// pitch stops short of the poles, zoom scales the distance, pan moves eye and target
// alike, and a drag there and back returns to the defined camera.
#include "glint/core/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace glint;
using glint::Camera;
using glint::OrbitControl;

namespace {

// A camera like the scenes': off-axis target, eye above it, 16:9.
Camera defined() { return Camera::lookAt({2.2f, 3.4f, 5.6f}, {0.9f, 0.8f, -0.4f}, {0, 1, 0}, 45.0f, 16.0f / 9.0f, 0.5f, 60.0f); }

float elevation(vec3 offset) { return std::asin(offset.y / glm::length(offset)); }
float azimuth(vec3 offset) { return std::atan2(offset.x, offset.z); }  // 0 on +Z, positive towards +X

bool sameBits(const Camera& a, const Camera& b) {
  return std::memcmp(&a.view, &b.view, sizeof a.view) == 0 && std::memcmp(&a.projection, &b.projection, sizeof a.projection) == 0 &&
         std::memcmp(&a.position, &b.position, sizeof a.position) == 0 && std::memcmp(&a.target, &b.target, sizeof a.target) == 0;
}

// The eye-space position of p: the target must stay on the view axis (x = y = 0).
vec3 inEye(const Camera& c, vec3 p) { return vec3(c.view * vec4(p, 1.0f)); }

void expectNear(vec3 a, vec3 b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

}  // namespace

TEST(OrbitControl, IdentityReturnsTheDefinedCameraBitForBit) {
  const OrbitControl identity;
  EXPECT_TRUE(identity.isIdentity());
  // Also a camera built by hand, whose view matrix is not a lookAt's: returned as it is,
  // not rebuilt from its eye and orientation (which would move its bits).
  const Camera handBuilt{glm::translate(glm::rotate(mat4(1.0f), 0.4f, glm::normalize(vec3(1.0f, 2.0f, 0.5f))),
                                        vec3(-0.3f, 0.7f, -5.1f)),
                         glm::perspective(0.8f, 1.25f, 0.1f, 50.0f), vec3(0.31f, -0.69f, 5.12f), vec3(0.0f)};
  const Camera cams[] = {defined(), Camera::orbit({0, 0, 0}, 4.6f, 3.14159f, 0.12f, 40.0f, 1.5f),
                         defined().cropped({640, 360}, {320, 0}, {320, 360}), handBuilt};
  for (const Camera& c : cams) EXPECT_TRUE(sameBits(identity.apply(c), c));
}

TEST(OrbitControl, LookAtAndOrbitRememberTheirTarget) {
  EXPECT_EQ(defined().target, vec3(0.9f, 0.8f, -0.4f));
  EXPECT_EQ(Camera::orbit({1, 2, 3}, 4.0f, 0.3f, 0.2f, 45.0f, 1.0f).target, vec3(1, 2, 3));
  EXPECT_EQ(defined().cropped({640, 360}, {0, 0}, {320, 360}).target, defined().target);
}

TEST(OrbitControl, YawTurnsAboutWorldUpKeepingDistanceAndHeight) {
  const Camera c = defined();
  const vec3 before = c.position - c.target;
  OrbitControl control;
  control.yaw = 0.7f;
  const Camera moved = control.apply(c);
  const vec3 after = moved.position - moved.target;
  EXPECT_EQ(moved.target, c.target);
  EXPECT_NEAR(glm::length(after), glm::length(before), 1e-5f);
  EXPECT_NEAR(after.y, before.y, 1e-5f);  // about world up: the height does not change
  EXPECT_NEAR(azimuth(after) - azimuth(before), 0.7f, 1e-5f);
  // Still looking at the target, still upright (the right axis horizontal), same projection.
  const vec3 t = inEye(moved, moved.target);
  EXPECT_NEAR(t.x, 0.0f, 1e-5f);
  EXPECT_NEAR(t.y, 0.0f, 1e-5f);
  EXPECT_NEAR(t.z, -glm::length(before), 1e-4f);
  EXPECT_NEAR(moved.view[1][0], 0.0f, 1e-6f);  // right axis · world up
  EXPECT_EQ(moved.projection, c.projection);
  // The eye position and the view matrix agree: the eye is at the eye-space origin.
  expectNear(inEye(moved, moved.position), vec3(0.0f), 1e-5f);
}

TEST(OrbitControl, PitchRaisesTheEyeAndStopsShortOfThePoles) {
  const Camera c = defined();
  const vec3 before = c.position - c.target;
  OrbitControl control;
  control.pitch = 0.3f;
  vec3 after = control.apply(c).position - c.target;
  EXPECT_NEAR(elevation(after), elevation(before) + 0.3f, 1e-5f);
  EXPECT_NEAR(azimuth(after), azimuth(before), 1e-5f);  // straight up, not sideways
  EXPECT_NEAR(glm::length(after), glm::length(before), 1e-5f);

  // Dragged far past either pole: the stored pitch and the applied one stop at the limit.
  for (const float drag : {10.0f, -10.0f}) {
    OrbitControl dragged;
    dragged.orbitBy(0.0f, drag, c);
    const float limit = std::copysign(OrbitControl::kMaxElevation, drag);
    EXPECT_NEAR(dragged.pitch, limit - elevation(before), 1e-6f);
    const Camera moved = dragged.apply(c);
    after = moved.position - c.target;
    EXPECT_NEAR(elevation(after), limit, 1e-4f);
    EXPECT_GT(moved.view[1][1], 0.0f);  // the picture's up still points up in the world
    // A pitch set directly beyond the limit is clamped by apply() too.
    OrbitControl raw;
    raw.pitch = drag;
    EXPECT_NEAR(elevation(raw.apply(c).position - c.target), limit, 1e-4f);
  }
}

TEST(OrbitControl, ZoomScalesTheDistanceToTheTarget) {
  const Camera c = defined();
  const vec3 before = c.position - c.target;
  OrbitControl control;
  control.zoomBy(0.5f);
  EXPECT_FLOAT_EQ(control.zoom, 0.5f);
  const Camera moved = control.apply(c);
  expectNear(moved.position - moved.target, 0.5f * before, 1e-5f);
  EXPECT_EQ(moved.target, c.target);
  for (int i = 0; i < 100; ++i) control.zoomBy(0.5f);
  EXPECT_FLOAT_EQ(control.zoom, OrbitControl::kMinZoom);
  for (int i = 0; i < 100; ++i) control.zoomBy(2.0f);
  EXPECT_FLOAT_EQ(control.zoom, OrbitControl::kMaxZoom);
}

TEST(OrbitControl, PanMovesEyeAndTargetByTheSameVector) {
  const Camera c = defined();
  OrbitControl control;
  control.pan = {0.3f, -0.2f, 1.1f};
  const Camera moved = control.apply(c);
  expectNear(moved.position - c.position, control.pan, 1e-5f);
  expectNear(moved.target - c.target, control.pan, 1e-5f);
  EXPECT_EQ(moved.rotation(), c.rotation());  // same orientation: a pure translation
}

TEST(OrbitControl, PanByMovesThePointUnderTheTargetWithThePointer) {
  // The view is 2·d·tan(fov/2) high at the target: panning by a fraction f of it shifts
  // the old target by 2f in NDC y, and by 2f/aspect in NDC x.
  const Camera c = defined();
  const float aspect = 16.0f / 9.0f;
  for (const vec2 f : {vec2(0.25f, 0.0f), vec2(0.0f, -0.1f)}) {
    OrbitControl control;
    control.orbitBy(0.4f, 0.2f, c);  // on a turned view, along the turned view's axes
    control.zoomBy(0.7f);
    const vec4 clip = control.apply(c).viewProjection() * vec4(c.target, 1.0f);
    const vec2 before = vec2(clip) / clip.w;
    control.panBy(f, c);
    const vec4 clipAfter = control.apply(c).viewProjection() * vec4(c.target, 1.0f);
    const vec2 after = vec2(clipAfter) / clipAfter.w;
    EXPECT_NEAR(after.x - before.x, -2.0f * f.x / aspect, 1e-4f);
    EXPECT_NEAR(after.y - before.y, -2.0f * f.y, 1e-4f);
  }
}

TEST(OrbitControl, OrbitingAfterAPanTurnsAroundThePannedTarget) {
  const Camera c = defined();
  OrbitControl control;
  control.pan = {1.0f, 0.0f, -2.0f};
  control.yaw = 1.2f;
  control.pitch = -0.2f;
  const Camera moved = control.apply(c);
  EXPECT_NEAR(glm::length(moved.position - moved.target), glm::length(c.position - c.target), 1e-5f);
  expectNear(moved.target, c.target + control.pan, 1e-6f);
}

TEST(OrbitControl, ADragThereAndBackReturnsTheDefinedCamera) {
  const Camera c = defined();
  OrbitControl control;
  control.orbitBy(0.9f, -0.25f, c);
  control.orbitBy(-0.9f, 0.25f, c);
  control.panBy({0.3f, 0.2f}, c);
  control.panBy({-0.3f, -0.2f}, c);
  const Camera back = control.apply(c);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(back.view[i][j], c.view[i][j], 1e-5f) << i << "," << j;
  expectNear(back.position, c.position, 1e-5f);
  expectNear(back.target, c.target, 1e-5f);
}
