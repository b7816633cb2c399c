#pragma once
// glint/render/env/dynamic_cube.h — a cube map re-rendered every frame from a point:
// the bubble demo's "local scenery" (the WWDC 2001 talk).
//
// The six faces are drawn one after another through one framebuffer object: each face
// of the cube texture in turn is the colour attachment (glNamedFramebufferTextureLayer),
// a depth renderbuffer the size of a face is shared by all six. After the sixth face
// glGenerateMipmap rebuilds the mip chain, so a reflecting object can filter it.
//
/// ```cpp
/// #include <glint/render/env/environment.h>
/// #include <glint/render/env/reflection.h>
/// namespace env = glint::render::env;
/// const glint::gl::Texture sky = env::cubeFromEquirect(env::loadEquirect(env::findEnvironment("courtyard")));
/// const env::Skybox skybox;  // the local scenery here: whatever the bubble should reflect
/// const env::Bubble bubble;
/// const glint::render::GpuMesh sphere(glint::makeUvSphere());
/// const glint::vec3 bubbleCentre(0.0f, 1.0f, 0.0f);
/// const glint::mat4 model = glm::scale(glm::translate(glint::mat4(1.0f), bubbleCentre), glint::vec3(0.5f));
/// const auto camera = glint::Camera::orbit(bubbleCentre, 3.0f, 0.0f, 0.2f, 45.0f, 16.0f / 9.0f);
/// const float time = 2.0f;
/// env::DynamicCubeMap local(128);
/// local.render(bubbleCentre, [&](const glint::Camera& face) { skybox.draw(sky, face); });
/// bubble.draw(sphere, model, camera, local.texture(), time);
/// ```
//
// Face cameras look along each face's major axis with a 90° field of view and the up
// vectors of the OpenGL cube map convention (−Y for the side faces, ±Z for ±Y), so what
// is drawn lands where a lookup by direction finds it.

#include "glint/gl/objects.h"
#include "glint/core/camera.h"

#include <functional>
#include <string_view>

namespace glint::render::env {

class DynamicCubeMap {
public:
  DynamicCubeMap() = default;
  /// RGBA8 faces of `size` texels with a full mip chain, plus a depth renderbuffer.
  explicit DynamicCubeMap(int size, std::string_view label = "dynamic-cube");

  /// The camera at `centre` that renders face `face` (0..5, GL order).
  static Camera faceCamera(int face, vec3 centre, float nearPlane = 0.05f, float farPlane = 100.0f);

  /// Renders all six faces: binds the framebuffer, sets the viewport, clears colour to
  /// `clear` and depth, calls draw(faceCamera) per face, then generates mipmaps. The
  /// caller's framebuffer binding and viewport are put back (render::SavedTarget).
  void render(vec3 centre, const std::function<void(const Camera&)>& draw, vec4 clear = vec4(0.0f, 0.0f, 0.0f, 1.0f),
              float nearPlane = 0.05f, float farPlane = 100.0f);

  const gl::Texture& texture() const { return m_cube; }
  int size() const { return m_size; }

private:
  int m_size = 0;
  gl::Texture m_cube;
  gl::Renderbuffer m_depth;
  gl::Framebuffer m_framebuffer;
};

}  // namespace glint::render::env
