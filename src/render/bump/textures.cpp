#include "glint/render/bump/textures.h"

namespace glint::render::bump {

gl::Texture uploadImage(const Image& image, const UploadOptions& options) {
  static constexpr GLenum kFormats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  static constexpr GLenum kU8[] = {GL_R8, GL_RG8, GL_RGB8, GL_RGBA8};
  static constexpr GLenum kU16[] = {GL_R16, GL_RG16, GL_RGB16, GL_RGBA16};
  static constexpr GLenum kF32[] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
  const int c = image.channels() - 1;
  GLenum internal = kU8[c], type = GL_UNSIGNED_BYTE;
  if (image.type() == PixelType::U16) internal = kU16[c], type = GL_UNSIGNED_SHORT;
  if (image.type() == PixelType::F32) internal = kF32[c], type = GL_FLOAT;

  Image flipped = image;
  flipped.flipVertical();
  gl::Texture texture(GL_TEXTURE_2D, options.label);
  texture.storage(internal, image.width(), image.height(), 1, options.mipmaps ? 0 : 1);
  texture.upload(0, image.width(), image.height(), kFormats[c], type, flipped.bytes().data());
  if (options.mipmaps) texture.generateMipmap();
  const GLenum mag = options.nearest ? GL_NEAREST : GL_LINEAR;
  const GLenum min = options.mipmaps ? (options.nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_LINEAR) : mag;
  texture.filtering(min, mag, options.wrap);
  return texture;
}

}  // namespace glint::render::bump
