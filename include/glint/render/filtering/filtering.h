#pragma once
// glint/render/filtering/filtering.h — texture filtering on a ground plane receding to the
// horizon, and how far each filter is from the truth (the WWDC 2001 talk: "anisotropic filtering").
//
// Contents
//   FilterMode        min/mag filter, anisotropy, LOD bias — one per variant of filtering/*
//   standardModes     nearest, bilinear, bilinear-mip-nearest, trilinear, aniso 2/4/8/16, lod-bias
//   applyFilterMode   sets a sampler; rejects anisotropy outside 1..GL_MAX_TEXTURE_MAX_ANISOTROPY
//   GroundPlane       a textured plane from eye height to the horizon, drawn with a FilterMode
//   measureFiltering  error against a heavily supersampled ground truth, sharpness, flicker
//
// What the WWDC 2001 talk says, and what measureFiltering shows: bilinear filtering without mipmaps
// sparkles when the plane moves (flicker); trilinear removes the sparkle but blurs where
// the plane is oblique; anisotropic filtering keeps it sharp there and is closest to the
// truth. Anisotropy costs fill rate; query the maximum and stay within it.
//
/// ```cpp
/// #include <glint/image/pattern.h>
/// namespace filtering = glint::render::filtering;
/// const filtering::GroundPlane ground(glint::makeCheckerboard(512, 8));  // with a current GL context
/// const filtering::FilterMode trilinear = filtering::standardModes()[3];
/// ground.draw(filtering::GroundPlane::camera({1280, 720}, 0.0f), trilinear);
/// const filtering::FilterQuality quality = filtering::measureFiltering(ground, trilinear);
/// ```

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/image/image.h"
#include "glint/core/camera.h"
#include "glint/render/gpu_mesh.h"

#include <span>
#include <string>

namespace glint::render::filtering {

struct FilterMode {
  const char* name = "trilinear";
  GLenum minFilter = GL_LINEAR_MIPMAP_LINEAR;
  GLenum magFilter = GL_LINEAR;
  float anisotropy = 1.0f;  ///< GL_TEXTURE_MAX_ANISOTROPY: 1 = isotropic
  float lodBias = 0.0f;     ///< GL_TEXTURE_LOD_BIAS: negative = sharper, aliasing returns
  const char* description = "";
};

/// The filtering/* variants in order (names as the variants').
std::span<const FilterMode> standardModes();

/// GL_MAX_TEXTURE_MAX_ANISOTROPY of the current context (1 without the extension).
float maxAnisotropy();

/// Sets min/mag filter, anisotropy and LOD bias on `sampler`. Error(Usage), one line,
/// when mode.anisotropy is below 1 or above maxAnisotropy() (the WWDC 2001 talk: "the value set must
/// range from one up to the maximum available value").
void applyFilterMode(const gl::Sampler& sampler, const FilterMode& mode);

/// `mode` with its anisotropy clamped to what this GPU offers (for the variants, which
/// ask for 16 whatever the GPU: the note says when it was clamped).
FilterMode clampedToDevice(FilterMode mode);

class GroundPlane {
public:
  GroundPlane() = default;
  /// Uploads `texture` (RGBA8) with a full mip chain; the plane repeats it every
  /// `tileSize` world units out to 40 units ahead, and a band in the texture's mean
  /// colour continues it to the horizon.
  explicit GroundPlane(const Image& texture, float tileSize = 4.0f, std::string_view label = "ground");

  /// The standard view: eye 1 unit above the plane, looking down the plane towards the
  /// horizon, `forward` units along it (the camera move that shows sparkle).
  static Camera camera(ivec2 size, float forward = 0.0f);
  /// Window row (0 = top) of the horizon in a view of `size` from camera().
  static float horizonRow(ivec2 size);

  /// Clears to the sky colour and draws the plane into the bound framebuffer.
  void draw(const Camera& camera, const FilterMode& mode) const;
  /// Identifies the texture content and tiling (measureFiltering caches truths by it).
  const std::string& contentKey() const { return m_key; }

private:
  std::string m_key;
  gl::Texture m_texture;
  gl::Sampler m_sampler;
  gl::Program m_program;
  GpuMesh m_plane;
  GpuMesh m_band;
  float m_tileSize = 4.0f;
  vec3 m_meanColor{0.5f};
};

struct MeasureOptions {
  ivec2 size{160, 90};   ///< measurement resolution (small: the truth is size × supersample²)
  int supersample = 16;  ///< truth samples per pixel along each axis (16 × 16 = 256)
  int frames = 4;        ///< frames of the camera move, for flicker
  float step = 0.37f;    ///< camera move per frame, world units (not a multiple of the texture period)
};

struct FilterQuality {
  double rmsError = 0;        ///< luminance RMS error against the truth, ground only
  double sharpness = 0;       ///< mean |∇L| in the oblique band (far half of the ground)
  double truthSharpness = 0;  ///< the truth's in the same band
  double flicker = 0;         ///< frame-to-frame change the truth does not have (sparkle)
  double sharpnessRatio() const { return truthSharpness > 0 ? sharpness / truthSharpness : 0; }
};

/// Renders `options.frames` frames of the camera move with `mode` and with the truth
/// (GL_LINEAR from level 0 at size × supersample, box-filtered down) and compares them.
/// Truth images are cached per (ground, options) so measuring many modes renders it once.
/// Restores the framebuffer binding and viewport it found.
FilterQuality measureFiltering(const GroundPlane& ground, const FilterMode& mode, const MeasureOptions& options = {});

}  // namespace glint::render::filtering
