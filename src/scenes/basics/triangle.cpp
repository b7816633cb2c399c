// basics/triangle — the lecture's simple triangle (the OpenGL III lecture, "OpenGL API Example").
//
// glShadeModel(GL_SMOOTH); glEnable(GL_DEPTH_TEST);
// red (-0.8, 0.8, 0.3), green (0.8, 0.8, -0.2), blue (0, -0.8, -0.2) in NDC; the
// lecture's viewport is 500×500, which gives window coordinates (50,450),
// (450,450), (250,50) and window depths 0.65, 0.4, 0.4.
#include "glint/render/depth_view.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <memory>

namespace glint::scenes {
namespace {

// The lecture's data, exposed for tests through the scene's mesh.
Mesh lectureTriangle() {
  Mesh m;
  m.positions = {{-0.8f, 0.8f, 0.3f}, {0.8f, 0.8f, -0.2f}, {0.0f, -0.8f, -0.2f}};
  m.indices = {0, 1, 2};
  return m;
}

// glColor4ub(255,0,0,255), (0,255,0,255), (0,0,255,255)
const vec4 kColors[] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};

// The lecture's tip: "set your clear color to something other than black".
const vec4 kClearColor{0.12f, 0.14f, 0.18f, 1.0f};

class TriangleScene final : public Scene {
public:
  explicit TriangleScene(bool showDepth)
      : m_showDepth(showDepth),
        m_mesh(lectureTriangle(), kColors, "lecture-triangle"),
        m_program(gl::Program::fromFiles({"basics/colored.vert", "basics/colored.frag"})) {
    if (m_showDepth) m_depthView = render::DepthView(false);
  }

  void render(const FrameInput& frame) override {
    if (!m_showDepth) {
      frame.target.bind();
      drawTriangle();
      return;
    }
    // Depth lives in a texture of our own so it can be shown as an image.
    if (m_offscreen.size() != frame.target.size) m_offscreen = gl::RenderTarget(frame.target.size, GL_RGBA8, "triangle-depth");
    m_offscreen.target().bind();
    drawTriangle();
    frame.target.bind();
    m_depthView.draw(m_offscreen.depthStencil());
  }

private:
  void drawTriangle() const {
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, &kClearColor.r, 1.0);
    render::PipelineState{.depthTest = true, .depthFunc = GL_LESS}.apply();
    m_program.use();
    m_mesh.draw();
  }

  bool m_showDepth;
  render::GpuMesh m_mesh;
  gl::Program m_program;
  render::DepthView m_depthView;
  gl::RenderTarget m_offscreen;
};

}  // namespace

void registerBasicsTriangle(Registry& registry) {
  registry.add({
      .name = "basics/triangle",
      .summary = "The lecture's simple triangle: NDC vertices, smooth colour interpolation, depth test (the OpenGL III lecture).",
      .variants = {{"color", "Red, green and blue vertices interpolated across the triangle (glShadeModel(GL_SMOOTH))."},
                   {"depth", "The depth buffer visualized: white = 1.0 (far, the clear value), black = 0.0 (near); "
                             "window z 0.65 at the red corner, 0.4 at the others."}},
      .defaultSize = {500, 500},
      .create = [](int variant) -> std::unique_ptr<Scene> { return std::make_unique<TriangleScene>(variant == 1); },
  });
}

}  // namespace glint::scenes
