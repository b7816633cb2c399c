#pragma once
// glint/render/pipedream/renderer.h — the `pipedream` scene's frame: WWDC 2003 session 212's "Pipe
// Dream" shadows, static and dynamic, combined through destination alpha.
//
// Contents
//   StaticGeometry    the cut static scene, grouped by light mask (made from glint::cut's
//                     output by scenes/pipedream.h)
//   Mode              what a frame shows (the scene's variants)
//   RendererOptions   shutter, opacity floor, LOD scale, ambient, culling
//   FrameStats        what the last frame drew: triangles, volumes, culled casters
//   StencilLayout     how one 8-bit stencil holds a volume count and the lights already done
//   Renderer          the passes, as one frame or step by step (tests, benchmarks)
//
// The frame (Mode::Full), in the order of WWDC 2003 session 212's talk:
//   1. Scene pass, into an 8-bit sRGB colour buffer (blended and dimmed in linear light)
//      plus a second buffer of per-light weights, one 8-bit channel per light: 6 bytes a
//      pixel for the two lights where RGBA16F and four half-float weights took 16
//      (issue 37: a datacenter GPU's few ROPs make the frame fill-bound). Static pieces come from the cut: each group of one light mask is drawn with
//      that mask as a uniform, lit by exactly the lights that reach it; pieces no light
//      reaches go through a cheaper shader (ambient only) — "we know none of our dominant
//      lights hit those polygons". Static triangles are drawn front faces only, in clusters
//      (RendererOptions::clusterSize): those outside the view are left out, the rest go
//      nearest first in one glMultiDrawElements per mask. Dynamic parts (skins, cymbals, mallets) are lit by every
//      light. Each pixel writes its colour and, in destination alpha, its *dim factor* for
//      the first light: the share of its light that remains when that light is blocked,
//      1 − w₀ with wₖ = (light k's diffuse here) / (ambient + all light here). Where no light
//      reaches (a baked shadow of every light) every w is 0 and the factor is 1: a dynamic
//      shadow cannot darken it again. The second buffer keeps every wₖ.
//   2. Translucent (motion-blurred) balls, blended over the scene with alpha writes masked
//      off, so destination alpha still holds the surface's factor.
//   3. For each light with dynamic casters in its range: their GPU-extruded volumes
//      (degenerate quads, shaders/shadows/extrude.vert; z-fail in one two-sided draw,
//      infinite far plane) counted into the stencil. Casters whose bounding sphere lies
//      beyond the light's range are culled: everything such a caster could shadow is
//      further still, where the light's attenuation is already zero, so nothing pops; and
//      as a caster nears the end of the range its shadow fades with the light it blocks.
//      Each volume is *bounded* (RendererOptions::boundVolumes): its turned-away faces
//      go not to infinity but to a distance T from the light, chosen on the CPU per caster
//      and light so that the part it leaves off lies wholly outside the box that holds the
//      eye and every surface the depth buffer can hold (the room's box, grown to the eye
//      when it stands outside): every segment from the eye to a visible point lies in that
//      box, and so does every visible point's count. A caster
//      inside the sphere (c, r) seen from the light fills a cone of half-angle α with
//      sin α = r / |c − L|; every point of the volume's far end then lies at least
//      T cos α along the cone's axis, so T cos α beyond the box's furthest corner along
//      that axis puts the whole difference in a half-space the box does not meet, and
//      every z-fail count (the volumes crossed behind a visible point) is the same. What
//      is saved is fill: the sides below the floor and behind the walls, which each pixel
//      counted up and down again. When a light is inside a caster's sphere, that volume
//      goes to infinity as before. (Where the frame shows no surface at all, a bounded
//      volume counts nothing, as it should.)
//      Then (lights after the first) destination alpha is rewritten to that light's factor,
//      and one full-screen quad is drawn under the stencil test with
//      glBlendFunc(GL_ZERO, GL_DST_ALPHA): colour × factor, in linear light. The quad
//      leaves a marker bit in the stencil (StencilLayout), so where several lights' shadows
//      overlap each later factor knows which lights are already gone — the result is
//      exactly ambient + the lights that still reach the pixel.
//   4. Present: the colour buffer into the frame's target, encoded to sRGB.
// Mode::Naive is the 2 fps baseline: the uncut scene in ambient, then per light every
// caster's volume (the whole static scene included) and an additive pass where the
// stencil is zero.
//
/// ```cpp
/// #include <glint/scenes/pipedream.h>
/// namespace pipedream = glint::render::pipedream;
/// const auto stage = glint::scenes::pipedream::loadStage();  // machine, score and the cut geometry
/// pipedream::Renderer renderer(stage->machine, stage->geometry);  // with a current 4.5 context
/// const glint::gl::RenderTarget frame({1280, 720});
/// const glint::pipedream::MachinePose pose = glint::pipedream::poseAt(stage->machine, stage->score, 3.0);
/// const glint::Camera camera = glint::scenes::pipedream::namedCamera(0, frame.target().aspect());
/// renderer.render(pose, camera, frame.target(), pipedream::Mode::Full);
/// ```

#include "glint/gl/objects.h"
#include "glint/gl/render_target.h"
#include "glint/gl/shader.h"
#include "glint/pipedream/machine_room.h"
#include "glint/core/camera.h"
#include "glint/render/env/dynamic_cube.h"
#include "glint/render/gpu_mesh.h"
#include "glint/pipedream/motion_blur.h"
#include "glint/pipedream/score.h"

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace glint::render::pipedream {

/// Lights a renderer handles (one weight channel each in an RGBA buffer).
constexpr int kMaxLights = 4;

/// The cut static scene as a renderer draws it (no GL). Each corner's normal is
/// interpolated from its source triangle's vertex normals at the cut vertex, so a piece
/// shades exactly as the part of the triangle it covers; corners at one cut vertex with one
/// material and (to rounding) one normal share a vertex, as the input's do.
struct StaticGeometry {
  Mesh mesh;                             ///< positions, normals, indices; triangles ordered by light mask
  std::vector<vec4> colors;              ///< albedo per vertex
  std::vector<std::uint32_t> maskStart;  ///< triangles of mask m: [maskStart[m], maskStart[m + 1]); 2^lights + 1 entries
  Mesh edges;                            ///< the cut polygons' sides as index pairs (GL_LINES; may be empty)
  std::size_t polygons = 0;              ///< cut polygons (before triangulation)
  int lights = 0;
};

enum class Mode {
  Full,        ///< WWDC 2003 session 212's method: cut static shadows, dynamic volumes, the dim-factor quad, blurred balls
  Wireframe,   ///< Full with the cut polygons' sides drawn over it
  DestAlpha,   ///< the dim factor as grey: what a pixel keeps when every light is blocked (the talk: "dest alpha view")
  Volumes,     ///< Full with the dynamic volumes drawn as blue wireframe (culled per light)
  StaticOnly,  ///< the cut static shadows alone: no volumes, no quad
  NoBlur,      ///< Full with the balls still, opaque and sharp
  Naive        ///< every caster's volumes (static too) per light, multi-pass: the 2 fps baseline
};

struct RendererOptions {
  float shutter = 1.0f / 30.0f;  ///< seconds the shutter is open: the streak length per speed
  float minOpacity = 0.25f;      ///< a fast ball's opacity does not drop below this
  float lodScale = 1.5f;         ///< mip levels of blur per doubling of a ball's length
  float ambient = 0.1f;          ///< the ambient term (what a pixel no light reaches keeps)
  bool cullVolumes = true;       ///< skip casters beyond a light's range (exact; see above)
  bool boundVolumes = true;      ///< end each volume just past the room's box, not at infinity (exact; see above)
  float clusterSize = 2.0f;      ///< static triangles are drawn in clusters of this cell size (m): culled
                                 ///< outside the view, nearest first (0: one cluster per mask)
  int cubeSize = 128;            ///< the room's environment map (the balls' reflections)
  bool floatBuffers = false;     ///< RGBA16F colour and four half-float weights (16 bytes a pixel, the
                                 ///< layout before issue 37) instead of 8-bit sRGB colour and a byte
                                 ///< a light (6 bytes for two lights): `glint bench pipedream`'s peer
};

/// One pass of a frame and what it writes into the framebuffer (Renderer::measureStaticFill).
struct PassFill {
  std::string pass;                ///< "clear", "scene", "balls", "present"
  std::uint64_t fragments = 0;     ///< fragments written (GL_SAMPLES_PASSED; clear, present: every pixel)
  int bytesPerFragment = 0;        ///< bytes of the attachments each writes: colour, weights, depth/stencil
  std::uint64_t bytes() const { return fragments * std::uint64_t(bytesPerFragment); }
};

/// What the last frame drew.
struct FrameStats {
  std::size_t sceneTriangles = 0;   ///< triangles of the scene pass(es): static + dynamic + balls, per pass
  std::size_t staticCulled = 0;     ///< static triangles left out (their cluster is outside the view), all passes
  std::size_t volumeTriangles = 0;  ///< shadow-volume triangles drawn, all lights
  std::size_t casters = 0;          ///< dynamic casters this frame (parts and balls)
  std::size_t castersDrawn = 0;     ///< (caster, light) pairs whose volume was drawn
  std::size_t castersCulled = 0;    ///< (caster, light) pairs culled by the light's range
  std::size_t castersBounded = 0;   ///< (caster, light) pairs whose volume was bounded (not to infinity)
  std::size_t balls = 0;            ///< balls in flight
  int lightsWithShadows = 0;        ///< lights that got a stencil pass and a quad
};

/// One 8-bit stencil for every light in turn: the low bits count the current light's
/// volumes (wrapping, modulo 2^countBits); the top `lights − 1` bits are markers, bit
/// 7 − k set where light k's dynamic shadow has already been applied. The last light needs
/// no marker.
struct StencilLayout {
  int lights = 1;
  GLuint countMask() const { return 0xFFu >> (lights - 1); }
  GLuint marker(int light) const { return light < lights - 1 ? 0x80u >> light : 0u; }
  /// Markers of lights [0, light).
  GLuint markersBefore(int light) const {
    GLuint m = 0;
    for (int k = 0; k < light; ++k) m |= marker(k);
    return m;
  }
};

class Renderer {
public:
  /// Uploads the geometry, builds the extrusion meshes and renders the room's cube map
  /// (from the middle of the stage) for the balls. Needs a current 4.5 context. The
  /// machine must outlive the renderer. Error(Usage) for more than kMaxLights lights.
  Renderer(const InstrumentMachine& machine, const StaticGeometry& geometry, const RendererOptions& options = {});

  /// A whole frame of `mode` into `target`. `camera`'s projection (from glm::perspective)
  /// is given an infinite far plane here (z-fail's far caps); its near plane is kept.
  void render(const glint::pipedream::MachinePose& pose, const Camera& camera, const gl::Target& target, Mode mode);

  // ---- The steps of render() for Full and its debug modes (tests, benchmarks). They draw
  // into the renderer's own framebuffer (size from prepare()); present() copies it out.
  /// Sizes the framebuffers, takes the pose and the camera (infinite far plane); call first.
  void prepare(const glint::pipedream::MachinePose& pose, const Camera& camera, ivec2 size, Mode mode);
  /// Step 1: clears, draws the static groups and the dynamic parts (and opaque balls).
  void drawScene();
  /// Step 2: the translucent balls (nothing in NoBlur, where the scene pass drew them).
  void drawTranslucent();
  /// Step 3 for light `light`: counts its casters' volumes into the stencil's count bits.
  /// Returns false (and draws nothing) when no caster is in range.
  bool countVolumes(int light);
  /// Step 3, after countVolumes(light): destination alpha := that light's factor (lights
  /// > 0), then the quad. `earlier`: bit j set for earlier lights whose quad ran.
  void compositeLight(int light, std::uint32_t earlier);
  /// Step 4: the colour buffer (or, for DestAlpha, the dim factor) into `target`.
  void present(const gl::Target& target) const;
  /// Fragments all shadow volumes of a frame rasterize (both faces, caps, every light's
  /// in-range casters; for Naive every caster, static ones included), counted with
  /// GL_SAMPLES_PASSED while drawing them with the depth test off: what counting costs in
  /// fill. Needs prepare().
  std::uint64_t measureVolumeFill();
  /// The static frame's passes (Mode::StaticOnly: clear, scene, translucent balls, present
  /// into `target`) drawn again with a GL_SAMPLES_PASSED query each: the framebuffer bytes
  /// each writes. Needs prepare().
  std::vector<PassFill> measureStaticFill(const gl::Target& target);

  /// The scene pass's framebuffer: colour (SRGB8_ALPHA8) + weights (R8, RG8 or RGBA8: a
  /// channel per light) + depth/stencil (DEPTH24_STENCIL8).
  const gl::Framebuffer& sceneFramebuffer() const { return m_sceneFbo; }
  /// Colour + depth/stencil only (translucent balls, alpha passes, quads).
  const gl::Framebuffer& compositeFramebuffer() const { return m_compositeFbo; }
  /// The colour attachment (sRGB-encoded RGB: texel fetches decode it to linear; alpha the
  /// dim factor, linear) and the weights (channels past the lights read 0).
  const gl::Texture& colorTexture() const { return m_color; }
  const gl::Texture& weightsTexture() const { return m_weights; }
  const Camera& camera() const { return m_camera; }
  ivec2 size() const { return m_size; }
  int lights() const { return m_lights; }
  /// The colour buffer holds linear light × colorScale(): 1 / the brightest a pixel can be
  /// this frame (the brightest albedo × (ambient + every light's intensity), or the light
  /// markers' emission), so its 8 bits clip nothing; present() divides it out.
  float colorScale() const { return m_colorScale; }
  /// A linear colour as the colour buffer holds it (rgb × colorScale(), alpha kept).
  vec4 scaled(const vec4& linear) const { return {vec3(linear) * m_colorScale, linear.a}; }
  StencilLayout stencilLayout() const { return {m_lights}; }
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
    vec3 centre{0.0f};    // bounding sphere in the mesh's frame
    float radius = 0.0f;
    bool twoSided = false;
  };
  struct DynamicDraw {  // one dynamic part this frame
    int mesh = 0;       // 0 skin, 1 cymbal, 2 mallet
    mat4 model{1.0f};
    vec3 albedo{1.0f};
  };
  /// A run of the static index buffer: the triangles of one light mask (0 for the uncut
  /// scene) whose centroids fall in one cell of space, and their bounds.
  struct Cluster {
    std::uint32_t mask = 0, first = 0, count = 0;
    Bounds bounds;
  };
  /// Reorders each group [groupStart[g], groupStart[g + 1]) of `mesh`'s triangles by cell
  /// (stable) and its vertices by first use; returns the clusters, by group then cell.
  static std::vector<Cluster> clusterTriangles(Mesh& mesh, std::vector<vec4>& colors,
                                               std::span<const std::uint32_t> groupStart, float cell);
  struct BallDraw {
    glint::pipedream::BallState state;
    glint::pipedream::BallBlur blur;
    float depth = 0.0f;  // view distance, for back-to-front order
  };
  Caster makeCaster(const Mesh& mesh, const std::string& name);
  void resize(ivec2 size);
  void setLights(const gl::Program& program) const;
  void drawStaticGroups();
  /// The clusters of `mask` inside the view, nearest first, in one glMultiDrawElements
  /// (the VAO and program set); returns the triangles drawn.
  std::size_t drawClusters(const std::vector<Cluster>& clusters, std::uint32_t mask);
  void drawDynamic(const gl::Program& program) const;
  void drawMarkers() const;
  void drawBalls(bool translucent);
  void drawCaster(const Caster& caster, const mat4& model, float extrudeTo) const;
  /// How far from `light` a volume of the world-space sphere (centre, radius) must reach
  /// so that cutting it off there changes no count in the view: 0 (infinity) when the
  /// volume cannot be bounded (see "bounded" above).
  float extrusionDistance(const vec3& centre, float radius, const vec3& light) const;
  bool inRange(const Caster& caster, const mat4& model, int light) const;
  /// Every volume of `light` with the current state: in-range dynamic casters, and with
  /// `everything` the static scene too (Naive). Counts into m_stats.
  bool drawVolumesOf(int light, bool everything);
  /// Grows m_volumeBounds by the screen area a caster's shadow volume can cover: its
  /// bounding sphere's box and that box pushed away from the light, to infinity or (a
  /// bounded volume) as far as `extrudeTo` from the light can reach.
  void extendVolumeBounds(const vec3& centre, float radius, const vec3& light, float extrudeTo);
  void ensureNaiveCasters();
  void renderNaive();
  void drawVolumeWireframe();
  void drawEdges();
  void renderCube();

  const InstrumentMachine& m_machine;
  RendererOptions m_options;
  int m_lights = 0;
  float m_maxAlbedo = 1.0f;   // the brightest albedo channel of any surface
  float m_colorScale = 1.0f;  // this frame's (colorScale())
  // Static geometry: the cut (groups by mask) and the uncut scene (naive, reflections).
  GpuMesh m_static, m_uncut, m_edges;
  std::vector<std::uint32_t> m_maskStart;
  std::vector<Cluster> m_staticClusters, m_uncutClusters;
  std::vector<GLsizei> m_drawCounts;         // drawClusters' scratch
  std::vector<const void*> m_drawOffsets;
  std::vector<std::pair<float, std::size_t>> m_drawOrder;
  std::size_t m_staticTriangles = 0, m_uncutTriangles = 0, m_edgeCount = 0;
  std::size_t m_staticVertices = 0, m_uncutVertices = 0;
  // Dynamic parts: meshes to draw and their extrusion meshes.
  GpuMesh m_parts[3];
  Caster m_partCasters[3];  // their shadows' casters (the mallet's a proxy inside it)
  bool m_partClosed[3] = {};
  vec3 m_partCentre[3] = {};  // the parts' bounding spheres (what they put in the depth buffer)
  float m_partRadius[3] = {};
  Bounds m_staticBox;         // the static scene's box (the room)
  Caster m_ballCaster;
  Caster m_staticSolids, m_staticShell;  // naive only
  gl::VertexArray m_ballVao;
  gl::Buffer m_ballVertices, m_ballIndices;
  GLsizei m_ballIndexCount = 0;
  GpuMesh m_marker;
  // Programs.
  gl::Program m_lit, m_shadowed, m_extrude, m_ball;
  FullscreenPass m_alphaPass, m_quad, m_present;
  // Framebuffers at the frame's size.
  ivec2 m_size{0};
  bool m_floatBuffers = false;  // the layout the buffers were made with
  gl::Texture m_color, m_weights, m_depthStencil;
  gl::Framebuffer m_sceneFbo, m_compositeFbo;
  env::DynamicCubeMap m_cube;
  // This frame.
  Camera m_camera;
  Mode m_mode = Mode::Full;
  std::vector<DynamicDraw> m_dynamic;
  std::vector<BallDraw> m_balls;
  FrameStats m_stats;
  /// This frame's box of the eye and of everything the depth buffer can hold (the static
  /// scene, the dynamic parts, the balls and light markers): bounded volumes end past it.
  Bounds m_frameBox;
  /// Normalized device rectangle holding this light's volumes (lo, hi); `whole` when a
  /// volume reaches behind the eye and its projection is unbounded.
  struct VolumeBounds {
    vec2 lo{1.0f}, hi{-1.0f};
    bool whole = false;
  } m_volumeBounds;
};

}  // namespace glint::render::pipedream
