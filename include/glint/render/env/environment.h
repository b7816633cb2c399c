#pragma once
// glint/render/env/environment.h — environment maps on the GPU: loading a real
// environment, converting it to a cube map, deriving a sphere map from the cube map.
//
// Contents
//   findEnvironment      a named HDRI ("courtyard") → its file in glint's data directory
//   loadEquirect         read + validate an equirectangular HDR/EXR
//   cubeFromEquirect     render the six faces through a framebuffer object, then mipmaps
//   cubeFromFaces        six face images (square, equal) → cube map with mipmaps
//   sphereMapFromCube    render a sphere map from a cube map (the WWDC 2001 talk: sphere maps are
//                        "generated from these six images")
//
// Every texture made here is RGBA8 holding display-encoded colour (image/envmap.h's
// displayEncode: exposure, filmic curve, sRGB) with a full mip chain and trilinear
// filtering, like the 8-bit maps of 2001: the shader paths and the fixed-function path
// then sample identical texels. Cube maps use GL_CLAMP_TO_EDGE; draw with
// GL_TEXTURE_CUBE_MAP_SEAMLESS enabled (the drawing classes here do).
//
// Data: environments come from Debian's blender-data package (CC0 HDRIs by Greg Zaal),
// extracted by scripts/setup into <source>/data/env and installed into
// <prefix>/share/glint/env; core/locations.h says where they are looked up
// (the environment variable GLINT_DATA_DIR overrides).
//
// Errors are glint::Error with one line: Input for a missing or corrupt file, a
// non-2:1 equirect, non-square or unequal cube faces.

#include "glint/core/math.h"
#include "glint/gl/objects.h"
#include "glint/image/image.h"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace glint::render::env {

/// env/<name>.exr in glint's data (core/locations.h's findDataFile). Error(Input) naming
/// where it looked and how to get it (scripts/setup, GLINT_DATA_DIR) when it is missing.
std::filesystem::path findEnvironment(std::string_view name);
/// Loads an equirectangular image (any format image/image.h reads; HDR and EXR keep
/// their range) and validates it. Error(Input), one line, when missing, corrupt or not 2:1.
Image loadEquirect(const std::filesystem::path& path);

struct CubeFromEquirectOptions {
  int faceSize = 256;      ///< texels per face edge (a 1024-wide equirect has 256 per 90°)
  float exposure = 1.0f;   ///< radiance scale before the tone curve
  int samples = 2;         ///< samples² HDR lookups averaged per texel
  std::string_view label = "environment-cube";
};
/// Uploads `equirect` (float or 8-bit, RGB/RGBA) and renders each cube face through a
/// framebuffer object whose colour attachment is that face, then glGenerateMipmap.
gl::Texture cubeFromEquirect(const Image& equirect, const CubeFromEquirectOptions& options = {});

/// Builds a cube map from six faces in GL order (+X −X +Y −Y +Z −Z). Row 0 of each
/// glint::Image is uploaded first (t = 0), as 2001 code passed files to glTexImage2D, so
/// side faces viewed as image files have +Y at the top. Float faces are display-encoded
/// with `exposure`; 8-bit faces are used as they are. Error(Input) when the faces are not
/// square and equal (`names`, e.g. file names, are used in the message).
gl::Texture cubeFromFaces(std::span<const Image> faces, std::span<const std::string> names = {},
                          float exposure = 1.0f);
/// Loads six face files (+X −X +Y −Y +Z −Z) and calls cubeFromFaces.
gl::Texture loadCubeFaces(std::span<const std::filesystem::path> paths, float exposure = 1.0f);

struct SphereMapOptions {
  int size = 512;          ///< texels per side (a 512² sphere map matches a 256² cube map head-on)
  mat3 worldToFrame{1.0f}; ///< rotation into the map's frame: the view it is made for looks along −Z
  int samples = 4;         ///< samples² cube lookups per texel (the rim needs many)
  std::string_view label = "sphere-map";
};
/// Renders a sphere map of `cube` through a framebuffer object, then mipmaps. Wasted
/// texels (centre outside the ball) are (0, 0, 0, 0); used texels have alpha 1.
gl::Texture sphereMapFromCube(const gl::Texture& cube, const SphereMapOptions& options = {});

}  // namespace glint::render::env
