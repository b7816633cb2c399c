#pragma once
// glint/image/normalmap.h — normal maps without GL: height → normal, encoding, checks.
//
// Contents
//   NormalFormula        the consistent gradient normal, or the lecture slide's formula as written
//   NormalMapOptions     scale (bumpiness), edge wrap, formula
//   heightNormal         the per-texel formula from the four neighbours n, s, e, w
//   heightToNormalMap    a whole height map → RGBA8 normal map (the CPU reference of the
//                        GPU pass in render/bump/height_to_normal.h; they agree within 1/255)
//   heightFromImage      any image → one-channel height (luminance when it has colour)
//   encodeNormal / decodeNormal   n ↔ (n + 1) / 2, the unsigned encoding of the WWDC 2001 talk (and
//                        DirectX's green-down variant); the one encoding baker and renderer use
//   NormalSpace          the frame a map's normals are in: tangent, object or world
//   prepareNormalMap     validate a normal map read from a file, with a clear message when
//                        its encoding is not what a renderer expects
//
// Conventions
//   - Texel directions: east = +x (next column), north = towards row 0, i.e. UP in the
//     picture. Textures are uploaded bottom row first (render/bump/textures.h), so north is
//     also +v, the mesh's bitangent direction: the normal maps made here are "OpenGL style"
//     (green = +Y = up), the convention of MikkTSpace, Blender and glTF.
//   - Heights are normalized values (0..1 for 8/16-bit images). `scale` says how high the
//     full 0..1 range stands, in texel widths: with scale = 8 a ramp from black to white over
//     8 texels is a 45° slope.
//
// The VGP353 lecture's slide, "Normal Map Generation", reads the four texels n, s, e, w and computes
//     d = vec3(e.x − w.x, s.y − n.y, 0.0);  d.z = 1.0 − sqrt(dot(d, d));  d = normalize(d);
// Two things about it are worth knowing (tests/bump/normalmap_test.cpp checks both):
//   1. Signs. The surface z = h(x, y) has the normal (−∂h/∂x, −∂h/∂y, 1): both components
//      point DOWNHILL. With north = +y, s − n = −2∂h/∂y is downhill, but e − w = +2∂h/∂x is
//      uphill. The slide's map is mirrored left–right: a bump lit from the east looks lit
//      from the west. (Its x and y agree only if north is −y — image rows growing
//      downwards — and then both are uphill, i.e. every bump reads as a dent.)
//   2. The z it computes. The geometric z before normalization is 1 for every slope; the
//      slide's 1 − |d| shrinks with the slope, so normals tilt further than the surface
//      (tilt = atan(|d| / (1 − |d|)) instead of atan(|d|)), lie flat at |d| = 1 and point
//      INTO the surface beyond it (possible diagonally: each difference reaches 1, so
//      |d| reaches √2). NormalFormula::Slide reproduces all of this on purpose;
//      NormalFormula::Gradient is what glint uses.

#include "glint/core/math.h"
#include "glint/image/image.h"

#include <string>
#include <string_view>

namespace glint {

enum class NormalFormula {
  Gradient,  ///< n = normalize(scale·(w − e)/2, scale·(s − n)/2, 1): the surface's true normal
  Slide      ///< the VGP353 lecture as written, d = (scale/2)·(e − w, s − n), z = 1 − |d| (scale 2 = the slide)
};

struct NormalMapOptions {
  float scale = 8.0f;   ///< height of the full 0..1 range in texel widths (bumpiness); any real value
  bool wrap = false;    ///< neighbours across an edge wrap around (tileable maps); false: clamp to edge
  NormalFormula formula = NormalFormula::Gradient;
};

/// The unit normal of one texel from the heights of its north, south, east and west
/// neighbours. Identical arithmetic to shaders/bump/height_to_normal.frag.
vec3 heightNormal(float north, float south, float east, float west, const NormalMapOptions& options = {});

/// A unit vector (or any vector in [−1, 1]³) → colour in [0, 1]³: (n + 1) / 2, green (y)
/// negated first for a DirectX-style map (green down, the Unreal convention).
inline vec3 encodeNormal(vec3 n, bool directX = false) {
  if (directX) n.y = -n.y;
  return n * 0.5f + 0.5f;
}
/// Colour in [0, 1]³ → vector in [−1, 1]³ (not normalized): 2c − 1, green negated for a
/// DirectX-style map. The exact inverse of encodeNormal.
inline vec3 decodeNormal(vec3 c, bool directX = false) {
  vec3 n = c * 2.0f - 1.0f;
  if (directX) n.y = -n.y;
  return n;
}

/// One-channel height from any image: channel 0 of a one- or two-channel image, Rec.709
/// luminance of an RGB(A) one. Sets *usedLuminance (when given) to whether colour was
/// converted, so a front end can say so. Keeps the pixel type.
Image heightFromImage(const Image& image, bool* usedLuminance = nullptr);

/// `glint normalmap --formula` and glint.normalmap's formula: "gradient" or "slide";
/// Error(Usage) for another name.
NormalFormula parseNormalFormula(std::string_view name);

/// The checks and words every front end of `glint normalmap` (the command, glint.normalmap)
/// gives a height map before it is turned into normals, from this one place: Error(Usage)
/// for a scale that is not finite; Error(Input), one line, for an empty image or a height that
/// is not finite (NaN or inf: it would make black texels without a word), naming the first
/// such texel; a warning when a colour image is turned into its luminance, and another when
/// that image already looks like a normal map. `what` names the input ("bricks.exr").
void checkHeightMap(const Image& height, const NormalMapOptions& options, std::string_view what);

/// Normal map of a height map of any size (power of two or not) and type: RGBA8, alpha 255,
/// rgb = encodeNormal(heightNormal(...)) rounded to 8 bits. A colour image is converted with
/// heightFromImage first. Rows as in the input (row 0 at the top).
Image heightToNormalMap(const Image& height, const NormalMapOptions& options = {});

/// What `glint normalmap` writes for `height`: `normals` (heightToNormalMap's, or the GPU
/// pass's) as 8-bit RGB, or RGBA carrying the height's alpha when it has one (grey + alpha,
/// RGBA).
Image withHeightAlpha(const Image& normals, const Image& height);

/// The frame a normal map's vectors are expressed in.
enum class NormalSpace {
  Tangent,  ///< relative to the surface's MikkTSpace frame: z (blue) points out, mostly > 0.5;
            ///< survives animation (the baker's default)
  Object,   ///< the mesh's own coordinates: any direction
  World     ///< object space transformed by a model matrix (bake::BakeOptions::objectToWorld)
};

/// What prepareNormalMap found and did.
struct NormalMapReport {
  double meanLength = 0;        ///< mean length of the decoded vectors (1 for a good map)
  double outwardFraction = 0;   ///< fraction of texels with decoded z > 0
  std::string conversion;       ///< what was converted (empty when used as it is), for a log line
};

/// Checks a normal map read from a file and returns it as RGBA8 (n + 1) / 2 encoded.
/// Accepted: RGB(A) 8/16-bit; float RGB(A) in [0, 1] (unsigned encoding) or with
/// negative values (signed encoding: re-encoded); two channels (x, y, as in BC5/RGTC maps:
/// z = sqrt(1 − x² − y²) is reconstructed). Error(Input) with one line naming `name` and
/// what to do, when:
///   - it has one channel (a height map: "glint normalmap" turns it into a normal map),
///   - the decoded vectors are not unit length (mean length off by more than 0.15: a colour
///     texture, or an sRGB-encoded/compressed map),
///   - space == Tangent and fewer than 90% of the vectors point outwards (blue ≥ 0.5): an
///     object-space map, or channels swapped.
Image prepareNormalMap(const Image& image, std::string_view name, NormalSpace space = NormalSpace::Tangent,
                       NormalMapReport* report = nullptr);

}  // namespace glint
