#pragma once
// glint/render/bump/textures.h — glint::Image → texture, with the row order every bump and
// water technique relies on.
//
// Images keep row 0 at the top; textures put t = 0 at the bottom. uploadImage uploads the
// LAST row first, so a picture appears upright on a mesh whose v grows upwards (glint's
// mesh convention) and gl::readTexture (which flips back) returns the same image. "North"
// in a height map (up in the picture) is then +v — the bitangent direction of MikkTSpace —
// which is what image/normalmap.h's OpenGL-style normal maps assume.
//
/// ```cpp
/// #include <glint/image/heightfield.h>
/// #include <glint/image/normalmap.h>
/// const glint::Image height = glint::makeBrickHeight(512);
/// const glint::gl::Texture normals =
///     glint::render::bump::uploadImage(glint::heightToNormalMap(height), {.label = "normal-map"});
/// ```

#include "glint/gl/objects.h"
#include "glint/image/image.h"

#include <string_view>

namespace glint::render::bump {

struct UploadOptions {
  bool mipmaps = true;        ///< full chain + trilinear filtering; false: one level, bilinear
  GLenum wrap = GL_REPEAT;    ///< wrap mode on S and T
  bool nearest = false;       ///< GL_NEAREST filtering (exact texel values; tests)
  std::string_view label = "image";
};

/// Uploads `image` (1–4 channels, 8/16-bit or float) into a new 2D texture of the matching
/// linear format (R8/RG8/RGB8/RGBA8, the 16-bit and 32F equivalents), rows flipped as above.
gl::Texture uploadImage(const Image& image, const UploadOptions& options = {});

}  // namespace glint::render::bump
