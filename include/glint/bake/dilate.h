#pragma once
// glint/bake/dilate.h — the normal mapper's dilation filter: grow baked texels into the
// unused texels around UV islands, so bilinear fetches and mipmaps near island borders
// read baked values instead of the background.
//
// Each pass fills every empty texel that has at least one filled 8-neighbour with the
// average of those neighbours (WWDC 2003 session 212's "grow out the normals ... a couple of times").
// After k passes every texel within k texels (Chebyshev distance) of an island is filled.
//
/// ```cpp run
/// #include <vector>
/// const int width = 8, height = 8;
/// std::vector<float> texels(std::size_t(width) * height * 4, 0.0f);  // RGBA, a normal in RGB
/// std::vector<std::uint8_t> filled(std::size_t(width) * height, 0);  // 1 where the bake wrote a value
/// texels[0] = 0.0f, texels[1] = 0.0f, texels[2] = 1.0f, texels[3] = 1.0f;  // one baked texel at (0, 0)
/// filled[0] = 1;
/// const std::uint64_t grown = glint::bake::dilate(texels, 4, width, height, filled, {.passes = 16, .unitVectorChannels = 3});
/// // grown == 63: every texel is within 16 texels of (0, 0), and holds its normal now
/// ```

#include <cstdint>
#include <span>

namespace glint::bake {

struct DilateOptions {
  int passes = 16;              ///< how many texels to grow; negative: until nothing is empty
  int unitVectorChannels = 0;   ///< 3: channels 0..2 hold a unit vector, renormalized after averaging
};

/// Dilates `texels` (width × height × channels floats, row-major) in place. `filled` (one
/// byte per texel) says which texels hold values on entry and is updated to include the
/// grown ones. Returns how many texels were filled. Deterministic (passes are computed
/// from the previous pass's state, not in scan order). A fully empty image stays empty.
std::uint64_t dilate(std::span<float> texels, int channels, int width, int height,
                     std::span<std::uint8_t> filled, const DilateOptions& options = {});

}  // namespace glint::bake
