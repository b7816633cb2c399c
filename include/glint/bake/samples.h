#pragma once
// glint/bake/samples.h — procedural high-poly meshes with real surface detail, so the
// baker can be demonstrated, tested and benchmarked without binary files in git.
//
//   Mesh high = bake::makeStuddedTorus({.segments = 512, .sides = 256});   // 262k triangles
//   Mesh low = makeTorus(1.0f, 0.35f, 32, 16);                              // its low poly
//
// The studded torus is glint's makeTorus displaced along its normals by a grid of smooth
// domes (studs) and a groove around the outer equator; its normals are recomputed from
// the displaced surface (computeNormals). Counts: 2 · segments · sides triangles.

#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include <filesystem>

namespace glint::bake {

struct StuddedTorusOptions {
  float majorRadius = 1.0f;
  float minorRadius = 0.35f;
  int segments = 256;        ///< around the main axis (u)
  int sides = 128;           ///< around the tube (v)
  int studsAround = 24;      ///< studs along u
  int studsAcross = 8;       ///< studs along v
  float studHeight = 0.03f;  ///< dome height, scene units (negative: dimples)
  float grooveDepth = 0.015f;///< depth of the groove on the outer equator (0: none)
};

/// Error(Usage) for fewer than 3 segments or sides.
Mesh makeStuddedTorus(const StuddedTorusOptions& options = {});

/// Splits every triangle of `mesh` into k² smaller ones lying exactly on it (barycentric
/// grid), interpolating normals and UVs; tangents are dropped. Vertices are not shared
/// between triangles. k ≥ 1.
Mesh subdivideFlat(const Mesh& mesh, int k);

/// A tileable painted-detail height map (R F32, 0..1, 1 = the surface): pores (small
/// round pits) and scratches (thin straight grooves), placed by a fixed seed. For
/// BakeOptions::detail demos and tests.
Image makeScratchesAndPores(int size = 256, int pores = 60, int scratches = 12);

/// Writes `mesh` as a Wavefront OBJ (v, vt, vn, f with 1-based indices), atomically, so
/// other tools (Blender in bench/peers/, the CLI tests) can read the same meshes.
/// Error(Output) when it cannot be written.
void writeObj(const Mesh& mesh, const std::filesystem::path& path);

}  // namespace glint::bake
