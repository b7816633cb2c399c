#pragma once
// glint/image/metrics.h — numbers that judge a rendering against a reference.
//
// Contents
//   Region             a rectangle of pixels to measure (empty = the whole image)
//   boxDownsample      average factor × factor blocks: turns a supersampled render into
//                      the ground truth at display resolution
//   rmsError           root-mean-square difference on luminance
//   sharpness          mean luminance gradient magnitude: detail (and aliasing noise)
//   temporalFlicker    frame-to-frame change that the reference does not have: sparkle
//
// Every metric works on Rec.709 luminance of channels 0..2 (or channel 0 of gray
// images), normalized values (0..1 for integer images), so U8 readbacks and float
// references compare directly.

#include "glint/image/image.h"

#include <span>

namespace glint {

struct Region {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< [x0, x1) × [y0, y1); all zero = whole image
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

/// Luminance of pixel (x, y): Rec.709 weights on channels 0..2, or channel 0 when gray.
float luminance(const Image& image, int x, int y);

/// Averages factor × factor blocks into one F32 pixel (same channel count). Error(Usage)
/// when the size is not a multiple of factor.
Image boxDownsample(const Image& image, int factor);

/// √(mean (La − Lb)²) over `region`. Error(Usage) when the sizes differ.
double rmsError(const Image& a, const Image& b, Region region = {});

/// Mean of |∇L| (forward differences, √(dx² + dy²)) over `region`. A blurred image scores
/// lower than its reference; an aliased one often higher (the noise is "detail" too), so
/// read it next to rmsError.
double sharpness(const Image& image, Region region = {});

/// Sparkle: the frame-to-frame change of `frames` that the reference sequence `truth`
/// (same camera path) does not have, √(mean ((f[i+1] − f[i]) − (t[i+1] − t[i]))²) over all
/// consecutive pairs and pixels of `region`. Error(Usage) for fewer than two frames or
/// mismatched counts/sizes.
double temporalFlicker(std::span<const Image> frames, std::span<const Image> truth, Region region = {});

}  // namespace glint
