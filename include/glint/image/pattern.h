#pragma once
// glint/image/pattern.h — procedural test images for texture filtering.
//
// Contents
//   makeCheckerboard   two-colour checks: the worst case for minification aliasing
//   drawText           a built-in 5×7 pixel font (A–Z, 0–9, . - : / ×), no font files
//   makeTestChart      a resolution chart: text at several sizes, line gratings, a grid
//
// All return RGBA8 images, row 0 at the top. They tile seamlessly (GL_REPEAT).

#include "glint/core/math.h"
#include "glint/image/image.h"

#include <string_view>

namespace glint {

/// size × size texels with checks × checks squares of colours a and b (a at the top left).
Image makeCheckerboard(int size, int checks, vec3 a = vec3(0.95f), vec3 b = vec3(0.08f));

/// Draws `text` with its top-left corner at (x, y); each font pixel becomes scale × scale
/// pixels; glyphs advance 6 × scale. Unknown characters draw as a box; lowercase is
/// drawn as uppercase. Pixels outside the image are clipped.
void drawText(Image& image, int x, int y, std::string_view text, int scale, vec3 color);

/// A size × size resolution chart (size ≥ 256): dark text lines from large to small on
/// white, horizontal and vertical line gratings, and a thin grid at the tile border.
Image makeTestChart(int size = 512);

}  // namespace glint
