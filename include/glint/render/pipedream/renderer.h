#pragma once
// glint/render/pipedream/renderer.h — the `pipedream` scene's frame: seed 001's "Pipe
// Dream" shadows, static and dynamic, combined through destination alpha.
//
// Contents
//   StaticGeometry    the cut static scene, grouped by light mask (made from glint::cut's
//                     output by scenes/pipedream.h), and the uncut one for the naive method
//   Mode              what a frame shows (the scene's variants)
//   RendererOptions   shutter, opacity floor, LOD scale, ambient, culling
//   FrameStats        what the last frame drew: triangles, volumes, culled casters
//   Renderer          the passes, as one frame or step by step (tests, benchmarks)
//
// The frame (Mode::Full), in the order of the seed's talk:
//   1. Scene pass, into an sRGB colour buffer plus a second buffer of per-light weights.
//      Static pieces come from the cut: each group of one light mask is drawn with that
//      mask as a uniform, lit by exactly the lights that reach it; pieces no light reaches
//      go through a cheaper shader (ambient only) — "we know none of our dominant lights hit
//      those polygons". Dynamic parts (skins, cymbals, mallets) are lit by every light in
//      range. Each pixel writes its colour and, in destination alpha, its *dim factor*: the
//      share of its light that remains when the first light is blocked, 1 − w₀ with
//      wₖ = (light k's diffuse here) / (all light here). Where no light reaches (a baked
//      shadow of every light), w = 0 and the factor is 1: a dynamic shadow cannot darken it
//      again. The second buffer keeps every wₖ.
//   2. Translucent (motion-blurred) balls, blended over the scene with alpha writes masked
//      off, so destination alpha still holds the surface's factor.
//   3. For each light with dynamic casters in its range: their GPU-extruded volumes
//      (degenerate quads, shaders/shadows/extrude.vert; z-fail, two-sided, infinite far
//      plane) counted into the stencil. Casters whose bounding sphere is out of the light's
//      range are culled: their shadow would fall where the light's attenuation is already
//      zero, so nothing pops. Then (lights after the first) destination alpha is rewritten
//      to that light's factor, and one full-screen quad is drawn under the stencil test with
//      glBlendFunc(GL_ZERO, GL_DST_ALPHA): colour × factor, in linear light (the sRGB
//      framebuffer blends linearly). The quad leaves a marker bit in the stencil, so where
//      several lights' shadows overlap each later factor knows which lights are already
//      gone — the result is exactly ambient + the lights that still reach the pixel.
//   4. Present: the colour buffer into the frame's target.
// Mode::Naive is the 2 fps baseline: the uncut scene in ambient, then per light every
// caster's volume (static ones included) and an additive pass where the stencil is zero.
//
//   render::pipedream::Renderer renderer(machine, geometry, {});
//   renderer.render(pose, camera, frame.target, render::pipedream::Mode::Full);

#include "glint/gl/objects.h"
#include "glint/gl/render_target.h"
#include "glint/gl/shader.h"
#include "glint/mesh/machine_room.h"
#include "glint/render/camera.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/pipedream/motion_blur.h"
#include "glint/render/pipedream/score.h"
#include "glint/render/env/dynamic_cube.h"

#include <cstdint>
#include <string>
#include <vector>

namespace glint::render::pipedream {

/// Lights a renderer handles (one weight channel each in an RGBA buffer).
constexpr int kMaxLights = 4;

/// The cut static scene as a renderer draws it (no GL). Vertices are one per (cut vertex,
/// input triangle): normals interpolated from the input triangle's vertex normals at the
/// cut vertex, so a piece shades exactly as the part of the triangle it covers.
struct StaticGeometry {
  Mesh mesh;                             ///< positions, normals, indices; triangles ordered by light mask
  std::vector<vec4> colors;              ///< albedo per vertex
  std::vector<std::uint32_t> maskStart;  ///< triangles of mask m: [maskStart[m], maskStart[m + 1]); 2^lights + 1 entries
  Mesh edges;                            ///< the cut polygons' sides: index pairs into mesh.positions (padded to whole triangles)
  std::size_t polygons = 0;              ///< cut polygons (before triangulation)
  int lights = 0;
};

enum class Mode {
  Full,        ///< the seed's method: cut static shadows, dynamic volumes, the dim-factor quad, blurred balls
  Wireframe,   ///< Full with the cut polygons' sides drawn over it
  DestAlpha,   ///< the dim factor as grey: what a pixel keeps when every light is blocked (seed: "dest alpha view")
  Volumes,     ///< Full with the dynamic volumes drawn as blue wireframe (culled per light)
  StaticOnly,  ///< the cut static shadows alone: no volumes, no quad
  NoBlur,      ///< Full with the balls still, opaque and sharp
  Naive        ///< every caster's volumes (static too) per light, multi-pass: the 2 fps baseline
};

struct RendererOptions {
  float shutter = 1.0f / 30.0f;  ///< seconds the shutter is open: the streak length per speed
  float minOpacity = 0.25f;      ///< a fast ball's opacity does not drop below this
  float lodScale = 1.5f;         ///< mip levels of blur per doubling of a ball's length
  float ambient = 0.16f;         ///< the ambient term (what a pixel no light reaches keeps)
  bool cullVolumes = true;       ///< skip casters out of a light's range (exact; see above)
  int cubeSize = 128;            ///< the room's environment map (the balls' reflections)
};

/// What the last frame drew.
struct FrameStats {
  std::size_t sceneTriangles = 0;   ///< static + dynamic triangles of the scene pass(es), once per pass
  std::size_t volumeTriangles = 0;  ///< shadow-volume triangles drawn, all lights
  std::size_t casters = 0;          ///< dynamic casters
  std::size_t castersDrawn = 0;     ///< (caster, light) pairs whose volume was drawn
  std::size_t castersCulled = 0;    ///< (caster, light) pairs culled by the light's range
  std::size_t balls = 0, translucentBalls = 0;
  int lightsWithShadows = 0;        ///< lights that got a stencil pass and a quad
};

class Renderer {
public:
  /// Uploads the geometry, builds the extrusion meshes and renders the room's cube map
  /// (from the middle of the stage) for the balls. Needs a current 4.5 context.
  Renderer(const InstrumentMachine& machine, const StaticGeometry& geometry, const RendererOptions& options = {});

  /// A whole frame of `mode` into `target`. `camera`'s projection is given an infinite far
  /// plane here (z-fail's far caps); its near plane is kept.
  void render(const MachinePose& pose, const Camera& camera, const gl::Target& target, Mode mode);

  // ---- The steps of render() for Full and its debug modes (tests, benchmarks). They draw
  // into the renderer's own framebuffer (size from prepare()); present() copies it out.
  /// Sizes the framebuffers and the camera (infinite far plane); call first.
  void prepare(const MachinePose& pose, const Camera& camera, ivec2 size, Mode mode);
  /// Step 1: clears, draws the static groups and the dynamic parts (and opaque balls).
  void drawScene();
  /// Step 2: the translucent balls.
  void drawTranslucent();
  /// Step 3 for light `light`: counts its casters' volumes into the stencil (the field below
  /// the markers of earlier lights). Returns false (and draws nothing) when no caster is in range.
  bool countVolumes(int light);
  /// Step 3, after countVolumes(light): destination alpha := that light's factor (lights > 0),
  /// then the quad. `earlier`: bit j set for earlier lights whose quad ran.
  void compositeLight(int light, std::uint32_t earlier);
  /// Step 4: the colour buffer (or, for DestAlpha, the dim factor) into `target`.
  void present(const gl::Target& target) const;
  /// Fragments all dynamic volumes rasterize in the lights' stencil passes (both faces, caps),
  /// with GL_SAMPLES_PASSED, depth test off (what counting costs in fill). Naive: every caster.
  std::uint64_t measureVolumeFill();

  /// The scene pass's framebuffer: colour (sRGB) + weights + depth/stencil.
  const gl::Framebuffer& sceneFramebuffer() const { return m_sceneFbo; }
  /// Colour + depth/stencil only (translucent balls, alpha passes, quads).
  const gl::Framebuffer& compositeFramebuffer() const { return m_compositeFbo; }
  ivec2 size() const { return m_size; }
  const FrameStats& stats() const { return m_stats; }
  const RendererOptions& options() const { return m_options; }
  RendererOptions& options() { return m_options; }
  /// One line on what the renderer holds.
  std::string describe() const;

private:
  struct Caster {
    gl::VertexArray vao;
    gl::Buffer vertices, indices;
    GLsizei indexCount = 0;
    float radius = 0.0f;  // bounding sphere in the mesh's frame, around the origin
    vec3 centre{0.0f};
  };
  struct DynamicDraw {  // one dynamic part this frame
    int mesh = 0;       // 0 skin, 1 cymbal, 2 mallet
    mat4 model{1.0f};
    vec3 albedo{1.0f};
  };
  struct BallDraw {
    BallState state;
    BallBlur blur;
    float depth = 0.0f;
  };
  Caster makeCaster(const Mesh& mesh, bool twoSided, const std::string& name);
  void resize(ivec2 size);
  void drawStatic(const gl::Program& lit, bool uncut) const;
  void drawDynamic(const gl::Program& program) const;
  void drawBall(const BallDraw& ball, bool translucent) const;
  void setLights(const gl::Program& program) const;
  void drawCaster(const Caster& caster, const mat4& model, vec3 light) const;
  bool inRange(const Caster& caster, const mat4& model, int light) const;
  void drawVolumesOf(int light, bool everything);
  void renderNaive();
  void drawVolumeWireframe();
  void drawEdges();
  void renderCube();

  const InstrumentMachine& m_machine;
  RendererOptions m_options;
  int m_lights = 0;
  // Static geometry: the cut (groups by mask) and the uncut scene (naive).
  GpuMesh m_static, m_uncut, m_edges;
  std::vector<std::uint32_t> m_maskStart;
  std::size_t m_uncutTriangles = 0;
  // Dynamic parts: meshes to draw and their extrusion meshes.
  GpuMesh m_parts[3];
  Caster m_partCasters[3];
  Caster m_ballCaster;
  Caster m_staticSolids, m_staticShell;  // naive only
  gl::VertexArray m_ballVao;
  gl::Buffer m_ballVertices, m_ballIndices;
  GLsizei m_ballIndexCount = 0;
  std::size_t m_ballTriangles = 0;
  GpuMesh m_marker;
  // Programs.
  gl::Program m_lit, m_shadowed, m_extrude, m_ball, m_flat3d;
  FullscreenPass m_alphaPass, m_quad, m_present;
  // Framebuffers at the frame's size.
  ivec2 m_size{0};
  gl::Texture m_color, m_weights, m_depthStencil;
  gl::Framebuffer m_sceneFbo, m_compositeFbo;
  env::DynamicCubeMap m_cube;
  // This frame.
  Camera m_camera;
  Mode m_mode = Mode::Full;
  std::vector<DynamicDraw> m_dynamic;
  std::vector<BallDraw> m_balls;
  FrameStats m_stats;
};

}  // namespace glint::render::pipedream
