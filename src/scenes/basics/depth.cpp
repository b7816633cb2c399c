// basics/depth — the lecture's depth-buffer example and its API (the OpenGL III lecture,
// "Depth Buffer Example", "OpenGL API for Depth Testing").
//
// The depth buffer is cleared to 0.8 (glClearDepth), then two primitives are drawn
// in order with the variant's glDepthFunc:
//   first  (red)   flat at window z 0.65 — under LESS it replaces 0.8;
//   second (blue)  tilted, window z from 0.52 (left) to 0.92 (right), 0.72 at its
//                  centre — under LESS that 0.72 is rejected where the red 0.65 is.
// So every function shows a different picture, and the mask-off variant shows
// what glDepthMask(GL_FALSE) on the first primitive does.
#include "glint/render/gpu_mesh.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <memory>

namespace glint::scenes {
namespace {

constexpr float kClearDepth = 0.8f;
const vec4 kClearColor{0.12f, 0.14f, 0.18f, 1.0f};

// Window z → NDC z for depth range [0, 1]: z_ndc = 2 z_win − 1.
float ndc(float windowZ) { return 2.0f * windowZ - 1.0f; }

Mesh quad(vec2 lo, vec2 hi, float zLeft, float zRight) {
  Mesh m;
  m.positions = {{lo.x, lo.y, ndc(zLeft)}, {hi.x, lo.y, ndc(zRight)}, {hi.x, hi.y, ndc(zRight)}, {lo.x, hi.y, ndc(zLeft)}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

struct FuncVariant {
  const char* name;
  GLenum func;
  bool maskFirst;
  const char* description;
};

const FuncVariant kVariants[] = {
    {"less", GL_LESS, true, "GL_LESS (the default): red (0.65) beats the cleared 0.8; blue wins only where it is nearer than red, and loses to the clear value past z 0.8 on the right."},
    {"lequal", GL_LEQUAL, true, "GL_LEQUAL: like LESS here, since no fragment ties exactly with a stored depth."},
    {"greater", GL_GREATER, true, "GL_GREATER: red (0.65 > 0.8 is false) is never drawn; only blue's far right part, beyond z 0.8, passes."},
    {"gequal", GL_GEQUAL, true, "GL_GEQUAL: like GREATER here."},
    {"equal", GL_EQUAL, true, "GL_EQUAL: no fragment's depth equals the stored 0.8, so nothing but the background is drawn."},
    {"notequal", GL_NOTEQUAL, true, "GL_NOTEQUAL: every fragment passes (none equals what is stored), so draw order decides: blue over red."},
    {"always", GL_ALWAYS, true, "GL_ALWAYS: the depth test never rejects; the painter's algorithm, blue drawn last is on top."},
    {"never", GL_NEVER, true, "GL_NEVER: every fragment is rejected; only the clear colour remains."},
    {"mask-off", GL_LESS, false, "GL_LESS with glDepthMask(GL_FALSE) while drawing red: red is drawn but leaves 0.8 in the depth buffer, so blue covers it wherever blue is nearer than 0.8."},
};

class DepthScene final : public Scene {
public:
  explicit DepthScene(const FuncVariant& v)
      : m_variant(v),
        m_first(quad({-0.7f, -0.5f}, {0.2f, 0.6f}, 0.65f, 0.65f), kRed, "depth-first"),
        m_second(quad({-0.3f, -0.6f}, {0.7f, 0.4f}, 0.52f, 0.92f), kBlue, "depth-second"),
        m_program(gl::Program::fromFiles({"basics/colored.vert", "basics/colored.frag"})) {}

  void render(const FrameInput& frame) override {
    frame.target.bind();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, &kClearColor.r, kClearDepth);
    m_program.use();
    render::PipelineState{.depthTest = true, .depthFunc = m_variant.func, .depthWrite = m_variant.maskFirst}.apply();
    m_first.draw();
    render::PipelineState{.depthTest = true, .depthFunc = m_variant.func}.apply();
    m_second.draw();
  }

private:
  static constexpr vec4 kRedColor{0.85f, 0.2f, 0.2f, 1.0f};
  // Blue is shaded by its depth (bright = near, dark = far) so its tilt is visible.
  static constexpr vec4 kBlueNear{0.45f, 0.65f, 1.0f, 1.0f};
  static constexpr vec4 kBlueFar{0.08f, 0.16f, 0.45f, 1.0f};
  static constexpr vec4 kRed[4] = {kRedColor, kRedColor, kRedColor, kRedColor};
  static constexpr vec4 kBlue[4] = {kBlueNear, kBlueFar, kBlueFar, kBlueNear};

  FuncVariant m_variant;
  render::GpuMesh m_first;
  render::GpuMesh m_second;
  gl::Program m_program;
};

}  // namespace

void registerBasicsDepth(Registry& registry) {
  SceneDesc desc{
      .name = "basics/depth",
      .summary = "The depth test: depth cleared to 0.8, a red primitive at 0.65, a tilted blue one through 0.72 "
                 "(the OpenGL III lecture's depth-buffer example), one variant per glDepthFunc.",
      .defaultSize = {500, 500},
  };
  for (const auto& v : kVariants) desc.variants.push_back({v.name, v.description});
  desc.create = [](int variant) -> std::unique_ptr<Scene> {
    return std::make_unique<DepthScene>(kVariants[variant]);
  };
  registry.add(std::move(desc));
}

}  // namespace glint::scenes
