// glint raster — geometry through glint::raster, the reference CPU pipeline, into pictures
// of its intermediate results: the lecture's pipeline (the OpenGL III lecture) made visible. The job is
// scenes/raster_job.h; this file is its options.
//
//   glint raster lecture -o DIR                 the lecture's triangle, with its numbers
//   glint raster mesh FILE -o DIR [options]     any mesh Assimp reads, Lambert-shaded
//   glint raster scene basics/reference/V -o DIR  a reference scene's draws
#include "common.h"

#include "glint/core/text.h"
#include "glint/scenes/raster_job.h"

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <string>

namespace glint::app {

namespace {
struct RasterArgs {
  std::string output;
  std::string size;
  int triangle = -1;  // -1: the largest visible one
  std::string file;   // mesh
  std::string camera = "30,20,2.6";
  bool cull = false;
  std::string scene;  // scene
};
}  // namespace

Command rasterCommand(CLI::App& app, const GlobalOptions&) {
  auto args = std::make_shared<RasterArgs>();
  auto* cmd = app.add_subcommand("raster", "Run geometry through glint::raster, the reference CPU pipeline, and picture "
                                           "its steps (colour, depth, edge functions, overdraw, stencil)");
  cmd->require_subcommand(1);
  cmd->footer(
      "Every form writes five PNGs into DIR (created if missing):\n"
      "  color.png     the colour buffer\n"
      "  depth.png     the depth buffer, white = 1.0 (far), black = 0.0 (near), 16-bit\n"
      "  edges.png     the chosen triangle's three edge functions E0 | E1 | E2 (E(x, y) = A x + B y + C,\n"
      "                oriented so inside is positive): red > 0, blue < 0, black = the edge itself (E = 0),\n"
      "                covered pixels darkened; a pixel is drawn where all three are >= 0\n"
      "  overdraw.png  fragments per pixel (depth complexity), false colour 1 blue ... max red\n"
      "  stencil.png   the stencil buffer (mesh: glStencilOp(KEEP, KEEP, INCR) counts depth-test passes)\n"
      "The pipeline is OpenGL's, step by step: clipping, window coordinates snapped to 1/256 pixel,\n"
      "edge equations with the bottom-left tie rule, depth/stencil/blending (docs/raster.md).\n"
      "Examples:\n"
      "  glint raster lecture -o out/lecture\n"
      "  glint raster mesh bunny.ply -o out/bunny --size 800x600 --camera 40,25 --triangle 1200\n"
      "  glint raster scene basics/reference/stencil-count -o out/stencil");
  auto addCommon = [&](CLI::App* sub, const char* defaultSize) {
    sub->add_option("-o,--output", args->output, "Output directory (created if missing)")->required();
    sub->add_option("--size", args->size, std::string("WIDTHxHEIGHT in pixels (default ") + defaultSize + ")");
    sub->add_option("--triangle", args->triangle,
                    "Triangle whose edge functions edges.png shows (default: the largest in view)");
  };
  auto* lecture = cmd->add_subcommand("lecture", "The lecture's triangle at 500x500, printing its window coordinates, "
                                                 "edge coefficients, z plane and barycentrics");
  addCommon(lecture, "500x500");
  auto* mesh = cmd->add_subcommand("mesh", "Any mesh Assimp reads (OBJ, PLY, glTF, STL, ...), Lambert-shaded, seen "
                                           "by an orbit camera");
  mesh->add_option("file", args->file, "Mesh file")->required();
  addCommon(mesh, "640x480");
  mesh->add_option("--camera", args->camera,
                   "AZIMUTH,ELEVATION[,DISTANCE]: degrees around and above the mesh, distance in bounding-sphere radii")
      ->capture_default_str();
  mesh->add_flag("--cull", args->cull, "Cull back faces (glEnable(GL_CULL_FACE)); off shows the full depth complexity");
  auto* scene = cmd->add_subcommand("scene", "The draws of a basics/reference scene variant (see `glint list`)");
  scene->add_option("name", args->scene, "basics/reference/VARIANT")->required();
  addCommon(scene, "500x500");

  return Command{.run = [args, lecture, mesh] {
    scenes::RasterJob job{.output = args->output, .triangle = args->triangle, .mesh = args->file, .cull = args->cull,
                          .scene = args->scene};
    job.geometry = lecture->parsed() ? scenes::RasterGeometry::Lecture
                   : mesh->parsed()  ? scenes::RasterGeometry::Mesh
                                     : scenes::RasterGeometry::Scene;
    if (!args->size.empty()) job.size = parseSize(args->size);
    if (mesh->parsed()) job.camera = scenes::parseOrbitCamera(args->camera);
    const scenes::RasterReport report = scenes::runRasterJob(job);
    std::fputs(report.text().c_str(), stdout);
    return 0;
  }};
}

}  // namespace glint::app
