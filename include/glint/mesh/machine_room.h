#pragma once
// glint/mesh/machine_room.h — a procedural stand-in for the static geometry of Animusic's
// "Pipe Dream" stage (seed 001): drums, banks of upright pipes, horizontal pipes, struts
// and platforms on a floor with two walls.
//
// The shadow cutter's benchmark (`glint bench cut`) and the `pipedream` scenes use it
// until the real stage exists. Every closed part (drum, pipe, strut, platform) is a
// watertight mesh of its own; the floor and walls are open tessellated grids, as stage
// sets are. The stage is `modules` instrument modules on a square grid (each about 8.7k
// triangles), so the triangle count grows with the stage, not with the tessellation:
//
//   glint::Mesh stage = glint::makeMachineRoom({.modules = 64});   // ≈ 560k triangles
//   auto lights = glint::machineRoomLights({.modules = 64});        // key and fill, above
//
// Deterministic: the same options give the same mesh, bit for bit, everywhere.

#include "glint/mesh/mesh.h"

#include <array>

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

}  // namespace glint
