#pragma once
// glint/raster/pipeline.h — drawTriangles: the whole OpenGL triangle pipeline on the CPU.
//
// A reference ("oracle") implementation: no OpenGL inside, written to be read.
// Given clip-space vertices (what a vertex shader writes to gl_Position) it does
//
//   primitive assembly   indices, 3 per triangle (or 0, 1, 2, ... when indices is empty)
//   clipping             all six view-volume planes in homogeneous clip space, as llvmpipe
//                        (geometry.h: clipTriangle, kGuardBand)
//   divide + viewport    clip → NDC → window, glViewport + glDepthRange semantics
//   facing + culling     sign of the window-space area; CCW is front unless frontFace = Cw
//   rasterization        oriented edge equations on 1/256-pixel fixed point, sample at
//                        pixel centres, left/bottom tie rule (exactly-once shared edges)
//   interpolation        window z linear in screen space; varyings perspective-correct
//   fragment shader      optional callback; default outputs varying 0 (or white)
//   per-fragment ops     stencil → depth → blend → colour mask (fragment_ops.h)
//
/// ```cpp run
/// using glint::vec4;
/// const std::vector<glint::raster::Vertex> tri = {
///     {vec4(-0.8f, 0.8f, 0.3f, 1.0f), {vec4(1, 0, 0, 1)}},  // position, varying 0 = colour
///     {vec4(0.8f, 0.8f, -0.2f, 1.0f), {vec4(0, 1, 0, 1)}},
///     {vec4(0.0f, -0.8f, -0.2f, 1.0f), {vec4(0, 0, 1, 1)}}};
/// glint::raster::Framebuffer fb(500, 500);
/// const glint::raster::DrawStats stats = glint::raster::drawTriangles(fb, glint::raster::State{.depthTest = true}, tri);
/// ```
//
// Bad input never crashes and never draws garbage: a triangle with any NaN or infinite
// position coordinate is dropped whole (counted in DrawStats::rejected); zero-area triangles
// draw nothing; huge finite coordinates are clipped and drawn correctly. Programming errors
// (index out of range, vertices with different varying counts, more than kMaxVaryings)
// throw Error(Usage) before anything is drawn.

#include "glint/core/math.h"
#include "glint/raster/framebuffer.h"
#include "glint/raster/state.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace glint::raster {

/// Most varyings (vec4 each) a vertex may carry.
constexpr std::size_t kMaxVaryings = 8;

/// One vertex as the rasterizer sees it: gl_Position and the vertex shader's outputs.
struct Vertex {
  vec4 position{0.0f, 0.0f, 0.0f, 1.0f};  ///< clip space
  std::vector<vec4> varyings;             ///< same count for every vertex of a draw
};

/// What the fragment shader gets.
struct Fragment {
  ivec2 pixel{0};                   ///< window pixel, (0, 0) = lower-left
  vec4 fragCoord{0.0f};             ///< gl_FragCoord: (x + 0.5, y + 0.5, window z, 1/w_clip)
  bool frontFacing = true;          ///< gl_FrontFacing
  std::span<const vec4> varyings;   ///< perspective-correct interpolated varyings
};

/// Returns the fragment colour, or nullopt to discard the fragment (GLSL `discard`),
/// which then never reaches the per-fragment operations (no overdraw count, no stencil op).
using FragmentShader = std::function<std::optional<vec4>(const Fragment&)>;

/// Counters of one draw, for tests and teaching output.
struct DrawStats {
  std::size_t triangles = 0;      ///< triangles assembled
  std::size_t rejected = 0;       ///< dropped for NaN/inf position coordinates
  std::size_t clippedAway = 0;    ///< entirely outside the clip volume
  std::size_t degenerate = 0;     ///< zero window-space area after snapping
  std::size_t culled = 0;         ///< removed by face culling
  std::size_t clipped = 0;        ///< partly outside, cut into a polygon by clipping
  std::size_t fragments = 0;      ///< covered pixel centres inside the viewport
  std::size_t discarded = 0;      ///< discarded by the fragment shader
  std::size_t stencilFailed = 0;  ///< killed by the stencil test
  std::size_t depthFailed = 0;    ///< killed by the depth test
  std::size_t written = 0;        ///< passed every test
};

/// Draws indexed triangles (GL_TRIANGLES). indices empty = non-indexed (vertex 3k, 3k+1,
/// 3k+2 is triangle k); a trailing incomplete triangle is ignored, as in GL.
/// The default shader (empty function) outputs varyings[0], or opaque white without varyings.
DrawStats drawTriangles(Framebuffer& fb, const State& state, std::span<const Vertex> vertices,
                        std::span<const std::uint32_t> indices = {}, const FragmentShader& shader = {});

}  // namespace glint::raster
