#pragma once
// glint/image/pattern.h — procedural test images for texture filtering.
//
// Contents
//   makeCheckerboard   two-colour checks: the worst case for minification aliasing
//   drawText           a built-in 5×7 pixel font (A–Z, 0–9, . - : / ×), no font files
//   makeTestChart      a resolution chart: text at several sizes, line gratings, a grid
//   makeZonePlate      the classic FFT / sampling test pattern: a radial chirp
//   makeRectangle      a white rectangle on black: the FFT textbook's 2D sinc
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

/// A size × size zone plate: 0.5 + 0.5·cos(π·r²/(√2·size)), r in pixels from the centre, so
/// the local frequency grows linearly from 0 at the centre to 0.5 cycles/pixel (Nyquist) in
/// the corners: no aliasing. Its Fourier transform is again a chirp (the rings are in the
/// phase; the magnitude is roughly even); a low-pass filter keeps the middle rings and greys
/// out the rest.
Image makeZonePlate(int size = 256);

/// A size × size black image with a white w × h rectangle in the middle (pixel-aligned):
/// its spectrum is the product of two sinc functions, a cross of decaying lobes.
Image makeRectangle(int size = 256, int w = 32, int h = 16);

}  // namespace glint
