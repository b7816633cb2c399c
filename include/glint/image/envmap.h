#pragma once
// glint/image/envmap.h — environment-map geometry without GL: the CPU references
// the GPU paths of render/env are tested against.
//
// Contents
//   Cube map faces      face order, face texel → direction, direction → face texel
//   Equirectangular     direction ↔ (u, v), bilinear sampling of a lat-long image
//   Display encoding    exposure + filmic tone curve + sRGB, shared with shaders/env/envmap.glsl
//   Sphere maps         GL_SPHERE_MAP's (s, t) ↔ direction, coverage and resolution figures
//   Validation          equirect images and six cube faces (square, equal sizes)
//
// Conventions (the same in every shader under shaders/env/)
//   - Right-handed world, +Y up. A direction is any non-zero vec3 (need not be unit).
//   - Cube faces in GL order: +X, −X, +Y, −Y, +Z, −Z (GL_TEXTURE_CUBE_MAP_POSITIVE_X + i).
//     Within a face, (s, t) ∈ [0, 1]² follow the OpenGL spec's table (§8.13): texel row 0
//     is t ≈ 0 as uploaded with glTexSubImage (i.e. the LAST row of a glint::Image read
//     back with gl::readTexture, which flips rows).
//   - Equirect images: row 0 (top) looks up (+Y); the centre column (u = 0.5) looks
//     along −Z, u = 0.75 along +X. v = 0 at the top.
//   - Sphere maps are defined in a frame: a rotation from world to the "eye space" of
//     the view they were made for; the viewer looks along −Z of that frame.

#include "glint/core/math.h"
#include "glint/image/image.h"

#include <array>
#include <span>
#include <string>

namespace glint {

// ---------------------------------------------------------------------------
// Cube map faces

constexpr int kCubeFaces = 6;
/// "+X", "-X", "+Y", "-Y", "+Z", "-Z" for faces 0..5.
const char* cubeFaceName(int face);

/// Direction through point (s, t) ∈ [0, 1]² of a face (not normalized; the major
/// axis component is ±1).
vec3 cubeFaceDirection(int face, vec2 st);
/// Direction through the centre of texel (x, y) of a face of `size` texels, y = GL row
/// (0 = t ≈ 0).
vec3 cubeTexelDirection(int face, int x, int y, int size);

struct CubeCoord {
  int face = 0;  ///< 0..5 in GL order
  vec2 st{0.0f}; ///< position on the face, [0, 1]²
};
/// Which face a direction hits and where (the OpenGL spec's major-axis rule; ties go to
/// X, then Y, like Mesa).
CubeCoord cubeLookup(vec3 direction);

// ---------------------------------------------------------------------------
// Equirectangular (latitude/longitude) images

/// (u, v) ∈ [0, 1]² of a direction; u wraps, v = 0 looks straight up.
vec2 equirectUv(vec3 direction);
/// Unit direction of an equirect position.
vec3 equirectDirection(vec2 uv);
/// Bilinear sample of channels 0..2 at a direction: u wraps around, v clamps at the poles
/// (GL_REPEAT / GL_CLAMP_TO_EDGE, texel centres at half-integers, as GL samples).
vec3 sampleEquirect(const Image& equirect, vec3 direction);

// ---------------------------------------------------------------------------
// Display encoding: HDR radiance → the 8-bit colours glint's environment textures hold

/// exposure × radiance, Narkowicz's fit of the ACES filmic curve, then the sRGB transfer
/// function. Output in [0, 1]. shaders/env/envmap.glsl's displayEncode() is the same code.
vec3 displayEncode(vec3 radiance, float exposure = 1.0f);

/// A photograph of the environment: a pinhole camera at its centre looking along yaw
/// (radians about +Y; 0 looks along −Z, π/2 along −X) and pitch (radians up), vertical
/// field of view `fovY` degrees, 2×2 samples per pixel, display-encoded into U8 RGBA (row 0
/// at the top). glint post's "real photograph": a view of a real HDR photograph.
Image perspectiveView(const Image& equirect, ivec2 size, float yaw, float pitch, float fovY, float exposure = 1.0f);

// ---------------------------------------------------------------------------
// Sphere maps (GL_SPHERE_MAP)
//
// A sphere map is the picture of a mirror ball seen from infinitely far away along −Z of
// its frame. Texel (s, t) shows the reflection r off the ball's normal n = (x, y, √(1−x²−y²))
// with x = 2s − 1, y = 2t − 1. Texgen computes the inverse: m = 2√(rx² + ry² + (rz+1)²),
// (s, t) = (rx/m + ½, ry/m + ½). Directions within θ of the viewer (+Z) land at radius
// sin(θ/2): the front hemisphere (θ < 90°) fills the disk of radius 1/√2, the back
// hemisphere the ring outside it, and the exact back direction (θ = 180°) the whole rim —
// the singularity. The corners outside the disk are never looked up: wasted texels.

/// Sphere-map (s, t) of a direction given in the map's frame (GL_SPHERE_MAP's formula).
/// The back direction (0, 0, −1) has no unique answer; this returns the rim point (1, ½).
vec2 sphereMapUv(vec3 directionInFrame);
/// Unit reflection direction (in the map's frame) shown at (s, t); `inside` is false for
/// points outside the unit disk (the direction returned is then the back direction).
vec3 sphereMapDirection(vec2 st, bool* inside = nullptr);

struct SphereMapCoverage {
  int size = 0;               ///< texels along each side
  double wastedFraction = 0;  ///< texel centres outside the disk (→ 1 − π/4 ≈ 21.5%)
  double frontFraction = 0;   ///< texels showing the front hemisphere (→ π/8 ≈ 39.3%)
  double backFraction = 0;    ///< texels showing the back hemisphere (→ π/8 ≈ 39.3%)
};
/// Counts a size × size sphere map's texels by what their centres show.
SphereMapCoverage sphereMapCoverage(int size);

struct AngularResolution {
  double radial = 0;      ///< texels per radian along the great circle through the view axis
  double tangential = 0;  ///< texels per radian around the view axis
  double minimum() const { return radial < tangential ? radial : tangential; }
};
/// Texels per radian of a size × size sphere map for directions θ radians away from the
/// viewer: radial = size·cos(θ/2)/4, tangential = size/(4·cos(θ/2)). Radial resolution falls
/// to 0 at the back (θ = π): the singularity.
AngularResolution sphereMapResolution(int size, double theta);
/// Texels per radian of a cube map with `faceSize` texels per face edge, at a face centre
/// (its lowest resolution; towards face corners it rises to 3× radially).
double cubeMapResolution(int faceSize);
/// The cube face size with the same worst-case resolution as a sphere map over the
/// directions within `maxTheta` of the viewer (2 × the sphere map's minimum texels/radian).
double equivalentCubeFaceSize(int sphereMapSize, double maxTheta);

// ---------------------------------------------------------------------------
// Validation (Error(Input), one line, naming the file)

/// An equirect image needs 3 or 4 channels, width = 2 × height, and finite values.
void validateEquirect(const Image& image, const std::string& name);
/// Six faces (GL order) must be square and all the same size (the WWDC 2001 talk: "the width and
/// height must be identical"); `names` are used in messages (file names).
void validateCubeFaces(std::span<const Image> faces, std::span<const std::string> names);

}  // namespace glint
