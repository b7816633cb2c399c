// Every pass that renders into a target of its own puts the caller's framebuffer binding and
// viewport back (render::SavedTarget, issue 47): the caller's target is bound with an odd
// viewport, each pass runs, and the GL state is read before and after.
#include "support/gl_test.h"

#include "glint/gl/render_target.h"
#include "glint/image/image.h"
#include "glint/image/normalmap.h"
#include "glint/post/effects.h"
#include "glint/render/bump/height_to_normal.h"
#include "glint/core/camera.h"
#include "glint/render/env/dynamic_cube.h"
#include "glint/render/env/environment.h"
#include "glint/render/post/chain.h"
#include "glint/render/post/passes.h"
#include "glint/render/rtt/rtt.h"
#include "glint/render/state.h"
#include "glint/render/water/wave_simulation.h"

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

using namespace glint;
using glint::testing::GlTest;

namespace {

struct Bound {
  GLint draw = 0, read = 0;
  std::array<GLint, 4> viewport{};
  bool operator==(const Bound&) const = default;
};

Bound bound() {
  Bound b;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &b.draw);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &b.read);
  glGetIntegerv(GL_VIEWPORT, b.viewport.data());
  return b;
}

gl::Texture texture(int size, GLenum format = GL_RGBA8) {
  gl::Texture t(GL_TEXTURE_2D, "saved-target-test");
  t.storage(format, size, size);
  return t;
}

}  // namespace

TEST_F(GlTest, EveryOffscreenPassPutsTheCallersFramebufferAndViewportBack) {
  const gl::RenderTarget caller({64, 48}, GL_RGBA8, "caller");
  const gl::RenderTarget other({32, 32}, GL_RGBA8, "other-read");
  Image equirect(16, 8, 4);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) equirect.set(x, y, 0, float(x) / 15.0f);
  const gl::Texture frame = texture(32);
  const gl::Texture result = texture(32);
  const gl::Texture height = texture(32, GL_R32F);

  const std::vector<std::pair<std::string, std::function<void()>>> passes = {
      {"env::cubeFromEquirect", [&] { (void)render::env::cubeFromEquirect(equirect, {.faceSize = 8, .samples = 1}); }},
      {"env::sphereMapFromCube",
       [&] {
         const gl::Texture cube = render::env::cubeFromEquirect(equirect, {.faceSize = 8, .samples = 1});
         const Bound before = bound();
         (void)render::env::sphereMapFromCube(cube, {.size = 16, .samples = 1});
         EXPECT_EQ(bound(), before) << "sphereMapFromCube alone";
       }},
      {"env::DynamicCubeMap::render",
       [&] { render::env::DynamicCubeMap(8).render(vec3(0.0f), [](const glint::Camera&) {}); }},
      {"water::WaveSimulation::addDrop",
       [&] { render::water::WaveSimulation({16, 16}).addDrop({.centre = vec2(8.0f)}); }},
      {"water::WaveSimulation::step", [&] { render::water::WaveSimulation({16, 16}).step(); }},
      {"rtt::FramebufferTexture::render", [&] { render::rtt::FramebufferTexture(16).render([](ivec2) {}); }},
      {"bump::HeightToNormalPass::run", [&] { render::bump::HeightToNormalPass().run(height, result); }},
      {"post::SepiaPass (fragment)",
       [&] { render::post::SepiaPass(render::post::PassStage::Fragment).run(frame, result, {}); }},
      {"post::KuwaharaPass (fragment)",
       [&] { render::post::KuwaharaPass(render::post::PassStage::Fragment).run(frame, result, {}); }},
      {"post::Chain::run", [&] {
         const std::vector<std::string> specs{"sepia", "kuwahara", "edges"};
         render::post::Chain({32, 32}, post::parseEffects(specs)).run(frame);
       }}};
  for (const auto& [name, run] : passes) {
    caller.framebuffer().bind(GL_DRAW_FRAMEBUFFER);
    other.framebuffer().bind(GL_READ_FRAMEBUFFER);
    glViewport(3, 5, 17, 19);
    const Bound before = bound();
    ASSERT_NE(before.draw, 0);
    ASSERT_NE(before.draw, before.read);
    run();
    EXPECT_EQ(bound(), before) << name << " left another framebuffer or viewport behind";
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
