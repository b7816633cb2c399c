#pragma once
// glint/pipedream/machine_room.h — a procedural stand-in for the static geometry of Animusic's
// "Pipe Dream" stage (WWDC 2003 session 212): drums, banks of upright pipes, horizontal pipes, struts
// and platforms on a floor with two walls.
//
// Contents
//   makeMachineRoom        the shadow cutter's benchmark stage (`glint bench cut`, tests/cut)
//   makeInstrumentMachine  the same kind of stage grown into the `pipedream` scene's instrument
//                          machine: curved pipes, drums, cymbals, xylophones, launchers,
//                          collectors, struts and walls, with normals and materials, the
//                          places where its moving parts sit, its dynamic parts and its lights
//
// The stand-in: every closed part (drum, pipe, strut, platform) is a
// watertight mesh of its own; the floor and walls are open tessellated grids, as stage
// sets are. The stage is `modules` instrument modules on a square grid (each about 8.7k
// triangles), so the triangle count grows with the stage, not with the tessellation:
//
/// ```cpp
/// const glint::Mesh stage = glint::makeMachineRoom({.modules = 64});  // ≈ 560k triangles
/// const std::array<glint::vec3, 2> lights = glint::machineRoomLights({.modules = 64});  // key and fill, above
/// ```
//
// Deterministic: the same options give the same mesh, bit for bit, everywhere.

#include "glint/mesh/mesh.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace glint {

struct MachineRoomOptions {
  int modules = 64;        ///< instrument modules (laid out on a ⌈√n⌉-wide grid)
  std::uint32_t seed = 1;  ///< varies sizes and heights
};

Mesh makeMachineRoom(const MachineRoomOptions& options = {});

/// Modules for about `triangles` triangles (at least 1).
int machineRoomModulesFor(std::size_t triangles);

/// The two lights the stage is lit by: a key light high above the front left, a fill
/// light lower at the right.
std::array<vec3, 2> machineRoomLights(const MachineRoomOptions& options = {});

// ------------------------------------------------------------------ the instrument machine
// The `pipedream` scene's stage (docs/pipedream.md): the stand-in's modules grown into
// instruments. Static (never moves; its shadows are cut in by glint::cut): a room (floor
// and three walls, open tessellated grids), long pipes on brackets along the walls, and
// a 3 × 2 grid of modules, each a platform with two drum shells, mallet posts, a cymbal
// stand, a xylophone (frame and eight bars), a bank of upright pipes, a launcher pipe swept
// along a curve (out of the platform, bent upwards, its mouth pointing up), a collector and
// an arched pipe on struts. Dynamic (moved by the scene's score): drum skins, cymbals,
// mallets and balls, as meshes in their own frames, and where each one sits.
//
// Every static part is a closed, outward mesh of its own (curved and flat faces meet at
// bit-identical positions, so it is watertight once welded); the room is one open surface.
// Normals are smooth along curved surfaces and flat across edges. Polygons grow with
// `detail` (segments around tubes, samples along curves, cells of the room's grids):
//
/// ```cpp
/// #include <algorithm>
/// const glint::InstrumentMachine machine = glint::makeInstrumentMachine({.detail = 4});
/// const std::size_t triangles = machine.staticMesh.triangleCount();  // the geometry glint::cut cuts
/// float reach = 0.0f;
/// for (const glint::MachineLight& light : machine.lights)  // key and fill: positions, ranges, intensities
///   reach = std::max(reach, light.range);
/// ```
//
// Deterministic: the same options give the same machine, bit for bit.

/// What a static triangle is made of (an albedo each: machineMaterialColor).
enum class MachineMaterial : std::uint8_t {
  Floor,     ///< the floor grid
  Wall,      ///< the three walls
  Platform,  ///< the modules' platforms
  Drum,      ///< drum shells
  Brass,     ///< upright pipes, wall pipes, arches
  Copper,    ///< launcher pipes
  Steel,     ///< struts, posts, stands, xylophone frames, brackets
  Wood,      ///< xylophone bars
  Teal,      ///< collectors
};
/// Linear albedo of a material.
vec3 machineMaterialColor(MachineMaterial material);

struct InstrumentMachineOptions {
  int detail = 4;          ///< tessellation level, 1..16: segments, curve samples and grid cells grow with it
  std::uint32_t seed = 1;  ///< varies heights and sizes
};

/// A drum: its shell is static, its skin (InstrumentMachine::skin) a dynamic part on top.
struct MachineDrum {
  vec3 top{0.0f};  ///< centre of the shell's top face, where the skin rests
  float radius = 0.0f;
};
/// A cymbal on its stand: the stand is static, the cymbal a dynamic part pivoting at `pivot`.
struct MachineCymbal {
  vec3 pivot{0.0f};  ///< top of the stand, the cymbal's centre at rest
  float radius = 0.0f;
};
/// A xylophone bar (static), struck from above.
struct MachineBar {
  vec3 top{0.0f};  ///< centre of the bar's top face
  vec3 size{0.0f};
};
/// A launcher pipe's mouth: balls leave it upwards.
struct MachineLauncher {
  vec3 mouth{0.0f};  ///< centre of the mouth (the pipe's top face)
  float radius = 0.0f;
};
/// A collector: a short wide tube balls drop into.
struct MachineCollector {
  vec3 top{0.0f};  ///< centre of its top face
  float radius = 0.0f;
};
/// A mallet on a post beside a drum: it turns about a horizontal axis through `pivot`.
struct MachineMallet {
  vec3 pivot{0.0f};  ///< top of its post
  int drum = 0;      ///< the drum it strikes (index into drums)
};
/// A point light with a range: its light (and a dynamic shadow of it) ends at `range`.
struct MachineLight {
  vec3 position{0.0f};
  float range = 10.0f;     ///< metres: attenuation falls smoothly to zero there
  float intensity = 1.0f;  ///< diffuse scale at the light
  std::string name;
};

struct InstrumentMachine {
  Mesh staticMesh;                                  ///< positions, normals, indices (world space)
  std::size_t shellTriangles = 0;                   ///< the first triangles of staticMesh: the room (one open surface)
  std::vector<MachineMaterial> triangleMaterial;    ///< one per static triangle
  std::vector<MachineDrum> drums;
  std::vector<MachineCymbal> cymbals;
  std::vector<MachineBar> bars;
  std::vector<MachineLauncher> launchers;
  std::vector<MachineCollector> collectors;
  std::vector<MachineMallet> mallets;
  std::vector<MachineLight> lights;                 ///< key, fill (the static lights)
  Bounds room;                                      ///< the room's floor and walls
  // Dynamic parts in their own frames (closed, outward, with normals):
  Mesh skin;         ///< a drum skin: radius 1 (scaled to the drum), 2 cm thick, bottom at y = 0
  Mesh cymbal;       ///< radius 1 (scaled), centred at the pivot, bell up
  Mesh mallet;       ///< arm along −x from the pivot (origin) to a head at (−1, 0, 0), scaled per mallet
  /// The mallet's shadow caster: the same arm, and a head with a third of the head's
  /// segments and rings where those divide (else the mallet itself). Its vertices lie at
  /// every third of the head's angles, 1e-4 inside the head's sphere, so it lies inside
  /// the convex head and its shadow inside the mallet's (inset by at most 1 − cos 18° ≈ 5 %
  /// of the head's radius); the volumes of the twelve mallets' 30 × 15 heads were most of a
  /// frame's volume triangles.
  Mesh malletShadow;
  float ballRadius = 0.12f;
};

InstrumentMachine makeInstrumentMachine(const InstrumentMachineOptions& options = {});

}  // namespace glint
