#pragma once
// glint/render/shadows/stencil_shadows.h — stencil shadow volumes, every variant.
//
// Contents
//   StencilCounting     how volume faces change the stencil (the WWDC 2001 talk's INVERT, z-pass, z-fail, one-pass)
//   VolumeConstruction  CPU silhouettes or GPU extrusion (WWDC 2003 session 212)
//   ShadowComposite     how the stencil becomes a shadow (the WWDC 2001 talk's three ways, WWDC 2003 session 212's dim alpha)
//   VolumeView          debug views: the WWDC 2001 talk's green back / blue front faces, wireframe
//   StencilShadowOptions, StencilShadows   the technique
//
// A frame (render()):
//   1. the scene into colour and depth (ambient only for the multi-pass composite);
//   2. the volumes into the stencil, colour and depth writes off, pushed back by a
//      polygon offset so a caster's own lit faces (the volume's near cap) never pass
//      the depth test against themselves (that z-fight would speckle shadows on them);
//   3. the composite.
// The stencil buffer is non-zero where a pixel is in shadow. Counting needs 8 bits
// and *_WRAP ops (a count may go below zero before coming back); every target glint
// draws into has GL_DEPTH24_STENCIL8 (gl::RenderTarget), and so does the window.
//
// Cameras: z-fail needs the far caps, at infinity, inside the depth range. Either give
// the camera an infinite-far projection (infiniteFarProjection() in world_renderer.h,
// needsInfiniteFar() says when) or set depthClamp, which disables far clipping and
// clamps depth to 1 instead.
//
// Common mistakes
//   - Z-pass is wrong when the camera is inside a volume (the count starts non-zero):
//     the shadows invert wherever that volume is seen. Z-fail counts behind the
//     surface instead and does not care (shadows/inside-volume shows both).
//   - INVERT counts parity: two overlapping volumes cancel (shadows/zpass-invert/overlap).
//     It also cancels TwoSided casters (their silhouettes are doubled), so INVERT
//     always uses CasterMode::Closed.

#include "glint/gl/objects.h"
#include "glint/gl/render_target.h"
#include "glint/render/gpu_mesh.h"
#include "glint/shadows/volume.h"
#include "glint/render/shadows/world_renderer.h"

#include <cstdint>
#include <string>
#include <vector>

namespace glint::render::shadows {

enum class StencilCounting {
  InvertZPass,    ///< the WWDC 2001 talk: back faces, then front faces, GL_INVERT where depth passes (parity)
  ZPass,          ///< front faces INCR_WRAP, back faces DECR_WRAP where depth passes; two draws
  ZFail,          ///< Carmack's reverse: back INCR_WRAP, front DECR_WRAP where depth fails; caps
  TwoSidedZPass,  ///< z-pass in one draw, culling off: glStencilOpSeparate per face
  TwoSidedZFail   ///< z-fail in one draw
};

enum class VolumeConstruction {
  Cpu,  ///< silhouettes from the edge map every frame (buildShadowVolume), streamed to the GPU
  Gpu   ///< a static mesh with degenerate quads, extruded in the vertex shader (buildExtrusionMesh)
};

enum class ShadowComposite {
  MultiPass,    ///< (iii) the correct one: ambient everywhere, diffuse + specular only where stencil = 0
  ShadowQuad,   ///< (i) a full-screen quad of the shadow colour, alpha-blended where stencil ≠ 0
  VolumeAlpha,  ///< (ii) the volume drawn again into colour, black at volumeOpacity, where stencil ≠ 0
  DimAlpha,     ///< WWDC 2003 session 212: a quad blended (ZERO, DST_ALPHA) where stencil ≠ 0; alpha holds the dim factor
  CountColors,  ///< the stencil count itself: 1 yellow, 2 orange, 3 red, ≥ 4 magenta, "negative" violet
  None          ///< the lit scene only (debug views draw their volumes over it)
};

enum class VolumeView {
  None,       ///< no debug drawing
  BackFaces,  ///< the WWDC 2001 talk's debug view: back faces green (additive, depth-tested)
  FrontFaces, ///< front faces blue
  BothFaces,  ///< both: cyan where both pass, blue where only the front passes — the shadow
  Wireframe   ///< volume edges as lines over the scene
};

struct StencilShadowOptions {
  StencilCounting counting = StencilCounting::ZFail;
  VolumeConstruction construction = VolumeConstruction::Cpu;
  glint::shadows::CasterMode casters = glint::shadows::CasterMode::Auto;
  ShadowComposite composite = ShadowComposite::MultiPass;
  VolumeView view = VolumeView::None;
  bool depthClamp = false;      ///< z-fail: GL_DEPTH_CLAMP instead of an infinite-far camera
  float quadAlpha = 0.55f;      ///< ShadowQuad: opacity of the black overlay
  float volumeOpacity = 0.85f;  ///< VolumeAlpha: opacity of the black volume; a shadow keeps 1 − this of
                                ///< the lit colour (the WWDC 2001 talk: "an 85% opaque alpha blend", or 50%)
  /// Polygon offset of the volume passes (pushes volumes away from the camera): slope
  /// factor for near caps seen at grazing angles, units for the rest.
  float offsetFactor = 1.0f;
  float offsetUnits = 4.0f;
};

/// Sizes and costs of the last update, for notes and benchmarks.
struct VolumeStats {
  std::size_t casters = 0;
  std::size_t silhouetteEdges = 0;  ///< CPU only
  std::size_t volumeTriangles = 0;  ///< triangles drawn per stencil pass (caps included when used)
  std::size_t bytes = 0;            ///< volume geometry on the GPU
  double buildMs = 0.0;             ///< CPU time of silhouette extraction + upload (0 for GPU)
};

class StencilShadows {
public:
  /// Builds edge maps (and for Gpu, extrusion meshes) of every caster in `world`.
  StencilShadows(const glint::shadows::World& world, const StencilShadowOptions& options);

  /// Whether the camera needs an infinite-far projection (z-fail without depth clamp).
  static bool needsInfiniteFar(const StencilShadowOptions& options);

  /// A whole frame into `target` (cleared first): scene, volumes, composite, debug view.
  void render(const glint::shadows::World& world, const Camera& camera, const gl::Target& target);

  // The steps of render(), for tests and custom frames. Each sets all state it uses.
  /// Rebuilds CPU volumes where the light moved relative to a caster (cheap otherwise).
  void update(const glint::shadows::World& world);
  /// Clears colour, depth (1) and stencil (0) of the bound target, draws the scene.
  void drawScene(const glint::shadows::World& world, const Camera& camera, LightTerms terms) const;
  /// Counts the volumes into the stencil buffer; the depth buffer must hold the scene.
  void countVolumes(const glint::shadows::World& world, const Camera& camera) const;
  /// Turns the stencil into shadows with the options' composite.
  void composite(const glint::shadows::World& world, const Camera& camera) const;
  /// Draws the options' debug view over the bound target.
  void drawView(const glint::shadows::World& world, const Camera& camera) const;
  /// Stencil fill: fragments the volumes rasterize in one stencil pass (both faces, caps
  /// when the counting uses them), counted with a GL_SAMPLES_PASSED query while drawing
  /// them with the depth test off and every write masked. Leaves the target untouched.
  std::uint64_t measureFill(const glint::shadows::World& world, const Camera& camera) const;
  /// Forgets the CPU volumes so the next update() rebuilds them all (a moving light).
  void invalidate() {
    for (Caster& c : m_casters) c.built = false;
  }

  const VolumeStats& stats() const { return m_stats; }
  const StencilShadowOptions& options() const { return m_options; }
  /// Options read every frame (opacities, offsets, view, composite); counting, construction
  /// and casters are fixed at construction.
  StencilShadowOptions& options() { return m_options; }
  /// One line: counting, construction, casters, sizes, build time.
  std::string describe() const;

private:
  // One shadow-casting object: its edge map and its volume geometry on the GPU.
  struct Caster {
    std::size_t object = 0;  // index in World::objects
    EdgeMap edges;
    glint::shadows::CasterMode mode = glint::shadows::CasterMode::Closed;
    // CPU: the volume of the last update, in object space.
    gl::Buffer buffer;
    gl::VertexArray vao;
    std::size_t sideVertices = 0, capVertices = 0, silhouetteEdges = 0;
    vec3 builtForLight{0.0f};
    bool built = false;
    // GPU: the extrusion mesh, drawn indexed.
    gl::Buffer indices;
    GLsizei indexCount = 0;
  };
  void drawVolumes(const glint::shadows::World& world, const Camera& camera, bool caps) const;
  bool usesCaps() const;

  StencilShadowOptions m_options;
  WorldRenderer m_scene;
  std::vector<Caster> m_casters;
  gl::Program m_volumeProgram;   // CPU volumes
  gl::Program m_extrudeProgram;  // GPU extrusion
  FullscreenPass m_flat;
  VolumeStats m_stats;
};

}  // namespace glint::render::shadows
