#pragma once
// glint/image/post.h — WWDC 2003 session 212's post-processing effects on the CPU: the references the
// GPU passes of render/post are tested against, with every convention written down.
//
// Contents
//   postLuma             the luma every effect uses: YIQ's Y (BT.601 weights)
//   Sepia                WWDC 2003 session 212's YIQ sepia: keep Y, hard-code I and Q, back to RGB
//   Sobel                horizontal / vertical edges and the gradient magnitude
//   Edges                Sobel edges composited over the image (darkening): the NPR lines
//   Kuwahara             the edge-preserving "posterize" filter, brute force
//
// Conventions (the GPU passes follow them exactly; docs/post.md has pictures)
//   - Input: 8-bit RGBA (Image U8, 4 channels; 3 channels are read as opaque), row 0 at the
//     TOP, as video frames and image files store them. Other types: Error(Usage).
//   - Effects work on the stored values — sRGB-encoded, as a camera, a video file and WWDC
//     2003 session 212's 8-bit textures hold them — not on linear light; alpha passes through.
//   - Results are F32 RGBA, unrounded. The GPU writes the same values into RGBA8 targets,
//     rounding to nearest, so round(255 · reference) and the GPU agree within one step.
//   - Borders: neighbours outside the image repeat the nearest edge pixel (clamp to edge,
//     OpenCV's BORDER_REPLICATE).
//   - x grows to the right, y grows DOWN (row index). A derivative ∂/∂y is positive where
//     the image gets brighter towards the bottom (cv::Sobel's dy on a top-first image).
//
/// ```cpp
/// const glint::Image photo = glint::postInput(glint::loadImage("street.png"));  // U8 RGBA
/// const glint::Image sepia = glint::sepiaReference(photo, {.i = 0.2f, .q = 0.0f});  // WWDC 2003 session 212's values
/// const glint::KuwaharaReference k = glint::kuwaharaReference(photo, {.size = 3});
/// glint::saveImage(glint::quantizeToU8(k.image), "street-posterized.png");  // what an RGBA8 target holds
/// ```

#include "glint/core/math.h"
#include "glint/image/image.h"

#include <array>
#include <cstdint>
#include <vector>

namespace glint {

// ---------------------------------------------------------------------------
// Luma

/// YIQ's Y (= BT.601 luma Y'): the weights NTSC broadcast, JPEG and cv::cvtColor's
/// RGB2GRAY use. Applied to stored (gamma-encoded) values.
constexpr double kLumaR = 0.299, kLumaG = 0.587, kLumaB = 0.114;
inline float postLuma(vec3 rgb) { return float(kLumaR) * rgb.r + float(kLumaG) * rgb.g + float(kLumaB) * rgb.b; }

// ---------------------------------------------------------------------------
// Sepia (WWDC 2003 session 212: "RGB → YIQ, keep Y, hard-code I and Q, back to RGB")
//
// YIQ is NTSC's colour space; the FCC matrix (rows Y, I, Q) is
//     Y = 0.299  R + 0.587  G + 0.114  B
//     I = 0.5959 R − 0.2746 G − 0.3213 B
//     Q = 0.2115 R − 0.5227 G + 0.3112 B
// and its inverse is computed in double. Because the I and Q rows sum to zero, the
// inverse's first column is (1, 1, 1), so with I and Q fixed the round trip is
//     rgb' = Y·(1, 1, 1) + c,   c = M⁻¹·(0, I, Q)      — "a dot product and an add"
// and the Y row times c is zero: the luma is preserved exactly. WWDC 2003 session 212's values are
// I = 0.2, Q = 0 (c ≈ (+0.191, −0.054, −0.221): orange-brown).
//
// Where Y + c leaves [0, 1] (shadows below Y ≈ 0.22 and highlights above Y ≈ 0.81 for the
// talk's values) the framebuffer would clip a channel and the luma would change. Instead
// the offset is shortened to t·c with the largest t ≤ 1 that keeps every channel in
// [0, 1] — one more multiply and a min; luma stays exact and shadows and highlights fade
// towards neutral, as they do in toned prints. (The common "sepia matrix" brightens the
// image instead: its rows sum to 1.351, 1.203 and 0.937.)

struct SepiaOptions {
  float i = 0.2f;  ///< the hard-coded I (in-phase: orange ↔ blue); WWDC 2003 session 212: 0.2
  float q = 0.0f;  ///< the hard-coded Q (quadrature: purple ↔ green); WWDC 2003 session 212: 0
};

/// The forward YIQ matrix above, row-major (rows Y, I, Q).
std::array<std::array<double, 3>, 3> yiqFromRgb();
/// Its inverse, computed in double, row-major (rows R, G, B; columns Y, I, Q).
std::array<std::array<double, 3>, 3> rgbFromYiq();
/// c = M⁻¹·(0, I, Q): what the sepia pass adds to Y·(1, 1, 1).
dvec3 sepiaOffset(const SepiaOptions& options);
/// The sepia colour of one pixel, in double: Y·(1,1,1) + t·c with t as above.
dvec3 sepiaPixel(dvec3 rgb, const SepiaOptions& options);
/// Every pixel through sepiaPixel. F32 RGBA, alpha from the input.
Image sepiaReference(const Image& rgba, const SepiaOptions& options = {});

// ---------------------------------------------------------------------------
// Sobel (WWDC 2003 session 212's two 3×3 kernels, on postLuma)
//
//   Gx = [-1 0 +1; -2 0 +2; -1 0 +1]   (∂/∂x: positive where it gets brighter to the right)
//   Gy = [-1 -2 -1; 0 0 0; +1 +2 +1]   (∂/∂y: positive where it gets brighter downwards)
// with the kernels' top row on the row above the pixel. Gx finds vertical edges, Gy
// horizontal ones (WWDC 2003 session 212's "horizontal edges" use the pixels above and below).
// |Gx|, |Gy| ≤ 4 and the magnitude ≤ 4√2 for values in [0, 1].

enum class SobelOutput {
  Horizontal,  ///< horizontal edges: min(1, scale·|Gy|), gray
  Vertical,    ///< vertical edges: min(1, scale·|Gx|), gray
  Magnitude,   ///< both: min(1, scale·√(Gx² + Gy²)), gray
  SignedX,     ///< Gx with its sign: clamp(0.5 + 0.5·scale·Gx, 0, 1) (mid-gray = flat)
  SignedY      ///< Gy with its sign: clamp(0.5 + 0.5·scale·Gy, 0, 1)
};

struct SobelOptions {
  SobelOutput output = SobelOutput::Magnitude;
  float scale = 1.0f;  ///< gain before clamping: 1 shows a full black-to-white step (|G| = 4) as white
};

/// (Gx, Gy) at pixel (x, y) of an image's luma, with clamp-to-edge borders.
vec2 sobelGradient(const Image& rgba, int x, int y);
/// The Sobel image: gray in RGB, alpha from the input. F32 RGBA.
Image sobelReference(const Image& rgba, const SobelOptions& options = {});

// ---------------------------------------------------------------------------
// Edges composited over the image: rgb' = rgb · (1 − e), e = clamp(scale·(|G| − threshold), 0, 1)
// with |G| the Sobel magnitude of the image's own luma. Black lines on strong edges; weak
// edges (noise, texture) below `threshold` leave the image as it was. Kuwahara followed by
// this is WWDC 2003 session 212's posterize look.

struct EdgesOptions {
  float scale = 2.0f;      ///< how fast lines darken above the threshold
  float threshold = 0.25f; ///< Sobel magnitudes below this draw nothing
};

/// F32 RGBA, alpha from the input.
Image edgesReference(const Image& rgba, const EdgesOptions& options = {});

// ---------------------------------------------------------------------------
// Kuwahara (WWDC 2003 session 212's "posterize": four overlapping quadrants, keep the mean of the calmest)
//
// For pixel p and quadrant size s (WWDC 2003 session 212: 3), the four s×s quadrants share p as a
// corner and overlap along p's row and column:
//   0 upper-left   x ∈ [px−s+1, px], y ∈ [py−s+1, py]
//   1 upper-right  x ∈ [px, px+s−1], y ∈ [py−s+1, py]
//   2 lower-left   x ∈ [px−s+1, px], y ∈ [py, py+s−1]
//   3 lower-right  x ∈ [px, px+s−1], y ∈ [py, py+s−1]
// Each has a mean colour and a total variance Var(R) + Var(G) + Var(B) (alpha is not
// considered, and passes through). The output is the mean of the quadrant with the
// smallest variance; exact ties go to the lowest index.
//
// Arithmetic: with 8-bit values k = 255·v and n = s² texels, the sums Σk and
// D = Σ_c (n·Σk_c² − (Σk_c)²) = n²·255²·variance are integers, and the comparison is on D:
// exact. The GPU's statistics pass sums in 32-bit integers and stores Σk and D in a float
// texture: exact while D < 2²⁴ (s ≤ 4), rounded once above (s up to 8), and rounding keeps
// the order, so the GPU can choose differently only where two quadrants' variances agree to
// seven digits without being equal (never on the test images).

struct KuwaharaOptions {
  int size = 3;  ///< quadrant edge length s, 2..8; WWDC 2003 session 212: 3 (a 5×5 window)
};

struct KuwaharaReference {
  Image image;                     ///< F32 RGBA: the chosen quadrant's mean, input alpha
  std::vector<std::uint8_t> chosen;  ///< per pixel, row-major: the quadrant used (0..3)
  std::vector<std::uint8_t> tied;    ///< per pixel: bit q set when quadrant q has the minimum D
};

/// Brute force: every pixel's four quadrants summed from scratch (no statistics image), in
/// 64-bit integers. Error(Usage) for a size outside 2..8.
KuwaharaReference kuwaharaReference(const Image& rgba, const KuwaharaOptions& options = {});

// ---------------------------------------------------------------------------
// Helpers shared by the references and the tests

/// `image` as U8 RGBA (3 channels gain opaque alpha). Error(Usage) for other types or
/// channel counts: the effects are defined on 8-bit colour.
Image postInput(const Image& image);
/// round(255·v) into U8 RGBA: what an RGBA8 target stores for a reference's values.
Image quantizeToU8(const Image& reference);

}  // namespace glint
