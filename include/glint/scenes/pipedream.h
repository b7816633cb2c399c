#pragma once
// glint/scenes/pipedream.h — the `pipedream` scene's stage: the instrument machine, its
// score, and its static shadows cut in (and cached on disk), ready for the renderer.
//
// Contents
//   kDefaultDetail     the tessellation that puts the frame in WWDC 2003 session 212's 400k–550k range
//   cutLights          the machine's static lights as the cutter takes them
//   makeStaticGeometry a cut → render::pipedream::StaticGeometry (normals, albedo, mask groups)
//   cutEdges           the cut polygons' sides, for the wireframe view
//   StageOptions, Stage, loadStage   everything a frame needs, built once per process
//   NamedCamera, namedCameras, namedCamera   WWDC 2003 session 212's camera moves
//
// The stage is deterministic: the machine is generated in code (pipedream/machine_room.h), the
// score is data (pipedream/score.h), and the cut is glint::cut's exact output for
// the machine's static geometry and lights. The cut takes seconds, so it is kept on disk
// (cut/cache.h: named by a hash of the geometry, the lights and the cutter's version, so a
// change to any of them cuts again, with a progress bar) and loaded in a fraction of that
// afterwards. Polygons grow with `detail`:
//
/// ```cpp
/// const auto stage = glint::scenes::pipedream::loadStage({.detail = 2});  // with a current GL context
/// glint::render::pipedream::Renderer renderer(stage->machine, stage->geometry);
/// const glint::gl::RenderTarget frame({1280, 720});
/// const glint::gl::Target target = frame.target();
/// const auto pose = glint::pipedream::poseAt(stage->machine, stage->score, 3.0);
/// renderer.render(pose, glint::scenes::pipedream::namedCamera(0, target.aspect()), target,
///                 glint::render::pipedream::Mode::Full);
/// ```

#include "glint/cut/cache.h"
#include "glint/pipedream/machine_room.h"
#include "glint/core/camera.h"
#include "glint/render/pipedream/renderer.h"
#include "glint/pipedream/score.h"

#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace glint::scenes::pipedream {

/// The scene's default tessellation: about 443k input triangles, cut into ~443k triangles
/// (the cut's optimization step merges as much as the shadows add), ~464k drawn per frame
/// with the dynamic parts (WWDC 2003 session 212: "about 400,000 polygons per frame on average, 550,000
/// peak"). Detail 5 gave the range while the cut still tripled its input.
constexpr int kDefaultDetail = 13;

/// The machine's lights, for glint::cut.
std::vector<cut::Light> cutLights(const InstrumentMachine& machine);

/// The renderer's static geometry from a cut of `machine.staticMesh` by its lights: one
/// vertex per (cut vertex, input triangle), its normal interpolated from the input
/// triangle's vertex normals at that point and its albedo from the triangle's material;
/// triangles grouped by light mask. `edges`: also the polygons' sides (cutEdges).
render::pipedream::StaticGeometry makeStaticGeometry(const InstrumentMachine& machine, const cut::CutTriangles& cut,
                                                     bool edges = true);

/// The sides of the cut's polygons (the triangles' edges that are not diagonals inside a
/// polygon), each once, as GL_LINES index pairs into `cut.positions` (padded with repeats
/// of the first pair to a multiple of 6 indices, so the mesh also has whole triangles).
Mesh cutEdges(const cut::CutTriangles& cut);

struct StageOptions {
  int detail = kDefaultDetail;           ///< 1..16 (InstrumentMachineOptions::detail)
  std::filesystem::path cacheDirectory;  ///< where cuts are kept; empty: glint's cache directory (core/cache.h)
  bool progress = true;                  ///< the cutter's progress bar when a cut is built (on a terminal)
};

struct Stage {
  InstrumentMachine machine;
  glint::pipedream::Score score;
  render::pipedream::StaticGeometry geometry;
  std::filesystem::path cutFile;  ///< the cached cut
  bool cutBuilt = false;          ///< this process cut it (false: loaded)
  double cutSeconds = 0.0;        ///< cutting and writing, or loading
  double buildSeconds = 0.0;      ///< everything: machine, cut, geometry
  int detail = 0;
  /// Triangles drawn per frame by WWDC 2003 session 212's method at `pose`: the cut static scene, the
  /// dynamic parts and the balls.
  std::size_t trianglesPerFrame(const glint::pipedream::MachinePose& pose) const;
  /// One line: input triangles, cut polygons, triangles, masks, where the cut came from.
  std::string describe() const;
};

/// The stage for `options`, built on first use and shared for the rest of the process
/// (one per detail and cache directory; thread-safe). Errors as cut::cachedCut.
std::shared_ptr<const Stage> loadStage(const StageOptions& options = {});

/// A camera of WWDC 2003 session 212's demo.
struct NamedCamera {
  const char* name;
  const char* description;
  vec3 eye, target;
  float fovY;  ///< degrees
};
/// The scene's cameras: 0 "stage" (the whole machine), 1 "drums" (over the drum machine on
/// the left), 2 "wall" (the back wall: baked and dynamic shadows side by side), 3 "side"
/// (across the machine from the side, where volume overdraw is worst), 4 "balls" (a close
/// look at balls in flight).
std::span<const NamedCamera> namedCameras();
/// Camera `index` (clamped to the list) at `aspect`, near plane 0.3 m.
glint::Camera namedCamera(int index, float aspect);

}  // namespace glint::scenes::pipedream
