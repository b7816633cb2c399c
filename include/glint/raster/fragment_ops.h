#pragma once
// glint/raster/fragment_ops.h — OpenGL's per-fragment operations, one function per step.
//
// GL 4.5 chapter 17 order, as applied by processFragment to a shaded fragment:
//   1. stencil test   (ref & valueMask) FUNC (stored & valueMask); on failure apply sfail, stop
//   2. depth test     z FUNC stored depth; on failure apply dpfail, stop
//                     on success apply dppass and write z if depthMask
//   3. blending       per channel; then the colour mask selects which channels are written
// A disabled stencil test passes and never modifies the stencil buffer; a disabled depth
// test passes (dppass applies) and never writes depth — exactly GL's rules.
// Which StencilFace is used depends on the fragment's polygon facing.

#include "glint/core/math.h"
#include "glint/raster/framebuffer.h"
#include "glint/raster/state.h"

#include <cstdint>

namespace glint::raster {

/// incoming FUNC stored (GL_LESS: incoming < stored, ...).
bool compare(CompareFunc func, double incoming, double stored);

/// The stencil test: (clamp(ref, 0, 255) & valueMask) FUNC (stored & valueMask).
bool stencilTestPasses(const StencilFace& face, std::uint8_t stored);

/// The value a stencil operation produces from the stored value (before the write mask).
std::uint8_t stencilOpResult(StencilOp op, std::uint8_t stored, int ref);

/// Write-masked update: bits set in writeMask come from value, the others stay.
std::uint8_t maskedStencilWrite(std::uint8_t stored, std::uint8_t value, std::uint32_t writeMask);

/// One blend factor as (r, g, b, a) given source and destination colours.
vec4 blendFactor(BlendFactor factor, const vec4& src, const vec4& dst);

/// The blended colour (blend.enabled is ignored: this is the enabled path). No clamping:
/// processFragment clamps inputs and result for Unorm8 framebuffers.
vec4 blendColors(const BlendState& blend, const vec4& src, const vec4& dst);

/// What happened to a fragment in the per-fragment operations.
enum class FragmentFate {
  StencilFailed,  ///< killed by the stencil test (sfail applied)
  DepthFailed,    ///< killed by the depth test (dpfail applied)
  Written         ///< passed both; colour (masked) and depth (if depthMask) written
};

/// Runs the per-fragment operations for one fragment at pixel (x, y) with window depth z
/// and shaded colour, and counts it in the overdraw buffer. The pixel must be inside the
/// framebuffer (Error(Usage) otherwise); z is used as given (the pipeline has already
/// clamped it to [0, 1]).
FragmentFate processFragment(Framebuffer& fb, const State& state, int x, int y, float z, const vec4& color,
                             bool frontFacing);

}  // namespace glint::raster
