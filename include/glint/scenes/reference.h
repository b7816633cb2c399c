#pragma once
// glint/scenes/reference.h — the geometry of the basics/reference scenes, as data.
//
// basics/reference/<variant> shows OpenGL (left half) and glint::raster, the reference
// CPU pipeline (right half), drawing the same setup: the same clip-space vertices under
// the same raster::State. The setups live here, free of GL, so that `glint raster scene`
// can run them through the reference pipeline alone and write its intermediate
// pictures (depth, edge functions, overdraw) too.
//
/// ```cpp run
/// namespace raster = glint::raster;
/// const glint::scenes::ReferenceSetup setup = glint::scenes::referenceSetup("stencil-count", {500, 500});
/// raster::Framebuffer fb(500, 500, {.depth = raster::DepthFormat::Unorm24});
/// fb.clear(setup.clearColor, setup.clearDepth, setup.clearStencil);
/// for (const glint::scenes::ReferenceDraw& draw : setup.draws) raster::drawTriangles(fb, draw.state, draw.vertices);
/// ```

#include "glint/core/math.h"
#include "glint/raster/pipeline.h"
#include "glint/raster/state.h"

#include <string>
#include <string_view>
#include <vector>

namespace glint::scenes {

/// What a reference scene shows of its framebuffer.
enum class ReferenceView {
  Color,   ///< the colour buffer
  Depth,   ///< the depth buffer, white = 1.0 (far)
  Stencil  ///< the stencil counts in false colour (raster::falseColorImage)
};

/// One glDraw* call: its state and its vertices (non-indexed GL_TRIANGLES).
struct ReferenceDraw {
  std::string what;  ///< one line for printing, e.g. "red quad at z 0.65"
  raster::State state;
  std::vector<raster::Vertex> vertices;
};

struct ReferenceSetup {
  std::string variant;
  std::string description;
  ReferenceView view = ReferenceView::Color;
  vec4 clearColor{0.0f};
  float clearDepth = 1.0f;
  int clearStencil = 0;
  std::vector<ReferenceDraw> draws;
};

/// The variant names of basics/reference, in registration order.
const std::vector<std::string>& referenceVariants();

/// The setup of a variant for a framebuffer of `size` (clip-space geometry does not
/// depend on it; the aspect ratio only widens the view of perspective variants).
/// Error(Usage) listing the variants for an unknown name.
ReferenceSetup referenceSetup(std::string_view variant, ivec2 size);

}  // namespace glint::scenes
