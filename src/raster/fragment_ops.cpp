// Per-fragment operations of the reference rasterizer (see fragment_ops.h).

#include "glint/raster/fragment_ops.h"

#include "glint/core/error.h"

#include <algorithm>

namespace glint::raster {

bool compare(CompareFunc func, double incoming, double stored) {
  switch (func) {
    case CompareFunc::Never: return false;
    case CompareFunc::Less: return incoming < stored;
    case CompareFunc::Equal: return incoming == stored;
    case CompareFunc::LessEqual: return incoming <= stored;
    case CompareFunc::Greater: return incoming > stored;
    case CompareFunc::NotEqual: return incoming != stored;
    case CompareFunc::GreaterEqual: return incoming >= stored;
    case CompareFunc::Always: return true;
  }
  return false;
}

namespace {
/// GL clamps the stencil reference to [0, 2^bits - 1] wherever it is used.
std::uint8_t clampedRef(int ref) { return static_cast<std::uint8_t>(std::clamp(ref, 0, 255)); }
}  // namespace

bool stencilTestPasses(const StencilFace& face, std::uint8_t stored) {
  const std::uint32_t mask = face.valueMask & 0xFFu;
  return compare(face.func, double(clampedRef(face.ref) & mask), double(stored & mask));
}

std::uint8_t stencilOpResult(StencilOp op, std::uint8_t stored, int ref) {
  switch (op) {
    case StencilOp::Keep: return stored;
    case StencilOp::Zero: return 0;
    case StencilOp::Replace: return clampedRef(ref);
    case StencilOp::Incr: return stored == 255 ? stored : static_cast<std::uint8_t>(stored + 1);
    case StencilOp::Decr: return stored == 0 ? stored : static_cast<std::uint8_t>(stored - 1);
    case StencilOp::IncrWrap: return static_cast<std::uint8_t>((stored + 1) & 0xFF);
    case StencilOp::DecrWrap: return static_cast<std::uint8_t>((stored + 255) & 0xFF);
    case StencilOp::Invert: return static_cast<std::uint8_t>(~stored & 0xFF);
  }
  return stored;
}

std::uint8_t maskedStencilWrite(std::uint8_t stored, std::uint8_t value, std::uint32_t writeMask) {
  const std::uint32_t mask = writeMask & 0xFFu;
  return static_cast<std::uint8_t>((stored & ~mask) | (value & mask));
}

vec4 blendFactor(BlendFactor factor, const vec4& src, const vec4& dst) {
  switch (factor) {
    case BlendFactor::Zero: return vec4(0.0f);
    case BlendFactor::One: return vec4(1.0f);
    case BlendFactor::SrcColor: return src;
    case BlendFactor::OneMinusSrcColor: return vec4(1.0f) - src;
    case BlendFactor::DstColor: return dst;
    case BlendFactor::OneMinusDstColor: return vec4(1.0f) - dst;
    case BlendFactor::SrcAlpha: return vec4(src.a);
    case BlendFactor::OneMinusSrcAlpha: return vec4(1.0f - src.a);
    case BlendFactor::DstAlpha: return vec4(dst.a);
    case BlendFactor::OneMinusDstAlpha: return vec4(1.0f - dst.a);
  }
  return vec4(0.0f);
}

namespace {
float applyEquation(BlendEquation equation, float s, float d, float sf, float df) {
  switch (equation) {
    case BlendEquation::Add: return s * sf + d * df;
    case BlendEquation::Subtract: return s * sf - d * df;
    case BlendEquation::ReverseSubtract: return d * df - s * sf;
    case BlendEquation::Min: return std::min(s, d);  // GL ignores the factors for MIN/MAX
    case BlendEquation::Max: return std::max(s, d);
  }
  return s;
}
}  // namespace

vec4 blendColors(const BlendState& blend, const vec4& src, const vec4& dst) {
  // The RGB factors come from the RGB pair, the alpha factor from the alpha pair.
  const vec4 srcRgb = blendFactor(blend.srcRgb, src, dst);
  const vec4 dstRgb = blendFactor(blend.dstRgb, src, dst);
  const float srcA = blendFactor(blend.srcAlpha, src, dst).a;
  const float dstA = blendFactor(blend.dstAlpha, src, dst).a;
  vec4 result;
  for (int i = 0; i < 3; ++i) result[i] = applyEquation(blend.equationRgb, src[i], dst[i], srcRgb[i], dstRgb[i]);
  result.a = applyEquation(blend.equationAlpha, src.a, dst.a, srcA, dstA);
  return result;
}

namespace {
vec4 clamp01(const vec4& c) {
  vec4 r;
  for (int i = 0; i < 4; ++i) r[i] = c[i] > 0.0f ? std::min(c[i], 1.0f) : 0.0f;  // NaN → 0
  return r;
}
}  // namespace

FragmentFate processFragment(Framebuffer& fb, const State& state, int x, int y, float z, const vec4& color,
                             bool frontFacing) {
  if (!fb.contains(x, y))
    fail(ErrorKind::Usage, "fragment ({}, {}) is outside the {}x{} framebuffer", x, y, fb.width(), fb.height());
  const std::size_t i = fb.index(x, y);
  ++fb.overdraws()[i];

  const StencilFace& face = frontFacing ? state.stencilFront : state.stencilBack;
  std::uint8_t& stencil = fb.stencils()[i];
  auto applyStencil = [&](StencilOp op) {
    if (state.stencilTest) stencil = maskedStencilWrite(stencil, stencilOpResult(op, stencil, face.ref), face.writeMask);
  };

  // 1. Stencil test.
  if (state.stencilTest && !stencilTestPasses(face, stencil)) {
    applyStencil(face.sfail);
    return FragmentFate::StencilFailed;
  }

  // 2. Depth test. The incoming depth is converted to the buffer's format first, as GL
  //    converts to fixed point before comparing with a fixed-point depth buffer.
  const float depth = fb.storedDepth(z);
  if (state.depthTest) {
    if (!compare(state.depthFunc, depth, fb.depths()[i])) {
      applyStencil(face.dpfail);
      return FragmentFate::DepthFailed;
    }
    if (state.depthMask) fb.depths()[i] = depth;
  }
  applyStencil(face.dppass);

  // 3. Blending, then the colour mask. Fixed-point buffers clamp the inputs to [0, 1].
  const bool normalized = fb.format().color == ColorFormat::Unorm8;
  vec4& stored = fb.colors()[i];
  const vec4 src = normalized ? clamp01(color) : color;
  const vec4 result = state.blend.enabled ? blendColors(state.blend, src, stored) : src;
  const vec4 value = fb.storedColor(result);
  for (int c = 0; c < 4; ++c)
    if (state.colorMask[c]) stored[c] = value[c];
  return FragmentFate::Written;
}

}  // namespace glint::raster
