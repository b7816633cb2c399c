#pragma once
// Shared set-up of the env/* scenes: the environment, the views, the mirror objects and
// the sphere-map figures quoted in the gallery. Private to src/scenes/env.
#include "glint/image/envmap.h"
#include "glint/mesh/mesh.h"
#include "glint/core/camera.h"
#include "glint/render/env/environment.h"

#include <fmt/format.h>

#include <string>
#include <vector>

namespace glint::scenes::env {

constexpr const char* kEnvironment = "courtyard";  // data/env/courtyard.exr (scripts/setup)
constexpr int kFaceSize = 256;                     // the equirect's 1024 texels / 4 faces around
constexpr int kSphereMapSize = 512;                // matches the cube map head-on (texels/radian)
constexpr float kDistance = 4.6f;
constexpr float kElevation = 0.12f;                // radians: a little above the objects
constexpr float kFovY = 40.0f;

/// The two views of the WWDC 2001 talk's demo: the one the sphere map is made for, and behind.
struct View {
  const char* name;
  float azimuth;  ///< radians around the objects; 0 = the sphere map's view
  const char* description;
};

inline glint::Camera viewCamera(float azimuth, ivec2 size) {
  return glint::Camera::orbit({0.0f, 0.0f, 0.0f}, kDistance, azimuth, kElevation, kFovY,
                               float(size.x) / float(size.y));
}

/// The frame the sphere map is generated for: the front view's eye space.
inline mat3 sphereMapFrame(ivec2 size) { return viewCamera(0.0f, size).rotation(); }

inline gl::Texture loadEnvironmentCube(int faceSize = kFaceSize) {
  const Image equirect = render::env::loadEquirect(render::env::findEnvironment(kEnvironment));
  return render::env::cubeFromEquirect(equirect, {.faceSize = faceSize});
}

/// A mirror ball and a torus side by side: the ball shows the whole environment, the
/// torus's saddle regions show how a lookup copes with quickly turning normals.
struct MirrorObject {
  Mesh mesh;
  mat4 model;
};
inline std::vector<MirrorObject> mirrorPair() {
  mat4 torus = glm::translate(mat4(1.0f), {1.25f, 0.0f, 0.0f});
  torus = glm::rotate(torus, glm::radians(65.0f), {1.0f, 0.0f, 0.3f});
  return {{makeUvSphere(0.95f, 96, 48), glm::translate(mat4(1.0f), {-1.15f, 0.0f, 0.0f})},
          {makeTorus(0.72f, 0.3f, 96, 48), torus}};
}
inline std::vector<MirrorObject> mirrorBall() { return {{makeUvSphere(1.35f, 128, 64), mat4(1.0f)}}; }

/// The sphere map's figures (image/envmap.h) for the gallery text.
inline std::string sphereMapFigures() {
  const auto c = glint::sphereMapCoverage(kSphereMapSize);
  const auto side = glint::sphereMapResolution(kSphereMapSize, kPi / 2);
  const auto rear = glint::sphereMapResolution(kSphereMapSize, kPi * 150.0 / 180.0);
  return fmt::format(
      "Sphere map {0}²: {1:.1f}% of texels wasted (the WWDC 2001 talk: about 20%), {2:.1f}% show the front half, {3:.1f}% the back "
      "half. Effective resolution in texels/radian: {4:.0f} head-on, {5:.0f} at 90°, {6:.0f} at 150°, 0 straight back "
      "(the singularity); the {7}² cube map has ≥ {8:.0f} in every direction. Over the front half the sphere map "
      "equals a {9:.0f}² cube map; {10:.0f}k texels against the cube map's {11:.0f}k.",
      kSphereMapSize, 100 * c.wastedFraction, 100 * c.frontFraction, 100 * c.backFraction,
      glint::sphereMapResolution(kSphereMapSize, 0).radial, side.radial, rear.radial, kFaceSize,
      glint::cubeMapResolution(kFaceSize), glint::equivalentCubeFaceSize(kSphereMapSize, kPi / 2),
      kSphereMapSize * kSphereMapSize / 1000.0, 6.0 * kFaceSize * kFaceSize / 1000.0);
}

}  // namespace glint::scenes::env
