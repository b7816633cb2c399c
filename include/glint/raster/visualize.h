#pragma once
// glint/raster/visualize.h — pictures of the rasterizer's math, for teaching.
//
// The lecture decides coverage with three oriented edge equations E_i(x, y) = A·x + B·y + C
// (geometry.h): a pixel centre is inside when all three are >= 0. These functions draw
// each E_i over the whole window, so one sees the half-planes whose intersection is the
// triangle:
//
/// ```cpp
/// using glint::dvec2;
/// const glint::Image panels =
///     glint::raster::edgeFunctionsImage({dvec2(50, 450), dvec2(450, 450), dvec2(250, 50)}, 500, 500);
/// glint::saveImage(panels, "edges.png");  // three 500×500 panels, E0 | E1 | E2
/// ```
//
// Colour map (diverging, symmetric): negative values blue, zero white, positive red,
// saturated at ±scale pixels of signed distance; the zero line itself (the edge's line,
// |distance| <= 0.5 px) black; thin darker contours every scale/8 pixels; and the pixels
// the triangle covers (all three edges >= 0, the lecture's inside test) darkened so the
// intersection of the three positive half-planes stands out. Values are shown as signed
// distances E / sqrt(A² + B²) (pixels), so the three panels share one scale.

#include "glint/core/math.h"
#include "glint/image/image.h"
#include "glint/raster/geometry.h"

#include <array>

namespace glint::raster {

/// Diverging colour for t in [-1, 1]: -1 blue (0.23, 0.30, 0.75), 0 white, +1 red
/// (0.71, 0.02, 0.15); values outside are clamped.
vec3 divergingColor(double t);

/// One panel: edge equation `edge` at every pixel centre of a width×height window,
/// row 0 of the image = the TOP window row (as image files). scale <= 0 = max(w, h).
/// RGB U8. Error(Usage) for a non-positive size or an edge with A = B = 0.
Image edgeFunctionImage(const EdgeEquation& edge, int width, int height, double scale = 0.0);

/// The three orientation-normalized edges of the window-space triangle v (edge i is opposite
/// vertex i: v1→v2, v2→v0, v0→v1, each negated when the triangle is clockwise, so inside is
/// positive — as setupTriangle does), side by side with a 4-pixel grey gap. RGB U8.
/// scale as for edgeFunctionImage. Error(Usage) for a zero-area triangle (it has no inside).
Image edgeFunctionsImage(const std::array<dvec2, 3>& v, int width, int height, double scale = 0.0);

/// The orientation-normalized edge equations of edgeFunctionsImage.
std::array<EdgeEquation, 3> orientedEdges(const std::array<dvec2, 3>& v);

}  // namespace glint::raster
