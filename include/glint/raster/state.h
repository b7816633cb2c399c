#pragma once
// glint/raster/state.h — the OpenGL state the reference rasterizer obeys.
//
// Every field starts at the value a fresh OpenGL 4.5 context has, so a default
// `State{}` renders exactly what GL renders before any glEnable/glDepthFunc/...
// call. Change only what a test needs, with designated initialisers:
//
/// ```cpp
/// const glint::raster::State state{
///     .viewport = glint::raster::Viewport{0, 0, 500, 500},  // glViewport(0, 0, 500, 500)
///     .depthTest = true,                                     // glEnable(GL_DEPTH_TEST)
///     .depthFunc = glint::raster::CompareFunc::LessEqual,    // glDepthFunc(GL_LEQUAL)
/// };
/// ```
//
// Field order follows the pipeline (transform, rasterization, per-fragment
// operations) and designated initialisers must keep that order.
//
// GL call                         field(s)
//   glViewport                      viewport (unset = the whole framebuffer, GL's initial value)
//   glDepthRange                    depthRange
//   glEnable(GL_DEPTH_TEST)         depthTest          (initially off, as in GL)
//   glDepthFunc / glDepthMask       depthFunc / depthMask
//   glEnable(GL_STENCIL_TEST)       stencilTest
//   glStencilFuncSeparate           stencilFront/Back.{func, ref, valueMask}
//   glStencilMaskSeparate           stencilFront/Back.writeMask
//   glStencilOpSeparate             stencilFront/Back.{sfail, dpfail, dppass}
//   glEnable(GL_CULL_FACE)          cull               (the names and defaults of render::PipelineState)
//   glCullFace / glFrontFace        cullFace / frontFace
//   glColorMask                     colorMask
//   glEnable(GL_BLEND)              blend.enabled
//   glBlendFuncSeparate             blend.{srcRgb, dstRgb, srcAlpha, dstAlpha}
//   glBlendEquationSeparate         blend.{equationRgb, equationAlpha}

#include "glint/core/math.h"

#include <cstdint>
#include <optional>

namespace glint::raster {

/// Comparison used by the depth test (incoming z FUNC stored z) and the stencil test
/// ((ref & valueMask) FUNC (stored & valueMask)), as in glDepthFunc / glStencilFunc.
enum class CompareFunc {
  Never,         ///< GL_NEVER: never passes
  Less,          ///< GL_LESS: incoming < stored
  Equal,         ///< GL_EQUAL: incoming == stored
  LessEqual,     ///< GL_LEQUAL: incoming <= stored
  Greater,       ///< GL_GREATER: incoming > stored
  NotEqual,      ///< GL_NOTEQUAL: incoming != stored
  GreaterEqual,  ///< GL_GEQUAL: incoming >= stored
  Always         ///< GL_ALWAYS: always passes
};

/// What glStencilOp does to the stored 8-bit stencil value s (before the write mask).
enum class StencilOp {
  Keep,      ///< GL_KEEP: s
  Zero,      ///< GL_ZERO: 0
  Replace,   ///< GL_REPLACE: the reference value (clamped to 0..255)
  Incr,      ///< GL_INCR: s + 1, saturating at 255
  Decr,      ///< GL_DECR: s - 1, saturating at 0
  IncrWrap,  ///< GL_INCR_WRAP: (s + 1) mod 256
  DecrWrap,  ///< GL_DECR_WRAP: (s - 1) mod 256
  Invert     ///< GL_INVERT: ~s (bitwise)
};

/// Polygon faces, for glCullFace.
enum class Face {
  Front,        ///< GL_FRONT
  Back,         ///< GL_BACK (GL's initial cull mode)
  FrontAndBack  ///< GL_FRONT_AND_BACK: every polygon is culled
};

/// Which window-space winding is front-facing, for glFrontFace.
enum class Winding {
  Ccw,  ///< GL_CCW: counter-clockwise in window space (lower-left origin) is front (initial)
  Cw    ///< GL_CW: clockwise is front
};

/// glBlendFunc factors. Each one is a vec4 (r, g, b, a) multiplying the source or destination.
enum class BlendFactor {
  Zero,              ///< GL_ZERO: (0, 0, 0, 0)
  One,               ///< GL_ONE: (1, 1, 1, 1)
  SrcColor,          ///< GL_SRC_COLOR: (Rs, Gs, Bs, As)
  OneMinusSrcColor,  ///< GL_ONE_MINUS_SRC_COLOR: 1 - (Rs, Gs, Bs, As)
  DstColor,          ///< GL_DST_COLOR: (Rd, Gd, Bd, Ad)
  OneMinusDstColor,  ///< GL_ONE_MINUS_DST_COLOR: 1 - (Rd, Gd, Bd, Ad)
  SrcAlpha,          ///< GL_SRC_ALPHA: As in every channel
  OneMinusSrcAlpha,  ///< GL_ONE_MINUS_SRC_ALPHA: 1 - As
  DstAlpha,          ///< GL_DST_ALPHA: Ad (the shadow-volume "dim by destination alpha" pass)
  OneMinusDstAlpha   ///< GL_ONE_MINUS_DST_ALPHA: 1 - Ad
};

/// glBlendEquation modes; result = f(S·Sfactor, D·Dfactor) per channel.
enum class BlendEquation {
  Add,              ///< GL_FUNC_ADD: S·Sf + D·Df (initial)
  Subtract,         ///< GL_FUNC_SUBTRACT: S·Sf - D·Df
  ReverseSubtract,  ///< GL_FUNC_REVERSE_SUBTRACT: D·Df - S·Sf
  Min,              ///< GL_MIN: min(S, D), factors ignored
  Max               ///< GL_MAX: max(S, D), factors ignored
};

/// glViewport(x, y, width, height): lower-left corner and size in pixels.
/// Like GL, width and height are clamped to kMaxViewportDim and x, y to
/// [kViewportBoundsMin, kViewportBoundsMax]; a negative size is an error (GL_INVALID_VALUE),
/// reported as Error(Usage) by drawTriangles.
struct Viewport {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
  bool operator==(const Viewport&) const = default;
};

/// GL_MAX_VIEWPORT_DIMS and GL_VIEWPORT_BOUNDS_RANGE as llvmpipe reports them.
constexpr int kMaxViewportDim = 16384;
constexpr int kViewportBoundsMin = -32768;
constexpr int kViewportBoundsMax = 32767;

/// glDepthRange(nearVal, farVal): window z = (far - near)/2 · z_ndc + (near + far)/2.
/// Both values are clamped to [0, 1] as GL does; near > far is allowed (reversed depth).
struct DepthRange {
  double nearVal = 0.0;
  double farVal = 1.0;
};

/// One face's stencil state (glStencilFuncSeparate + glStencilMaskSeparate + glStencilOpSeparate).
/// Only the low 8 bits of the masks matter: the stencil buffer has 8 bits.
struct StencilFace {
  CompareFunc func = CompareFunc::Always;  ///< (ref & valueMask) func (stored & valueMask)
  int ref = 0;                             ///< clamped to 0..255 when used, as GL does
  std::uint32_t valueMask = 0xFFu;         ///< glStencilFunc mask (GL's initial value is all ones)
  std::uint32_t writeMask = 0xFFu;         ///< glStencilMask: which bits an operation may change
  StencilOp sfail = StencilOp::Keep;       ///< stencil test failed
  StencilOp dpfail = StencilOp::Keep;      ///< stencil passed, depth test failed
  StencilOp dppass = StencilOp::Keep;      ///< both passed (or depth test disabled)
};

/// glEnable(GL_BLEND) + glBlendFuncSeparate + glBlendEquationSeparate. Initially disabled,
/// (ONE, ZERO), GL_FUNC_ADD: the fragment colour replaces the stored one.
struct BlendState {
  bool enabled = false;
  BlendFactor srcRgb = BlendFactor::One;
  BlendFactor dstRgb = BlendFactor::Zero;
  BlendFactor srcAlpha = BlendFactor::One;
  BlendFactor dstAlpha = BlendFactor::Zero;
  BlendEquation equationRgb = BlendEquation::Add;
  BlendEquation equationAlpha = BlendEquation::Add;

  /// glEnable(GL_BLEND); glBlendFunc(src, dst); glBlendEquation(GL_FUNC_ADD).
  static constexpr BlendState func(BlendFactor src, BlendFactor dst) {
    return BlendState{.enabled = true, .srcRgb = src, .dstRgb = dst, .srcAlpha = src, .dstAlpha = dst};
  }
};

/// Everything drawTriangles needs to know besides the geometry; defaults = a fresh GL context.
struct State {
  std::optional<Viewport> viewport;  ///< unset: (0, 0, framebuffer width, height), GL's initial viewport
  DepthRange depthRange;

  bool depthTest = false;                  ///< GL_DEPTH_TEST (disabled initially, as in GL)
  CompareFunc depthFunc = CompareFunc::Less;
  bool depthMask = true;                   ///< write depth when the depth test passes

  bool stencilTest = false;                ///< GL_STENCIL_TEST
  StencilFace stencilFront;                ///< used by front-facing polygons
  StencilFace stencilBack;                 ///< used by back-facing polygons

  bool cull = false;                       ///< GL_CULL_FACE
  Face cullFace = Face::Back;              ///< glCullFace: which faces are culled
  Winding frontFace = Winding::Ccw;

  glm::bvec4 colorMask{true};              ///< glColorMask(r, g, b, a)
  BlendState blend;
};

}  // namespace glint::raster
