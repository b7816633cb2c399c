#pragma once
// Shared pieces of the bump/* scenes: the demo's textures (procedural, made with the same
// height → normal function as `glint normalmap`), the light circling the polygon, and a
// marker showing where the light is. Private to src/scenes/bump.
#include "glint/gl/objects.h"
#include "glint/image/heightfield.h"
#include "glint/image/normalmap.h"
#include "glint/render/bump/textures.h"
#include "glint/core/camera.h"

#include <cmath>

namespace glint::scenes::bump {

constexpr int kTextureSize = 256;
constexpr float kBrickBumpiness = 10.0f;  // NormalMapOptions::scale: bricks stand out clearly

/// Which height field the normal map comes from.
enum class Relief {
  Bricks,  ///< a brick wall: bevelled edges, pitted faces, recessed mortar
  Bumps    ///< round bumps and dents: the clearest check of the lighting's sign
};

struct DemoTextures {
  gl::Texture normalMap;  ///< RGBA8, (n + 1)/2, mipmapped, repeating
  gl::Texture base;       ///< RGBA8 colours ("an unlit base texture")
};

inline DemoTextures makeDemoTextures(Relief relief) {
  using render::bump::uploadImage;
  if (relief == Relief::Bumps) {
    Image plain(kTextureSize, kTextureSize, 4);
    for (int y = 0; y < kTextureSize; ++y)
      for (int x = 0; x < kTextureSize; ++x) {
        const vec3 c{0.92f, 0.86f, 0.70f};
        for (int k = 0; k < 3; ++k) plain.set(x, y, k, c[k]);
        plain.set(x, y, 3, 1.0f);
      }
    return {uploadImage(heightToNormalMap(makeBumpsHeight(kTextureSize, 4), {.scale = 24.0f, .wrap = true}),
                        {.label = "bumps-normal-map"}),
            uploadImage(plain, {.label = "bumps-base"})};
  }
  return {uploadImage(heightToNormalMap(makeBrickHeight(kTextureSize), {.scale = kBrickBumpiness, .wrap = true}),
                      {.label = "brick-normal-map"}),
          uploadImage(makeBrickAlbedo(kTextureSize), {.label = "brick-base"})};
}

/// "A positional light source circling the source texture": its position in the polygon's
/// local frame at `time` (radius and height in polygon half-sizes, speed in radians/s).
inline vec3 circlingLight(double time, float radius, float height, float speed) {
  const float a = speed * float(time);
  return {radius * std::cos(a), radius * std::sin(a), height};
}

/// The camera of the DOT3 scenes: looking at the origin from the front and a little above.
inline glint::Camera dot3Camera(ivec2 size, float distance = 2.9f) {
  return glint::Camera::lookAt({0.0f, 0.75f, distance}, {0.0f, -0.08f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f,
                                float(size.x) / float(size.y));
}

}  // namespace glint::scenes::bump
