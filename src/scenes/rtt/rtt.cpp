// rtt/texture — render to texture, both ways of the VGP353 lecture: (a) draw into the window and
// copy to a texture, (b) draw straight into the texture through a framebuffer object.
// The texture then covers a spinning cube; both variants show the same picture.
#include "glint/core/camera.h"
#include "glint/render/rtt/rtt.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint::scenes {
namespace {
namespace rtt = render::rtt;

const vec4 kContentClear{0.1f, 0.1f, 0.14f, 1.0f};

class RttScene final : public Scene {
public:
  explicit RttScene(bool copy)
      : m_copy(copy),
        m_program(gl::Program::fromFiles({"rtt/textured.vert", "rtt/textured.frag"})),
        m_cube(makeCube(1.3f), {}, "rtt-display-cube") {}

  std::vector<Option> options() override {
    return {{"texture-size", "texture edge in texels (copy-to-texture: must fit in the window)", &m_size, 16.0f, 2048.0f}};
  }

  void render(const FrameInput& frame) override {
    const float t = float(frame.time);
    const auto content = [&](ivec2 size) { m_content.draw(size, t); };
    const gl::Texture* texture = nullptr;
    if (m_copy) {
      if (!m_copyTexture || m_copyTexture->size() != m_size) m_copyTexture.emplace(m_size);
      m_copyTexture->render(frame.target, content, kContentClear);
      texture = &m_copyTexture->texture();
    } else {
      if (!m_fboTexture || m_fboTexture->size() != m_size) m_fboTexture.emplace(m_size);
      m_fboTexture->render(content, kContentClear);
      texture = &m_fboTexture->texture();
    }
    // The frame itself (for the copy method, the second clear of the window).
    frame.target.bind();
    render::PipelineState{.depthTest = true, .cull = true}.apply();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.32f, 0.34f, 0.38f, 1.0f));
    const ivec2 size = frame.target.size;
    const auto camera = frame.camera(glint::Camera::orbit(vec3(0.0f), 3.0f, 0.0f, 0.35f, 45.0f, float(size.x) / float(size.y)));
    mat4 model = glm::rotate(mat4(1.0f), 0.5f * t + 0.6f, vec3(0.0f, 1.0f, 0.0f));
    model = glm::rotate(model, 0.3f, vec3(1.0f, 0.0f, 0.0f));
    m_program.set("uModel", model);
    m_program.set("uViewProj", camera.viewProjection());
    texture->bind(0);
    m_program.use();
    m_cube.draw();
    glBindTextureUnit(0, 0);
  }

  std::string notes() const override {
    if (m_copy) {
      return fmt::format("Copy-to-texture: the content is drawn into the lower-left {0}x{0} of the window, copied with "
                         "glCopyTextureSubImage2D, mipmapped with glGenerateMipmap; the window is then cleared again "
                         "for the frame. A texture larger than the window is refused. `glint bench rtt` times both "
                         "methods.",
                         m_size);
    }
    return fmt::format("Framebuffer object: a {0}x{0} RGBA8 texture as colour attachment plus a depth-stencil "
                       "renderbuffer; the content is drawn straight into the texture, then glGenerateMipmap. No copy, "
                       "no window-size limit. `glint bench rtt` times both methods.",
                       m_size);
  }

private:
  bool m_copy;
  int m_size = 256;
  rtt::RttContent m_content;
  std::optional<rtt::CopyToTexture> m_copyTexture;
  std::optional<rtt::FramebufferTexture> m_fboTexture;
  gl::Program m_program;
  render::GpuMesh m_cube;
};

}  // namespace

void registerRttScenes(Registry& registry) {
  registry.add({.name = "rtt/texture",
                .summary = "Render to texture (the VGP353 lecture): copy from the window vs a framebuffer object with a texture "
                           "colour attachment and a depth-stencil renderbuffer; the result textures a spinning cube.",
                .variants = {{"copy", "draw into the window, glCopyTextureSubImage2D, glGenerateMipmap"},
                             {"fbo", "draw into the texture through a framebuffer object, glGenerateMipmap"}},
                .defaultTime = 1.0,
                .create = [](int variant) -> std::unique_ptr<Scene> { return std::make_unique<RttScene>(variant == 0); }});
}

}  // namespace glint::scenes
