// Per-fragment operations: depth test (the lecture's example and all eight functions),
// stencil test and operations against hand computations, blending, masks, formats.

#include "glint/core/error.h"
#include "glint/raster/fragment_ops.h"

#include <gtest/gtest.h>

#include <cstdint>

using namespace glint;
using namespace glint::raster;

namespace {
constexpr CompareFunc kAllFuncs[] = {CompareFunc::Never,   CompareFunc::Less,     CompareFunc::Equal,
                                     CompareFunc::LessEqual, CompareFunc::Greater, CompareFunc::NotEqual,
                                     CompareFunc::GreaterEqual, CompareFunc::Always};

/// Hand truth table for incoming vs stored in {less, equal, greater}.
struct Row {
  CompareFunc func;
  bool whenLess, whenEqual, whenGreater;
};
constexpr Row kTruth[] = {
    {CompareFunc::Never, false, false, false},     {CompareFunc::Less, true, false, false},
    {CompareFunc::Equal, false, true, false},      {CompareFunc::LessEqual, true, true, false},
    {CompareFunc::Greater, false, false, true},    {CompareFunc::NotEqual, true, false, true},
    {CompareFunc::GreaterEqual, false, true, true}, {CompareFunc::Always, true, true, true},
};

const vec4 kRed(1, 0, 0, 1);

void expectFloatEq(const vec4& got, const vec4& expected) {
  for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(got[i], expected[i]) << "channel " << i;
}
const vec4 kGreen(0, 1, 0, 1);
}  // namespace

// ---------------------------------------------------------------------------------
// Depth
// ---------------------------------------------------------------------------------

TEST(RasterLecture, DepthBufferExample) {
  Framebuffer fb(1, 1);
  fb.clearDepth(0.8f);  // "Reads the value 0.8"
  const State state{.depthTest = true};  // glEnable(GL_DEPTH_TEST), GL_LESS by default
  // 0.65 GL_LESS 0.8 is true: 0.65 replaces 0.8, the colour is written.
  EXPECT_EQ(processFragment(fb, state, 0, 0, 0.65f, kRed, true), FragmentFate::Written);
  EXPECT_EQ(fb.depth(0, 0), 0.65f);
  EXPECT_EQ(fb.color(0, 0), kRed);
  // Second primitive: 0.72 GL_LESS 0.65 is false: depth and colour are discarded.
  EXPECT_EQ(processFragment(fb, state, 0, 0, 0.72f, kGreen, true), FragmentFate::DepthFailed);
  EXPECT_EQ(fb.depth(0, 0), 0.65f);
  EXPECT_EQ(fb.color(0, 0), kRed);
  EXPECT_EQ(fb.overdraw(0, 0), 2u);  // both fragments reached the per-fragment stage
}

TEST(RasterDepth, AllEightFunctions) {
  for (const Row& row : kTruth) {
    EXPECT_EQ(compare(row.func, 0.25, 0.5), row.whenLess);
    EXPECT_EQ(compare(row.func, 0.5, 0.5), row.whenEqual);
    EXPECT_EQ(compare(row.func, 0.75, 0.5), row.whenGreater);
    const float incoming[] = {0.25f, 0.5f, 0.75f};
    const bool expected[] = {row.whenLess, row.whenEqual, row.whenGreater};
    for (int i = 0; i < 3; ++i) {
      Framebuffer fb(1, 1, {.color = ColorFormat::Float32});
      fb.clear(kGreen, 0.5f);
      const FragmentFate fate = processFragment(fb, State{.depthTest = true, .depthFunc = row.func}, 0, 0, incoming[i], kRed, true);
      EXPECT_EQ(fate == FragmentFate::Written, expected[i]);
      EXPECT_EQ(fb.depth(0, 0), expected[i] ? incoming[i] : 0.5f);
      EXPECT_EQ(fb.color(0, 0), expected[i] ? kRed : kGreen);
    }
  }
}

TEST(RasterDepth, MaskAndDisabledTest) {
  Framebuffer fb(1, 1);
  fb.clearDepth(0.5f);
  // glDepthMask(GL_FALSE): the test still runs, colour is written, depth is not.
  EXPECT_EQ(processFragment(fb, State{.depthTest = true, .depthMask = false}, 0, 0, 0.25f, kRed, true), FragmentFate::Written);
  EXPECT_EQ(fb.depth(0, 0), 0.5f);
  EXPECT_EQ(fb.color(0, 0), kRed);
  EXPECT_EQ(processFragment(fb, State{.depthTest = true, .depthMask = false}, 0, 0, 0.75f, kGreen, true), FragmentFate::DepthFailed);
  // Depth test disabled (GL's initial state): always passes and never writes depth.
  EXPECT_EQ(processFragment(fb, State{}, 0, 0, 0.9f, kGreen, true), FragmentFate::Written);
  EXPECT_EQ(fb.depth(0, 0), 0.5f);
  EXPECT_EQ(fb.color(0, 0), kGreen);
}

TEST(RasterDepth, ClearDepthClampsAndUnorm24Quantizes) {
  Framebuffer fb(2, 1, {.depth = DepthFormat::Unorm24});
  fb.clearDepth(2.0f);
  EXPECT_EQ(fb.depth(1, 0), 1.0f);
  fb.clearDepth(-1.0f);
  EXPECT_EQ(fb.depth(1, 0), 0.0f);
  const double level = 1.0 / 16777215.0;
  EXPECT_EQ(fb.storedDepth(float(1000.4 * level)), float(1000 * level));
  EXPECT_EQ(fb.storedDepth(float(1000.6 * level)), float(1001 * level));
  // Two depths 0.3 of a level apart compare EQUAL in a 24-bit buffer.
  fb.clearDepth(float(1000.0 * level));
  const State equal{.depthTest = true, .depthFunc = CompareFunc::Equal};
  EXPECT_EQ(processFragment(fb, equal, 0, 0, float(1000.3 * level), kRed, true), FragmentFate::Written);
  Framebuffer precise(1, 1);
  precise.clearDepth(float(1000.0 * level));
  EXPECT_EQ(processFragment(precise, equal, 0, 0, float(1000.3 * level), kRed, true), FragmentFate::DepthFailed);
}

// ---------------------------------------------------------------------------------
// Stencil
// ---------------------------------------------------------------------------------

TEST(RasterStencil, FunctionsWithReferenceAndValueMask) {
  // ref 0x35 & mask 0x0F = 5; stored values whose masked value is 4, 5, 6 (upper bits differ).
  const std::uint8_t stored[] = {0xA4, 0x25, 0x06};
  for (const Row& row : kTruth) {
    const StencilFace face{.func = row.func, .ref = 0x35, .valueMask = 0x0F};
    // GL compares ref FUNC stored: ref 5 vs stored 4 is "greater", vs 6 is "less".
    EXPECT_EQ(stencilTestPasses(face, stored[0]), row.whenGreater);
    EXPECT_EQ(stencilTestPasses(face, stored[1]), row.whenEqual);
    EXPECT_EQ(stencilTestPasses(face, stored[2]), row.whenLess);
  }
  // The reference is clamped to 0..255 before masking.
  EXPECT_TRUE(stencilTestPasses(StencilFace{.func = CompareFunc::Equal, .ref = 1000}, 255));
  EXPECT_TRUE(stencilTestPasses(StencilFace{.func = CompareFunc::Equal, .ref = -7}, 0));
  // Mask bits above 8 are ignored.
  EXPECT_TRUE(stencilTestPasses(StencilFace{.func = CompareFunc::Equal, .ref = 3, .valueMask = 0xFFFFFF01u}, 0x81));
}

TEST(RasterStencil, OperationsByHand) {
  struct Case {
    StencilOp op;
    std::uint8_t in, out;
  };
  const int ref = 0x5A;
  const Case cases[] = {
      {StencilOp::Keep, 0x33, 0x33},     {StencilOp::Zero, 0x33, 0x00},     {StencilOp::Replace, 0x33, 0x5A},
      {StencilOp::Incr, 0x33, 0x34},     {StencilOp::Incr, 0xFF, 0xFF},     {StencilOp::Decr, 0x33, 0x32},
      {StencilOp::Decr, 0x00, 0x00},     {StencilOp::IncrWrap, 0xFF, 0x00}, {StencilOp::IncrWrap, 0x10, 0x11},
      {StencilOp::DecrWrap, 0x00, 0xFF}, {StencilOp::DecrWrap, 0x10, 0x0F}, {StencilOp::Invert, 0x33, 0xCC},
      {StencilOp::Invert, 0x00, 0xFF},
  };
  for (const Case& c : cases) EXPECT_EQ(stencilOpResult(c.op, c.in, ref), c.out) << int(c.op) << " on " << int(c.in);
  EXPECT_EQ(stencilOpResult(StencilOp::Replace, 9, 300), 255);
  EXPECT_EQ(stencilOpResult(StencilOp::Replace, 9, -4), 0);
  // Write mask 0x0F: only the low nibble may change.
  EXPECT_EQ(maskedStencilWrite(0xA3, 0x5C, 0x0F), 0xAC);
  EXPECT_EQ(maskedStencilWrite(0xA3, 0x5C, 0x00), 0xA3);
  EXPECT_EQ(maskedStencilWrite(0xA3, 0x5C, 0xFFFFFFFFu), 0x5C);
}

TEST(RasterStencil, SfailDpfailDppassInGlOrder) {
  // Each outcome gets a distinct op so the stored value tells which one ran.
  const StencilFace face{.func = CompareFunc::Equal, .ref = 1, .sfail = StencilOp::Invert,
                         .dpfail = StencilOp::Replace, .dppass = StencilOp::IncrWrap};
  const State state{.depthTest = true, .stencilTest = true, .stencilFront = face, .stencilBack = face};
  Framebuffer fb(3, 1);
  fb.clearDepth(0.5f);
  fb.stencils()[0] = 7;  // stencil fails: ~7
  fb.stencils()[1] = 1;  // stencil passes, depth fails: ref
  fb.stencils()[2] = 1;  // both pass: 1 + 1
  EXPECT_EQ(processFragment(fb, state, 0, 0, 0.25f, kRed, true), FragmentFate::StencilFailed);
  EXPECT_EQ(processFragment(fb, state, 1, 0, 0.75f, kRed, true), FragmentFate::DepthFailed);
  EXPECT_EQ(processFragment(fb, state, 2, 0, 0.25f, kRed, true), FragmentFate::Written);
  EXPECT_EQ(fb.stencil(0, 0), 0xF8);
  EXPECT_EQ(fb.stencil(1, 0), 1);
  EXPECT_EQ(fb.stencil(2, 0), 2);
  // A stencil failure stops the fragment before the depth test: depth and colour untouched.
  EXPECT_EQ(fb.depth(0, 0), 0.5f);
  EXPECT_EQ(fb.color(0, 0), vec4(0.0f));
  EXPECT_EQ(fb.depth(2, 0), 0.25f);

  // Without a depth test, dppass applies.
  State noDepth = state;
  noDepth.depthTest = false;
  fb.stencils()[1] = 1;
  EXPECT_EQ(processFragment(fb, noDepth, 1, 0, 0.75f, kRed, true), FragmentFate::Written);
  EXPECT_EQ(fb.stencil(1, 0), 2);
  // Without a stencil test nothing touches the stencil buffer, even with ops set.
  State noStencil = state;
  noStencil.stencilTest = false;
  EXPECT_EQ(processFragment(fb, noStencil, 0, 0, 0.1f, kRed, true), FragmentFate::Written);
  EXPECT_EQ(fb.stencil(0, 0), 0xF8);
}

TEST(RasterStencil, FrontAndBackStateAreSeparate) {
  const State state{
      .stencilTest = true,
      .stencilFront = {.dppass = StencilOp::IncrWrap},
      .stencilBack = {.dppass = StencilOp::DecrWrap},
  };
  Framebuffer fb(1, 1);
  processFragment(fb, state, 0, 0, 0.5f, kRed, true);
  processFragment(fb, state, 0, 0, 0.5f, kRed, true);
  EXPECT_EQ(fb.stencil(0, 0), 2);
  processFragment(fb, state, 0, 0, 0.5f, kRed, false);
  processFragment(fb, state, 0, 0, 0.5f, kRed, false);
  processFragment(fb, state, 0, 0, 0.5f, kRed, false);
  EXPECT_EQ(fb.stencil(0, 0), 255);  // wrapped below zero
  // Write mask applies to operations: INCR with mask 0x01 toggles only bit 0.
  const State masked{.stencilTest = true, .stencilFront = {.writeMask = 0x01, .dppass = StencilOp::Incr}};
  fb.clearStencil(0x10);
  processFragment(fb, masked, 0, 0, 0.5f, kRed, true);  // 0x11 & 0x01 → 0x11
  EXPECT_EQ(fb.stencil(0, 0), 0x11);
  processFragment(fb, masked, 0, 0, 0.5f, kRed, true);  // 0x12 & 0x01 → 0x10
  EXPECT_EQ(fb.stencil(0, 0), 0x10);
}

TEST(RasterStencil, ClearHonoursTheWriteMask) {
  Framebuffer fb(1, 1);
  fb.clearStencil(0x1F3);  // only 8 bits: 0xF3
  EXPECT_EQ(fb.stencil(0, 0), 0xF3);
  fb.clearStencil(0x0C, 0x0F);
  EXPECT_EQ(fb.stencil(0, 0), 0xFC);
}

// ---------------------------------------------------------------------------------
// Blending and masks
// ---------------------------------------------------------------------------------

TEST(RasterBlend, TheFourRequiredFunctionsOnAFloatBuffer) {
  const vec4 src(1.0f, 0.5f, 0.0f, 0.25f);
  const vec4 dst(0.0f, 0.5f, 1.0f, 0.5f);
  struct Case {
    BlendFactor s, d;
    vec4 expected;
  };
  const Case cases[] = {
      // SRC_ALPHA, ONE_MINUS_SRC_ALPHA: 0.25·src + 0.75·dst
      {BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha, vec4(0.25f, 0.5f, 0.75f, 0.4375f)},
      // ZERO, DST_ALPHA: dst·Ad (the shadow-volume dimming pass)
      {BlendFactor::Zero, BlendFactor::DstAlpha, vec4(0.0f, 0.25f, 0.5f, 0.25f)},
      // ONE, ONE: additive, unclamped in a float buffer
      {BlendFactor::One, BlendFactor::One, vec4(1.0f, 1.0f, 1.0f, 0.75f)},
      // ONE, ZERO: plain replace
      {BlendFactor::One, BlendFactor::Zero, src},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(blendColors(BlendState::func(c.s, c.d), src, dst), c.expected);
    Framebuffer fb(1, 1, {.color = ColorFormat::Float32});
    fb.clearColor(dst);
    processFragment(fb, State{.blend = BlendState::func(c.s, c.d)}, 0, 0, 0.5f, src, true);
    EXPECT_EQ(fb.color(0, 0), c.expected);
  }
}

TEST(RasterBlend, AdditiveBlendingClampsInAnRgba8Buffer) {
  Framebuffer fixed(1, 1);
  Framebuffer floating(1, 1, {.color = ColorFormat::Float32});
  const State add{.blend = BlendState::func(BlendFactor::One, BlendFactor::One)};
  for (Framebuffer* fb : {&fixed, &floating}) {
    fb->clearColor(vec4(0.6f, 0.2f, 0.0f, 1.0f));
    processFragment(*fb, add, 0, 0, 0.5f, vec4(0.6f, 0.2f, 1.5f, 1.0f), true);
  }
  expectFloatEq(fixed.color(0, 0), vec4(1.0f, 102.0f / 255.0f, 1.0f, 1.0f));  // 0.4 → 102/255
  EXPECT_NEAR(floating.color(0, 0).r, 1.2f, 1e-6f);
  EXPECT_EQ(floating.color(0, 0).b, 1.5f);
  EXPECT_EQ(floating.color(0, 0).a, 2.0f);
}

TEST(RasterBlend, EquationsAndSeparateAlpha) {
  const vec4 s(0.75f, 0.25f, 0.5f, 1.0f), d(0.5f, 0.5f, 0.5f, 0.5f);
  BlendState b = BlendState::func(BlendFactor::One, BlendFactor::One);
  b.equationRgb = BlendEquation::ReverseSubtract;
  b.equationAlpha = BlendEquation::Max;
  EXPECT_EQ(blendColors(b, s, d), vec4(-0.25f, 0.25f, 0.0f, 1.0f));
  b.equationRgb = BlendEquation::Min;
  EXPECT_EQ(blendColors(b, s, d), vec4(0.5f, 0.25f, 0.5f, 1.0f));
  const BlendState sep{.enabled = true, .srcRgb = BlendFactor::DstColor, .dstRgb = BlendFactor::Zero,
                       .srcAlpha = BlendFactor::Zero, .dstAlpha = BlendFactor::One};
  EXPECT_EQ(blendColors(sep, s, d), vec4(0.375f, 0.125f, 0.25f, 0.5f));
  EXPECT_EQ(blendFactor(BlendFactor::OneMinusDstAlpha, s, d), vec4(0.5f));
  EXPECT_EQ(blendFactor(BlendFactor::OneMinusSrcColor, s, d), vec4(0.25f, 0.75f, 0.5f, 0.0f));
}

TEST(RasterColor, MaskAndUnorm8Quantization) {
  Framebuffer fb(1, 1);
  fb.clearColor(vec4(0.2f, 0.2f, 0.2f, 0.2f));
  expectFloatEq(fb.color(0, 0), vec4(51.0f / 255.0f));  // 0.2·255 = 51
  processFragment(fb, State{.colorMask = glm::bvec4(false, true, false, true)}, 0, 0, 0.5f, vec4(1.0f, 2.0f, 1.0f, -1.0f), true);
  expectFloatEq(fb.color(0, 0), vec4(51.0f / 255.0f, 1.0f, 51.0f / 255.0f, 0.0f));  // clamped, masked
  fb.clearColor(vec4(1.0f), glm::bvec4(true, false, false, false));
  expectFloatEq(fb.color(0, 0), vec4(1.0f, 1.0f, 51.0f / 255.0f, 0.0f));
  // NaN colours are not garbage: they store as 0 in a normalized buffer.
  processFragment(fb, State{}, 0, 0, 0.5f, vec4(NAN), true);
  EXPECT_EQ(fb.color(0, 0), vec4(0.0f));
}

TEST(RasterFramebuffer, SizesAndBounds) {
  EXPECT_THROW(Framebuffer(0, 5), Error);
  EXPECT_THROW(Framebuffer(5, kMaxFramebufferSize + 1), Error);
  Framebuffer fb(3, 2);
  EXPECT_EQ(fb.colors().size(), 6u);
  EXPECT_EQ(fb.depth(2, 1), 1.0f);  // GL's initial clear depth
  EXPECT_EQ(fb.stencil(2, 1), 0);
  EXPECT_THROW(fb.depth(3, 0), Error);
  EXPECT_THROW(fb.color(0, -1), Error);
  EXPECT_THROW(processFragment(fb, State{}, 0, 2, 0.5f, kRed, true), Error);
  EXPECT_EQ(fb.index(2, 1), 5u);
}

TEST(RasterFramebuffer, ImagesAreFlippedToImageConvention) {
  Framebuffer fb(2, 3, {.color = ColorFormat::Float32});
  fb.clear(vec4(0.0f), 1.0f, 0);
  fb.colors()[fb.index(0, 0)] = kRed;  // bottom-left in GL
  fb.depths()[fb.index(1, 0)] = 0.25f;
  fb.stencils()[fb.index(0, 2)] = 3;   // top-left in GL
  fb.overdraws()[fb.index(1, 2)] = 1;
  const Image color = colorImage(fb);
  EXPECT_EQ(color.type(), PixelType::F32);
  EXPECT_EQ(color.at(0, 2, 0), 1.0f);  // image row 2 is the bottom
  EXPECT_EQ(color.at(0, 0, 0), 0.0f);
  const Image depth = depthImage(fb);
  EXPECT_EQ(depth.channels(), 1);
  EXPECT_EQ(depth.at(1, 2, 0), 0.25f);
  EXPECT_EQ(depth.at(0, 0, 0), 1.0f);  // white = far
  const Image stencil = stencilImage(fb);
  EXPECT_EQ(stencil.channels(), 3);
  EXPECT_GT(stencil.at(0, 0, 0), 0.9f);  // the largest value is red
  EXPECT_EQ(stencil.at(1, 1, 0) + stencil.at(1, 1, 1) + stencil.at(1, 1, 2), 0.0f);  // zero is black
  const Image overdraw = overdrawImage(fb);
  EXPECT_EQ(overdraw.at(1, 0, 2), 1.0f);  // one fragment, single-level ramp: blue
  EXPECT_THROW(falseColorImage(fb.overdraws(), 3, 3), Error);
}
