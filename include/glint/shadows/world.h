#pragma once
// glint/shadows/world.h — what every shadow technique draws: objects, a ground
// and one point light, as plain data (no GL), plus the worlds the shadow scenes,
// tests and benchmarks share.
//
// Contents
//   WorldObject        a mesh in object space, its placement, colour, caster/ground flags
//   World              objects + a positional light + ambient level
//   makeDemoWorld      the WWDC 2001 talk's demo: a slab casting a volume, a sphere moving in and out
//   makeBunnyWorld     the Stanford bunny (closed, or with its base cut open) on a ground
//   makeBenchWorld     a field of spheres with about N triangles in total
//   SceneView, sceneCamera  where the shadow scenes look at these worlds from
//   bunnyPath/loadBunny  where scripts/setup put the bunny, and loading it
//
// The same World feeds the GPU techniques (render/shadows/*) and the ray-traced
// oracle in the tests (worldMesh() gives each object in world space), so both see
// exactly the same triangles; sceneCamera() gives both the same viewpoints, so the
// oracle tests check what the gallery shows.

#include "glint/core/math.h"
#include "glint/mesh/mesh.h"
#include "glint/core/camera.h"

#include <filesystem>
#include <string>
#include <vector>

namespace glint::shadows {

struct WorldObject {
  std::string name;
  Mesh mesh;                 ///< object space, with normals; counter-clockwise front faces
  mat4 transform{1.0f};      ///< object → world (rigid or uniformly scaled)
  vec3 color{0.8f};          ///< diffuse albedo
  bool castsShadow = true;   ///< false: receives shadows only (its triangles build no volume)
  bool ground = false;       ///< the receiving plane y = World::groundHeight (planar shadows);
                             ///< drawn with a checker pattern
};

struct World {
  std::vector<WorldObject> objects;
  vec3 lightPosition{0.0f, 5.0f, 0.0f};  ///< positional light, world space
  float ambient = 0.22f;                 ///< ambient fraction of the albedo (what shadows keep)
  float groundHeight = 0.0f;

  /// Object `i` transformed to world space (positions and normals).
  Mesh worldMesh(std::size_t i) const;
  /// Bounds of every object in world space.
  Bounds bounds() const;
  /// Triangles over all objects.
  std::size_t triangleCount() const;
};

/// The WWDC 2001 talk's demo: a square slab hovering under the light casts a shadow
/// volume onto the ground; a sphere rolls along x through it, in and out of the volume,
/// with `time` (period 8 s; at t = 0 it is half inside). `sphereCasts` = false keeps the
/// sphere a receiver only, as in the WWDC 2001 talk, where only the slab's volume is drawn.
World makeDemoWorld(double time = 0.0, bool sphereCasts = true);
/// Moves the demo sphere to where it is at `time` (only World::objects[2] changes).
void animateDemoWorld(World& world, double time);

/// The Stanford bunny (1 unit tall) on a ground with a torus beside it. `openBase`
/// deletes the triangles of its base, leaving holes like the original scan's.
World makeBunnyWorld(const Mesh& bunny, bool openBase);

/// About `triangles` triangles: a grid of UV spheres (casters) over a ground, for benchmarks.
World makeBenchWorld(std::size_t triangles);

/// Where a shadow scene looks from.
enum class SceneView {
  Demo,    ///< the demo world (makeDemoWorld) from the front and above
  Inside,  ///< from inside the demo slab's shadow volume, looking out at the sphere
  Bunny    ///< the bunny world (makeBunnyWorld): the bunny and the pinwheel
};

/// The camera of `view` at `aspect` (width / height), with the near and far planes the
/// scenes draw with (z-fail scenes then move the far plane to infinity):
///
/// ```cpp run
/// using namespace glint::shadows;
/// const glint::Camera camera = sceneCamera(SceneView::Demo, 16.0f / 9.0f);
/// ```
Camera sceneCamera(SceneView view, float aspect);

/// bunny/bunny.ply in glint's data (core/locations.h's findDataFile; scripts/setup fetches
/// it). Error(Input) naming where it looked and `scripts/setup` when it is missing.
std::filesystem::path bunnyPath();
/// Loads the bunny from bunnyPath() with winding checked (outward). Error(Input) as bunnyPath().
Mesh loadBunny();

}  // namespace glint::shadows
