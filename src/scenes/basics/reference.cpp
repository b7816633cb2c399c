// basics/reference — OpenGL and glint::raster (the reference CPU pipeline) side by side.
//
// Each variant is one setup (include/glint/scenes/reference.h): clip-space vertices and a
// raster::State per draw. OpenGL draws it (render/raster_gl.h applies the same state)
// into an offscreen target; glint::raster draws it on the CPU at the same size; the
// frame shows GL's picture left of the middle and the CPU's right of it, pixel for pixel,
// with a thin divider. Where the two agree the seam is invisible: the triangle, the
// depth buffer and the stencil counts continue straight across it. notes() reports the
// measured differences over the whole frame (tests/raster_gl checks them in bulk).
#include "glint/scenes/reference.h"

#include "glint/core/error.h"
#include "glint/raster/raster.h"
#include "glint/core/camera.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/raster_gl.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>

namespace glint::scenes {

namespace {

const vec4 kClearColor{0.12f, 0.14f, 0.18f, 1.0f};  // the lecture's tip: not black

raster::Vertex ndcVertex(float x, float y, float z, const vec4& color) { return {vec4(x, y, z, 1.0f), {color}}; }

/// The lecture's simple triangle with glEnable(GL_DEPTH_TEST) (the OpenGL III lecture).
ReferenceSetup lectureTriangle(bool showDepth) {
  ReferenceSetup s;
  s.view = showDepth ? ReferenceView::Depth : ReferenceView::Color;
  s.clearColor = kClearColor;
  s.draws.push_back({"the lecture's triangle: red (-0.8, 0.8, 0.3), green (0.8, 0.8, -0.2), blue (0, -0.8, -0.2)",
                     raster::State{.depthTest = true},
                     {ndcVertex(-0.8f, 0.8f, 0.3f, {1, 0, 0, 1}), ndcVertex(0.8f, 0.8f, -0.2f, {0, 1, 0, 1}),
                      ndcVertex(0.0f, -0.8f, -0.2f, {0, 0, 1, 1})}});
  return s;
}

/// Two triangles covering the NDC rectangle lo..hi, window depth zLeft → zRight across x.
std::vector<raster::Vertex> quad(vec2 lo, vec2 hi, float zLeft, float zRight, vec4 colorLeft, vec4 colorRight) {
  const auto ndcZ = [](float windowZ) { return 2.0f * windowZ - 1.0f; };  // depth range [0, 1]
  const raster::Vertex a = ndcVertex(lo.x, lo.y, ndcZ(zLeft), colorLeft), b = ndcVertex(hi.x, lo.y, ndcZ(zRight), colorRight),
                       c = ndcVertex(hi.x, hi.y, ndcZ(zRight), colorRight), d = ndcVertex(lo.x, hi.y, ndcZ(zLeft), colorLeft);
  return {a, b, c, a, c, d};
}

/// basics/depth/less: depth cleared to 0.8, red at 0.65, blue tilted 0.52 → 0.92.
ReferenceSetup depthLess() {
  ReferenceSetup s;
  s.clearColor = kClearColor;
  s.clearDepth = 0.8f;
  const vec4 red{0.85f, 0.2f, 0.2f, 1.0f}, blueNear{0.45f, 0.65f, 1.0f, 1.0f}, blueFar{0.08f, 0.16f, 0.45f, 1.0f};
  s.draws.push_back({"red quad at window z 0.65", raster::State{.depthTest = true},
                     quad({-0.7f, -0.5f}, {0.2f, 0.6f}, 0.65f, 0.65f, red, red)});
  s.draws.push_back({"blue quad, window z 0.52 (left) to 0.92 (right)", raster::State{.depthTest = true},
                     quad({-0.3f, -0.6f}, {0.7f, 0.4f}, 0.52f, 0.92f, blueNear, blueFar)});
  return s;
}

/// Six triangles rotated by 20° each around the centre, counted in the stencil buffer.
ReferenceSetup stencilCount(ivec2 size) {
  ReferenceSetup s;
  s.view = ReferenceView::Stencil;
  s.clearColor = vec4(0.0f);
  const raster::StencilFace count{.func = raster::CompareFunc::Always, .dppass = raster::StencilOp::Incr};
  const raster::State state{.stencilTest = true, .stencilFront = count, .stencilBack = count};
  const float aspect = float(size.y) / float(size.x);  // keep the star round on wide targets
  std::vector<raster::Vertex> star;
  for (int k = 0; k < 6; ++k) {
    for (int i = 0; i < 3; ++i) {
      const float a = glm::radians(90.0f + 20.0f * float(k) + 120.0f * float(i));
      star.push_back(ndcVertex(0.85f * std::cos(a) * aspect, 0.85f * std::sin(a) - 0.06f, 0.0f, vec4(1.0f)));
    }
  }
  s.draws.push_back({"six triangles rotated by 20°, glStencilOp(GL_KEEP, GL_KEEP, GL_INCR)", state, star});
  return s;
}

/// A checkered ground running behind the eye (near-plane clipping) and a standing triangle
/// whose top vertex is behind the eye (w < 0): clipping and perspective-correct colour.
ReferenceSetup perspective(ivec2 size) {
  ReferenceSetup s;
  s.clearColor = kClearColor;
  const auto camera = glint::Camera::lookAt({0.0f, 1.0f, 0.0f}, {0.0f, 0.6f, -4.0f}, {0, 1, 0}, 60.0f,
                                             float(size.x) / float(size.y), 0.1f, 40.0f);
  const mat4 viewProj = camera.viewProjection();
  auto clip = [&](vec3 p, vec4 color) { return raster::Vertex{viewProj * vec4(p, 1.0f), {color}}; };
  std::vector<raster::Vertex> ground;
  constexpr int kCells = 16;
  for (int j = 0; j < kCells; ++j) {
    for (int i = 0; i < kCells; ++i) {
      const vec4 c = (i + j) % 2 ? vec4(0.85f, 0.82f, 0.7f, 1) : vec4(0.3f, 0.35f, 0.45f, 1);
      const float x0 = -8.0f + float(i), z0 = -12.0f + float(j), x1 = x0 + 1.0f, z1 = z0 + 1.0f;
      ground.insert(ground.end(), {clip({x0, 0, z1}, c), clip({x1, 0, z1}, c), clip({x1, 0, z0}, c), clip({x0, 0, z1}, c),
                                   clip({x1, 0, z0}, c), clip({x0, 0, z0}, c)});
    }
  }
  s.draws.push_back({"16x16 checkered ground from z -12 to +4 (the eye is at z 0)", raster::State{.depthTest = true}, ground});
  s.draws.push_back({"standing triangle: red (-1.5, 0, -6), green (1.5, 0, -6), blue (0, 2.5, 1) behind the eye",
                     raster::State{.depthTest = true},
                     {clip({-1.5f, 0.0f, -6.0f}, {1, 0, 0, 1}), clip({1.5f, 0.0f, -6.0f}, {0, 1, 0, 1}),
                      clip({0.0f, 2.5f, 1.0f}, {0, 0, 1, 1})}});
  return s;
}

struct VariantInfo {
  const char* name;
  const char* description;
};

const VariantInfo kVariants[] = {
    {"triangle", "The lecture's triangle (the OpenGL III lecture): left OpenGL, right the CPU reference pipeline; the colour "
                 "gradients and edges continue across the divider."},
    {"triangle-depth", "The same triangle's depth buffer (white = 1.0, far): the z plane "
                       "Z = -0.000625x + 0.0003125y + 0.540625 from both pipelines."},
    {"depth-less", "basics/depth/less in both pipelines: depth cleared to 0.8, red at 0.65, blue tilted through "
                   "0.72; GL_LESS decides the same pixels."},
    {"stencil-count", "Six overlapping triangles counted with GL_INCR in the stencil buffer, shown in false colour "
                      "(1 blue ... 6 red): identical counts on both sides."},
    {"perspective", "A checkered ground clipped by the near plane and a triangle with a vertex behind the eye "
                    "(w < 0): clipping and perspective-correct colour in both pipelines."},
};

std::size_t variantIndex(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kVariants); ++i)
    if (name == kVariants[i].name) return i;
  std::string names;
  for (const auto& v : kVariants) names += (names.empty() ? "" : ", ") + std::string(v.name);
  fail(ErrorKind::Usage, "basics/reference has no variant '{}' (variants: {})", name, names);
}

}  // namespace

const std::vector<std::string>& referenceVariants() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& v : kVariants) out.emplace_back(v.name);
    return out;
  }();
  return names;
}

ReferenceSetup referenceSetup(std::string_view variant, ivec2 size) {
  const std::size_t index = variantIndex(variant);
  ReferenceSetup s;
  switch (index) {
    case 0: s = lectureTriangle(false); break;
    case 1: s = lectureTriangle(true); break;
    case 2: s = depthLess(); break;
    case 3: s = stencilCount(size); break;
    default: s = perspective(size); break;
  }
  s.variant = kVariants[index].name;
  s.description = kVariants[index].description;
  return s;
}

namespace {

/// The false colour of stencil count k out of maxCount, exactly as raster::stencilImage draws it.
vec4 countColor(std::uint32_t k, std::uint32_t maxCount) {
  const Image one = raster::falseColorImage(std::span(&k, 1), 1, 1, maxCount);
  return vec4(one.at(0, 0, 0), one.at(0, 0, 1), one.at(0, 0, 2), 1.0f);
}

class ReferenceScene final : public Scene {
public:
  explicit ReferenceScene(int variant)
      : m_variant(kVariants[variant].name), m_split("raster/split.frag"), m_solid("raster/solid.frag") {}

  void render(const FrameInput& frame) override {
    if (frame.target.size != m_size) prepare(frame.target.size);
    frame.target.bind();
    m_split.program().set("uSplitX", m_size.x / 2);
    m_split.program().set("uDepth", m_setup.view == ReferenceView::Depth);
    if (m_setup.view == ReferenceView::Depth) m_gl.depthStencil().bind(0);
    else m_gl.color().bind(0);
    m_cpu.bind(1);
    m_split.draw();
  }

  std::string notes() const override { return m_notes; }

private:
  /// Draws the setup in both pipelines at `size` (once per size: the scene is static).
  void prepare(ivec2 size) {
    m_size = size;
    m_setup = referenceSetup(m_variant, size);

    // -- CPU ----------------------------------------------------------------------------
    raster::Framebuffer fb(size.x, size.y, {.depth = raster::DepthFormat::Unorm24});  // as GL_DEPTH24_STENCIL8
    fb.clear(m_setup.clearColor, m_setup.clearDepth, m_setup.clearStencil);
    for (const ReferenceDraw& draw : m_setup.draws) raster::drawTriangles(fb, draw.state, draw.vertices);
    const std::uint32_t maxCount = std::max<std::uint32_t>(1, *std::max_element(fb.stencils().begin(), fb.stencils().end()));
    Image cpu = m_setup.view == ReferenceView::Depth     ? raster::depthImage(fb)
                : m_setup.view == ReferenceView::Stencil ? raster::stencilImage(fb, maxCount).withChannels(4)
                                                         : raster::colorImage(fb).converted(PixelType::U8);
    cpu.flipVertical();  // textures are bottom row first, like GL's window
    const bool depth = m_setup.view == ReferenceView::Depth;
    m_cpu = gl::Texture(GL_TEXTURE_2D, "reference-cpu");
    m_cpu.storage(depth ? GL_R32F : GL_RGBA8, size.x, size.y);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    m_cpu.upload(0, size.x, size.y, depth ? GL_RED : GL_RGBA, depth ? GL_FLOAT : GL_UNSIGNED_BYTE, cpu.bytes().data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);

    // -- OpenGL -------------------------------------------------------------------------
    m_gl = gl::RenderTarget(size, GL_RGBA8, "reference-gl");
    m_gl.framebuffer().bind();
    render::PipelineState{}.apply();  // clear with every write mask on
    m_gl.framebuffer().clearColor(0, &m_setup.clearColor.x);
    m_gl.framebuffer().clearDepthStencil(m_setup.clearDepth, m_setup.clearStencil);
    for (const ReferenceDraw& draw : m_setup.draws) {
      const render::RasterTriangles triangles(draw.vertices, "reference-draw");
      render::applyRasterState(draw.state, size);
      triangles.draw();
    }
    compare(fb, maxCount);
    if (m_setup.view == ReferenceView::Stencil) showStencilCounts(maxCount);
    glViewport(0, 0, size.x, size.y);
    glDepthRange(0.0, 1.0);
  }

  /// GL's stencil counts as colours, the classic way: one full-screen pass per count k
  /// under glStencilFunc(GL_EQUAL, k), in raster::stencilImage's colours.
  void showStencilCounts(std::uint32_t maxCount) {
    const vec4 black(0.0f, 0.0f, 0.0f, 1.0f);
    m_gl.framebuffer().clearColor(0, &black.x);
    glViewport(0, 0, m_size.x, m_size.y);
    for (std::uint32_t k = 1; k <= maxCount; ++k) {
      render::PipelineState{.depthTest = false,
                            .depthWrite = false,
                            .stencil = {.enabled = true, .front = {.func = GL_EQUAL, .ref = GLint(k), .writeMask = 0}}}
          .apply();
      m_solid.program().set("uColor", countColor(k, maxCount));
      m_solid.drawWithCurrentState();
    }
    render::PipelineState{.depthTest = true}.apply();
  }

  /// Reads GL's buffers back once and measures the differences for notes().
  void compare(const raster::Framebuffer& fb, std::uint32_t maxCount) {
    const int w = m_size.x, h = m_size.y;
    const Image glColor = gl::readColor(m_gl.framebuffer(), m_size);
    const Image glDepth = gl::readDepth(m_gl.framebuffer(), m_size);
    const Image glStencil = gl::readStencil(m_gl.framebuffer(), m_size);
    std::size_t stencilDiff = 0, colorDiff = 0;
    double maxColor = 0, maxDepth = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const int row = h - 1 - y;  // readback is top row first
        stencilDiff += glStencil.pixels<std::uint8_t>()[std::size_t(row * w + x)] != fb.stencil(x, y);
        maxDepth = std::max(maxDepth, double(std::abs(glDepth.at(x, row, 0) - fb.depth(x, y))));
        double worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(glColor.at(x, row, c) - fb.color(x, y)[c])));
        maxColor = std::max(maxColor, worst);
        colorDiff += worst > 1.5 / 255.0;
      }
    }
    m_notes = fmt::format(
        "Left: OpenGL ({}x{}), right: glint::raster on the CPU, same vertices and state. Over the whole frame: "
        "{} of {} pixels differ in colour by more than one 8-bit step (largest {:.0f}/255), {} in stencil{}, "
        "largest depth difference {:.2g}.",
        w, h, colorDiff, std::size_t(w) * std::size_t(h), maxColor * 255.0, stencilDiff,
        m_setup.view == ReferenceView::Stencil ? fmt::format(" (counts up to {})", maxCount) : std::string(), maxDepth);
  }

  std::string m_variant;
  ivec2 m_size{0};
  ReferenceSetup m_setup;
  render::FullscreenPass m_split;
  render::FullscreenPass m_solid;
  gl::RenderTarget m_gl;
  gl::Texture m_cpu;
  std::string m_notes;
};

}  // namespace

void registerBasicsReference(Registry& registry) {
  SceneDesc desc{
      .name = "basics/reference",
      .summary = "OpenGL (left) and glint::raster, the reference CPU pipeline (right), drawing the same vertices under "
                 "the same state: coverage, depth and stencil agree across the divider (the OpenGL III lecture).",
      .defaultSize = {500, 500},
  };
  for (const auto& v : kVariants) desc.variants.push_back({v.name, v.description});
  desc.create = [](int variant) -> std::unique_ptr<Scene> { return std::make_unique<ReferenceScene>(variant); };
  registry.add(std::move(desc));
}

}  // namespace glint::scenes
