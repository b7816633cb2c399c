// Per-fragment state against OpenGL: two-sided stencil with value and write masks,
// every stencil operation, every depth function, culling and front face, viewport and
// depth range, blending — the same operations in both pipelines (one raster::State
// each, applied to GL by render/raster_gl.h) on GL_DEPTH24_STENCIL8 like glint's render
// targets. Stencil buffers must be identical; depth and colour agree within tolerances.
//
// The one allowed stencil difference: a fragment whose depth is within the two depths'
// tolerances of the stored depth (cross_check.h). There the depth test's outcome depends
// on the last bits of two independently interpolated depths (each pipeline is
// self-consistent, they just round differently), so ReferenceRecorder finds such pixels
// while drawing the reference and they are excluded; the tests report how many and
// require them to be rare.
#include "cross_check.h"

#include "glint/mesh/mesh.h"
#include "glint/core/camera.h"
#include "support/gl_test.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace glint;
using glint::testing::GlTest;
using raster::CompareFunc;
using raster::StencilOp;

namespace {

constexpr int kWidth = 160, kHeight = 120;

// Depth: cross_check.h's model (24-bit quantization, 6e-8, is inside kDepthAbsolute).
// Colour, unblended: as in coverage_gl_test.cpp, two codes. Blended: llvmpipe blends in
// 8-bit fixed point, rounding after each multiply, the reference in float, rounding once;
// each blend may add a code of difference, damped by (1 − α) in later blends over the
// same pixel. Measured: 3 codes with up to ~10 layers here; 4 leaves one for other LLVM
// versions, while a wrong factor or equation is off by tens of codes.
constexpr double kColorTolerance = 2.0 / 255.0 + 1e-6;
constexpr double kBlendedColorTolerance = 4.0 / 255.0 + 1e-6;
// At most this fraction of the pixels may be excluded (ambiguous depth ties, clip edges):
// 300 large random triangles, most of them clipped, have long clip-created edges
// (measured: 1.8% of the pixels lie within kClipEdgeSlack of one; depth ties 0.05%).
constexpr double kMaxAmbiguousFraction = 0.03;

struct Pass {
  raster::State state;
  std::vector<raster::Vertex> vertices;
};

struct Result {
  raster::Framebuffer ref{kWidth, kHeight, {.depth = raster::DepthFormat::Unorm24}};
  test::ReferenceRecorder recorder{ref};
  test::GlBuffers gl;
  bool blended = false;
};

/// Clears both to (colour, depth, stencil) and runs every pass in both pipelines.
void run(Result& r, const std::vector<Pass>& passes, const vec4& clearColor, float clearDepth, int clearStencil) {
  test::GlCanvas canvas({kWidth, kHeight}, GL_DEPTH24_STENCIL8);
  canvas.clear(clearColor, clearDepth, clearStencil);
  r.ref.clear(clearColor, clearDepth, clearStencil);
  for (const Pass& pass : passes) {
    const render::RasterTriangles gpu(pass.vertices, "state-pass");
    canvas.draw(pass.state, gpu);
    r.recorder.draw(pass.state, pass.vertices);
    r.blended = r.blended || pass.state.blend.enabled;
  }
  r.gl = canvas.read();
}

void expectAgreement(const Result& r, const std::string& what) {
  const auto a = test::compareBuffers(r.recorder, r.ref, r.gl, [](int, int) { return true; },
                                      r.blended ? kBlendedColorTolerance : kColorTolerance);
  EXPECT_EQ(a.stencilMismatches, 0u) << what << ": first difference at " << a.firstStencilMismatch;
  EXPECT_EQ(a.depthOutside, 0u) << what << ": first at " << a.firstDepthOutside;
  EXPECT_EQ(a.colorOutside, 0u) << what << " (max " << a.maxColorError * 255 << "/255)";
  EXPECT_LE(double(a.excluded), kMaxAmbiguousFraction * double(a.pixels)) << what;
  std::printf("[ raster ] %-30s stencil mismatches %zu, depth err %.3g (%.2g px of gradient), colour err %.0f/255, "
              "excluded %zu depth-tie + %zu clip-edge of %zu px (%zu of those differ)\n",
              what.c_str(), a.stencilMismatches, a.maxDepthError, a.maxDepthShift, a.maxColorError * 255,
              a.excludedDepthTies, a.excludedClipEdges, a.pixels, a.excludedMismatches);
}

/// `count` random coloured triangles; every 7th vertex behind the eye (w < 0).
std::vector<raster::Vertex> randomTriangles(std::mt19937& rng, int count) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), c01(0.0f, 1.0f);
  std::vector<raster::Vertex> out;
  for (int k = 0; k < count * 3; ++k) {
    const float w = 0.3f + 2.0f * c01(rng);
    vec4 p(u(rng) * 1.3f * w, u(rng) * 1.3f * w, u(rng) * 1.2f * w, w);
    if (k % 7 == 0) p.w = -p.w;
    out.push_back({p, {vec4(c01(rng), c01(rng), c01(rng), c01(rng))}});
  }
  return out;
}

}  // namespace

TEST_F(GlTest, TwoSidedStencilDepthBlendAndCullingMatch) {
  // Three passes of the same 300 random triangles under different state, as a shadow
  // or decal technique would set it (throwaway check: /tmp/llvmcheck/scene.cpp).
  std::mt19937 rng(11);
  for (int variant = 0; variant < 3; ++variant) {
    raster::State state{
        .viewport = raster::Viewport{5, 3, kWidth - 16, kHeight - 6},
        .depthRange = {0.1, 0.9},
        .depthTest = true,
        .depthFunc = variant == 2 ? CompareFunc::GreaterEqual : CompareFunc::Less,
        .stencilTest = true,
        .stencilFront = {.func = CompareFunc::Always, .ref = 7, .sfail = StencilOp::Keep, .dpfail = StencilOp::DecrWrap,
                         .dppass = StencilOp::IncrWrap},
        .stencilBack = {.func = variant == 1 ? CompareFunc::Less : CompareFunc::Always, .ref = 2, .valueMask = 0x3,
                        .writeMask = 0xF7, .sfail = StencilOp::Invert, .dpfail = StencilOp::IncrWrap,
                        .dppass = StencilOp::Replace},
        .cull = variant == 1,
        .frontFace = variant == 1 ? raster::Winding::Cw : raster::Winding::Ccw,
        .blend = raster::BlendState::func(raster::BlendFactor::SrcAlpha, raster::BlendFactor::OneMinusSrcAlpha),
    };
    Result r;
    run(r, {{state, randomTriangles(rng, 300)}}, vec4(0.2f, 0.3f, 0.4f, 1.0f), variant == 2 ? 0.0f : 1.0f, 0);
    expectAgreement(r, "two-sided stencil, variant " + std::to_string(variant));
  }
}

TEST_F(GlTest, EveryDepthFunctionAndStencilOperationMatches) {
  // Each function decides between a first and a second layer of random triangles; the
  // stencil records each fragment's fate with a distinct operation per outcome, so a
  // single different decision shows as a stencil difference. The second layer
  // repeats a third of the first layer's triangles exactly: real depth ties (EQUAL,
  // LEQUAL, GEQUAL, NOTEQUAL decide them), which both pipelines reproduce bit for bit.
  const CompareFunc funcs[] = {CompareFunc::Never,   CompareFunc::Less,     CompareFunc::Equal,        CompareFunc::LessEqual,
                               CompareFunc::Greater, CompareFunc::NotEqual, CompareFunc::GreaterEqual, CompareFunc::Always};
  const StencilOp ops[] = {StencilOp::Keep, StencilOp::Zero,     StencilOp::Replace,  StencilOp::Incr,
                           StencilOp::Decr, StencilOp::IncrWrap, StencilOp::DecrWrap, StencilOp::Invert};
  for (int f = 0; f < 8; ++f) {
    std::mt19937 rng(100u + unsigned(f));
    const std::vector<raster::Vertex> first = randomTriangles(rng, 60);
    std::vector<raster::Vertex> second = randomTriangles(rng, 60);
    for (std::size_t k = 0; k + 3 <= second.size(); k += 9)
      std::copy(first.begin() + std::ptrdiff_t(k), first.begin() + std::ptrdiff_t(k + 3), second.begin() + std::ptrdiff_t(k));
    const raster::StencilFace face{.func = CompareFunc::NotEqual, .ref = 0x5A, .valueMask = 0xF0,
                                   .sfail = ops[f], .dpfail = ops[(f + 3) % 8], .dppass = ops[(f + 5) % 8]};
    const raster::State layer{.depthTest = true, .depthFunc = CompareFunc::LessEqual, .stencilTest = true,
                              .stencilFront = face, .stencilBack = face};
    raster::State tested = layer;
    tested.depthFunc = funcs[f];
    tested.depthMask = f % 2 == 0;  // and glDepthMask both ways
    Result r;
    run(r, {{layer, first}, {tested, second}}, vec4(0.1f, 0.1f, 0.1f, 1.0f), 0.5f, 0x33);
    expectAgreement(r, "depth func " + std::to_string(f));
  }
}

TEST_F(GlTest, ShadowVolumeStencilCountsMatch) {
  // The technique this oracle exists for: a receiver (ground and a box) drawn with depth,
  // then closed volumes with colour and depth writes off, z-fail counting (back faces
  // GL_INCR_WRAP and front faces GL_DECR_WRAP on depth fail). Non-zero stencil = inside.
  const auto camera = glint::Camera::lookAt({2.5f, 3.0f, 5.0f}, {0.0f, 0.3f, 0.0f}, {0, 1, 0}, 50.0f,
                                             float(kWidth) / float(kHeight), 0.5f, 30.0f);
  const mat4 viewProj = camera.viewProjection();
  auto transformed = [&](Mesh mesh, const mat4& model, vec4 color) {
    std::vector<raster::Vertex> out;
    for (std::uint32_t i : mesh.indices) out.push_back({viewProj * model * vec4(mesh.positions[i], 1.0f), {color}});
    return out;
  };
  std::vector<raster::Vertex> receiver = transformed(makeGrid(8, 8, 8.0f), mat4(1.0f), vec4(0.6f, 0.6f, 0.5f, 1));
  const auto box = transformed(makeCube(1.0f), glm::translate(mat4(1.0f), {0.8f, 0.5f, 0.3f}), vec4(0.8f, 0.3f, 0.2f, 1));
  receiver.insert(receiver.end(), box.begin(), box.end());
  std::vector<raster::Vertex> volumes = transformed(makeIcosphere(1.0f, 2), glm::translate(mat4(1.0f), {0.0f, 0.5f, 0.3f}), vec4(1));
  const auto column = transformed(makeCube(1.0f), glm::scale(glm::translate(mat4(1.0f), {0.7f, 0.0f, 0.4f}), {0.6f, 3.0f, 0.6f}), vec4(1));
  volumes.insert(volumes.end(), column.begin(), column.end());

  const raster::State depthPass{.depthTest = true};
  const raster::State zFail{
      .depthTest = true, .depthMask = false, .stencilTest = true,
      .stencilFront = {.dpfail = StencilOp::DecrWrap}, .stencilBack = {.dpfail = StencilOp::IncrWrap},
      .colorMask = glm::bvec4(false)};
  Result r;
  run(r, {{depthPass, receiver}, {zFail, volumes}}, vec4(0.1f, 0.1f, 0.15f, 1.0f), 1.0f, 0);
  expectAgreement(r, "shadow volume z-fail counts");
  // Not vacuous: some pixels are inside one volume, some inside both.
  std::size_t inside = 0, insideBoth = 0;
  for (std::uint8_t s : r.ref.stencils()) inside += s > 0, insideBoth += s == 2;
  EXPECT_GT(inside, 500u);
  EXPECT_GT(insideBoth, 10u);
}
