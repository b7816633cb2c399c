// `glint raster` as a user runs it: the five pictures, the lecture's numbers, and bad
// input — a one-line error, the documented exit code, and no files left behind.
#include "glint/image/image.h"

#include "support/cli.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace glint;

namespace {
using Run = glint::testing::CliRun;
using glint::testing::fileCount;
using glint::testing::oneLine;
using glint::testing::runGlint;

fs::path dir(const char* name) { return glint::testing::freshDir("raster-cli", name); }

void writeFile(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// A closed cube as OBJ (counter-clockwise faces seen from outside).
const char* const kCubeObj =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\n";

const char* const kPictures[] = {"color.png", "depth.png", "edges.png", "overdraw.png", "stencil.png"};
}  // namespace

TEST(RasterCli, LectureWritesFivePicturesAndTheLecturesNumbers) {
  const fs::path out = dir("lecture") / "out";  // created by the command
  const auto r = runGlint("raster lecture -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* name : kPictures) EXPECT_TRUE(fs::exists(out / name)) << name;
  EXPECT_EQ(fileCount(out), 5u);  // no temporaries left behind
  // The slides' numbers: window coordinates, the LN edge, the z plane.
  EXPECT_NE(r.output.find("window (50, 450, 0.65)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("A = Ly - Ny = 0, B = Nx - Lx = -400, C = Ny Lx - Nx Ly = 180000"), std::string::npos);
  EXPECT_NE(r.output.find("E(250, 250) = 80000 > 0"), std::string::npos);
  EXPECT_NE(r.output.find("A_z = -0.000625, B_z = 0.0003125, C_z = 0.540625"), std::string::npos);
  EXPECT_NE(r.output.find("80000 fragments"), std::string::npos);  // the triangle's area: 400 · 400 / 2

  const Image color = loadImage(out / "color.png");
  ASSERT_EQ(color.width(), 500);
  EXPECT_GT(color.at(250, 500 - 1 - 400, 0), 0.3f);  // near the red corner: red
  const Image edges = loadImage(out / "edges.png");
  EXPECT_EQ(edges.width(), 3 * 500 + 2 * 4);  // three panels and two gaps
  EXPECT_EQ(edges.height(), 500);
  const Image depth = loadImage(out / "depth.png");
  // Window pixel (250, 250): Z = -0.000625·250.5 + 0.0003125·250.5 + 0.540625, in a 16-bit PNG.
  EXPECT_NEAR(depth.at(250, 500 - 1 - 250, 0), -0.000625 * 250.5 + 0.0003125 * 250.5 + 0.540625, 1.0 / 65535);
  EXPECT_FLOAT_EQ(depth.at(5, 5, 0), 1.0f);  // the clear value: white = far
}

TEST(RasterCli, MeshRendersWithTheChosenTriangle) {
  const fs::path d = dir("mesh");
  writeFile(d / "cube.obj", kCubeObj);
  const auto r = runGlint("raster mesh " + (d / "cube.obj").string() + " -o " + (d / "out").string() +
                          " --size 160x120 --camera 30,20,3 --triangle 2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("triangle 2: window"), std::string::npos) << r.output;
  const Image color = loadImage(d / "out" / "color.png");
  ASSERT_EQ(color.width(), 160);
  ASSERT_EQ(color.height(), 120);
  EXPECT_GT(color.at(80, 60, 0), 0.3f);  // the lit cube in the middle, not the dark background
  const Image overdraw = loadImage(d / "out" / "overdraw.png");
  EXPECT_GT(overdraw.at(80, 60, 0) + overdraw.at(80, 60, 1) + overdraw.at(80, 60, 2), 0.5f);  // front and back faces
}

TEST(RasterCli, SceneRunsAReferenceSceneAndRejectsOthers) {
  const fs::path d = dir("scene");
  auto r = runGlint("raster scene basics/reference/stencil-count --size 100x100 -o " + (d / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(fileCount(d / "out"), 5u);
  r = runGlint("raster scene basics/triangle/color -o " + (d / "other").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_FALSE(fs::exists(d / "other"));
  r = runGlint("raster scene basics/reference/nope -o " + (d / "other").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("variants: triangle"), std::string::npos) << r.output;
}

TEST(RasterCli, MissingMeshFileIsAnInputErrorAndWritesNothing) {
  const fs::path d = dir("missing");
  const auto r = runGlint("raster mesh " + (d / "nope.obj").string() + " -o " + (d / "out").string());
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("nope.obj"), std::string::npos) << r.output;
  EXPECT_EQ(fileCount(d), 0u);  // not even the output directory
}

TEST(RasterCli, EmptyMeshIsAnInputErrorAndWritesNothing) {
  const fs::path d = dir("empty");
  writeFile(d / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");  // vertices, no faces
  writeFile(d / "nothing.obj", "");
  for (const char* file : {"points.obj", "nothing.obj"}) {
    const auto r = runGlint("raster mesh " + (d / file).string() + " -o " + (d / "out").string());
    EXPECT_EQ(r.status, 3) << file << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << r.output;
    EXPECT_FALSE(fs::exists(d / "out")) << file;
  }
}

TEST(RasterCli, BadSizeCameraOrTriangleIsAUsageError) {
  const fs::path d = dir("usage");
  writeFile(d / "cube.obj", kCubeObj);
  const std::string mesh = "raster mesh " + (d / "cube.obj").string() + " -o " + (d / "out").string();
  for (const char* size : {"0x10", "axb", "100000x10"}) {  // parseSize itself: cli_test.cpp
    const auto r = runGlint(mesh + " --size " + size);
    EXPECT_EQ(r.status, 2) << size << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << r.output;
  }
  for (const char* camera : {"a,b", "0,95", "0,0,0.5"}) {
    const auto r = runGlint(mesh + " --camera " + camera);
    EXPECT_EQ(r.status, 2) << camera << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << r.output;
  }
  const auto r = runGlint(mesh + " --triangle 12");  // the cube has triangles 0..11
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("0..11"), std::string::npos) << r.output;
  EXPECT_EQ(runGlint("raster lecture").status, 2);  // -o is required
  EXPECT_EQ(runGlint("raster").status, 2);          // a form is required
  EXPECT_FALSE(fs::exists(d / "out"));
}

TEST(RasterCli, UnwritableOutputDirectoryFailsBeforeRendering) {
  const fs::path d = dir("unwritable");
  writeFile(d / "file", "not a directory");
  // A path through a regular file cannot be created, even by root; a file is not a directory.
  for (const fs::path& out : {d / "file" / "out", d / "file"}) {
    const auto r = runGlint("raster lecture -o " + out.string());
    EXPECT_EQ(r.status, 4) << out << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << r.output;
  }
  EXPECT_EQ(fileCount(d), 1u);  // only the file we made
}
