#pragma once
// glint/render/water/water_surface.h — shading water with the normal map of a simulated
// height field: cube-map reflection, refraction onto a pool floor, a sun highlight.
//
// Contents
//   WaterSurfaceOptions   look of the water (Fresnel, depth, colour, sun)
//   WaterSurface          draws a pool of water: a grid in the XZ plane, shaded per pixel
//   skyEnvironment        the cube map to reflect: the env module's HDR environment when
//                         glint's data is installed, else a procedural sky (and says which)
//
// Per pixel (shaders/water/surface.frag): the normal comes from the normal map the
// height→normal pass made from the wave heights (the VGP353 lecture: "the resulting texture can be
// used ... to generate a normal map"), turned from the grid's tangent space (u = +X,
// v = −Z, up = +Y) into world space. The view ray is reflected by it into the cube map and
// refracted (water's index 1.33) down to a tiled pool floor; Schlick's Fresnel term mixes the
// two, so the water mirrors the sky at grazing angles and shows the floor looking down.

#include "glint/gl/objects.h"
#include "glint/core/camera.h"
#include "glint/render/gpu_mesh.h"

#include <string>

namespace glint::render::water {

struct WaterSurfaceOptions {
  float halfSize = 1.0f;            ///< the pool spans [−halfSize, halfSize] in X and Z, surface at y = 0
  float displacement = 0.04f;       ///< world units the grid vertices move per unit of height
  float depth = 0.35f;              ///< pool depth below the surface (world units)
  float fresnelF0 = 0.02f;          ///< reflectance of water head-on ((1.33 − 1)² / (1.33 + 1)²)
  vec3 absorption{0.9f, 0.35f, 0.25f}; ///< per world unit of path; red fades first (water is blue-green)
  vec3 sunDirection{0.35f, 0.55f, -0.75f};  ///< towards the sun (normalized by the shader)
  vec3 sunColor{1.0f, 0.95f, 0.85f};
  float sunShininess = 900.0f;      ///< Phong exponent of the sun's glints on the reflection vector
};

class WaterSurface {
public:
  /// A grid of `cells` × `cells` quads (vertex displacement resolution).
  explicit WaterSurface(int cells = 128);
  /// Draws the pool. `waveState`: the RG32F simulation state (R = height) for displacement;
  /// `normalMap`: its normal map (RGBA8, (n + 1)/2); `environment`: a world-space cube map;
  /// `poolFloor`: a 2D colour texture tiled on the floor. Sets the state it uses (depth test,
  /// no blending, seamless cube maps); units 0–3.
  void draw(const Camera& camera, const gl::Texture& waveState, const gl::Texture& normalMap,
            const gl::Texture& environment, const gl::Texture& poolFloor, const WaterSurfaceOptions& options = {}) const;

private:
  GpuMesh m_grid;
  gl::Program m_program;
};

/// The cube map the water reflects, and a line saying where it came from.
struct SkyEnvironment {
  gl::Texture cube;
  std::string source;  ///< "courtyard.exr (data/env)" or "procedural sky (glint data not installed)"
};
/// Reuses the env module (render/env/environment.h): data/env/<name>.exr converted to a cube
/// map of `faceSize` texels. When the file is missing, renders a procedural sky (gradient, sun,
/// dark ground) into the six faces instead and logs a warning.
SkyEnvironment skyEnvironment(const char* name = "courtyard", int faceSize = 256);

}  // namespace glint::render::water
