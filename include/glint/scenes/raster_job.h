#pragma once
// glint/scenes/raster_job.h — `glint raster`'s job: geometry through glint::raster, the
// reference CPU pipeline (raster/raster.h), into pictures of its intermediate results —
// the lecture's pipeline (the OpenGL III lecture) made visible. Three kinds of geometry: the lecture's
// triangle, any mesh Assimp reads (Lambert-shaded, seen by an orbit camera), or the draws
// of a basics/reference scene variant. Every job writes DIR/color.png, depth.png (16-bit),
// edges.png (the chosen triangle's three edge functions), overdraw.png and stencil.png.
//
/// ```cpp
/// glint::scenes::RasterJob job;
/// job.geometry = glint::scenes::RasterGeometry::Mesh;
/// job.mesh = "bunny.ply";
/// job.output = "out/bunny";
/// job.camera = glint::scenes::parseOrbitCamera("40,25");
/// const glint::scenes::RasterReport report = glint::scenes::runRasterJob(job);
/// std::fputs(report.text().c_str(), stdout);  // what `glint raster mesh` prints
/// ```
//
// Everything is checked before anything is written (the size, the camera, the mesh, the
// triangle, the output directory); each picture is written atomically, so an error never
// leaves a partial one behind.
#include "glint/core/math.h"
#include "glint/raster/pipeline.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glint::scenes {

enum class RasterGeometry {
  Lecture,  ///< the lecture's triangle, with its numbers (RasterReport::lecture)
  Mesh,     ///< RasterJob::mesh, Lambert-shaded per vertex
  Scene,    ///< the draws of RasterJob::scene, a basics/reference variant
};

/// `glint raster`'s options as typed.
struct RasterJob {
  RasterGeometry geometry = RasterGeometry::Lecture;
  std::string output;              ///< the directory (created when missing)
  std::optional<ivec2> size;       ///< default: 640×480 for a mesh, 500×500 otherwise
  int triangle = -1;               ///< whose edge functions edges.png shows; -1: the largest in view
  std::string mesh;                ///< Mesh: the file
  vec3 camera{30.0f, 20.0f, 2.6f};  ///< Mesh: azimuth°, elevation°, distance in bounding radii
  bool cull = false;               ///< Mesh: cull back faces (off shows the full depth complexity)
  std::string scene;               ///< Scene: "basics/reference/VARIANT"
};

/// `--camera AZIMUTH,ELEVATION[,DISTANCE]` ("30,20" or "30,20,2.6"; distance 2.6 when
/// left out), through core/text's strict numbers. Error(Usage) naming the field.
vec3 parseOrbitCamera(std::string_view text);

/// What a job did: the draws, the pipeline's counts, the chosen triangle and the pictures.
struct RasterReport {
  std::string output;
  ivec2 size{0};
  std::vector<std::string> draws;  ///< one line per draw
  raster::DrawStats stats;         ///< summed over the draws
  std::size_t triangle = 0;        ///< the chosen triangle, counted across the draws
  std::array<glm::dvec3, 3> window{};  ///< its window coordinates (x, y, z)
  std::uint32_t maxOverdraw = 0, maxStencil = 0;
  /// Lecture: the lecture's own numbers, recomputed with the pipeline's functions (window
  /// coordinates, the LN edge's equation, the z plane, barycentrics). Empty otherwise.
  std::string lecture;

  /// What `glint raster` prints: the lecture's numbers, the draws, the pipeline's counts,
  /// the chosen triangle's edge equations and z plane, and the files written.
  std::string text() const;
};

/// Runs the job: the geometry, through the pipeline (a progress bar on a terminal), into
/// the five pictures. Error(Usage) for a bad option (a triangle out of range, behind the
/// eye or of zero area; a scene other than basics/reference), Error(Input) for a mesh that
/// cannot be read or is empty, Error(Output) for a directory that cannot hold the files.
RasterReport runRasterJob(const RasterJob& job);

}  // namespace glint::scenes
