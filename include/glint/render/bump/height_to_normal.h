#pragma once
// glint/render/bump/height_to_normal.h — the VGP353 lecture's "Normal Map Generation" on the GPU: a
// fragment shader on a full-screen quad reads the four texels around each texel (n, s, e,
// w) of a height texture and writes the encoded normal into a framebuffer object.
//
/// ```cpp
/// #include <glint/image/heightfield.h>
/// #include <glint/render/bump/textures.h>
/// namespace bump = glint::render::bump;
/// const glint::gl::Texture height = bump::uploadImage(glint::makeBrickHeight(512), {.label = "height"});
/// bump::HeightToNormalPass pass;  // with a current GL context
/// glint::gl::Texture normals(GL_TEXTURE_2D, "normals");
/// normals.storage(GL_RGBA8, height.width(), height.height());
/// pass.run(height, normals, {.scale = 8.0f, .wrap = true});
/// ```
//
// The arithmetic is image/normalmap.h's heightNormal, line for line
// (shaders/bump/height_to_normal.frag), so the GPU and CPU maps agree within one 8-bit step
// (tests/bump/height_to_normal_test.cpp). Neighbours are read with texelFetch at integer
// coordinates, wrapped or clamped by hand: exact for any size, power of two or not, and
// independent of the height texture's filtering. Heights come from the red channel of any
// 2D texture: R8/R16/R32F images, or the RG32F wave state (R = height).

#include "glint/gl/objects.h"
#include "glint/image/normalmap.h"
#include "glint/render/gpu_mesh.h"

namespace glint::render::bump {

class HeightToNormalPass {
public:
  HeightToNormalPass();
  /// Renders the normal map of `height` (level 0) into level 0 of `normalMap`, which must be a
  /// 2D texture of the same size in a colour-renderable format (GL_RGBA8 for the (n + 1)/2
  /// encoding; float formats store the same encoded values unrounded). Regenerates
  /// normalMap's mipmaps when it has more than one level. The caller's framebuffer binding and
  /// viewport are put back (render::SavedTarget).
  /// Error(Usage) when the sizes differ.
  void run(const gl::Texture& height, const gl::Texture& normalMap, const NormalMapOptions& options = {});

private:
  FullscreenPass m_pass;
  gl::Framebuffer m_framebuffer;
};

/// CPU image in, CPU image out, through the GPU pass: uploads `height` (luminance if it has
/// colour), renders into an RGBA8 texture and reads it back (row 0 at the top). Needs a
/// current context. Equal to heightToNormalMap(height, options) within 1/255.
Image heightToNormalMapGpu(const Image& height, const NormalMapOptions& options = {});

}  // namespace glint::render::bump
