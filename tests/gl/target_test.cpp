// Split screens: gl::Target regions keep draws and clears inside their rectangle, and a
// camera cropped to each rectangle (glint::Camera::cropped) tiles the same picture the
// whole camera draws into the whole frame.
#include "support/gl_test.h"

#include "glint/gl/render_target.h"
#include "glint/mesh/mesh.h"
#include "glint/core/camera.h"
#include "glint/render/raster_gl.h"
#include "glint/render/state.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

using namespace glint;
using glint::testing::GlTest;

namespace {
constexpr ivec2 kSize{161, 97};  // odd on purpose: the columns do not split evenly

// An icosphere's triangles as clip-space vertices of `camera`, coloured by their normal.
std::vector<raster::Vertex> sphereIn(const glint::Camera& camera) {
  const Mesh sphere = makeIcosphere(1.0f, 2);
  std::vector<raster::Vertex> out;
  for (std::uint32_t index : sphere.indices) {
    const vec3 p = sphere.positions[index];
    out.push_back({.position = camera.viewProjection() * vec4(p, 1.0f), .varyings = {vec4(p * 0.5f + 0.5f, 1.0f)}});
  }
  return out;
}

Image draw(const gl::RenderTarget& rt, const std::vector<std::pair<gl::Target, glint::Camera>>& parts) {
  rt.target().bind();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, vec4(0.1f, 0.2f, 0.3f, 1.0f));
  for (const auto& [target, camera] : parts) {
    target.bind();
    render::PipelineState{.depthTest = true, .cull = true}.apply();
    render::RasterTriangles(sphereIn(camera)).draw();
  }
  rt.target().bind();
  return gl::readColor(rt.framebuffer(), kSize);
}
}  // namespace

TEST(TargetRegions, ColumnsAndCellsTileTheTarget) {
  const gl::Target whole{.framebuffer = nullptr, .size = kSize};
  int width = 0;
  for (int i = 0; i < 3; ++i) {
    const gl::Target c = whole.column(i, 3);
    EXPECT_EQ(c.origin.x, width);
    EXPECT_EQ(c.size.y, kSize.y);
    EXPECT_TRUE(c.clipped);
    width += c.size.x;
  }
  EXPECT_EQ(width, kSize.x);
  // Row 0 is the top: its rectangle ends at the target's top edge (GL origin lower left).
  const gl::Target top = whole.cell(1, 0, 2, 2, 3);
  EXPECT_EQ(top.origin.y + top.size.y + 3, kSize.y);
  EXPECT_EQ(whole.cell(0, 1, 2, 2, 3).origin.y, 3);
  // Regions are clamped to their target, and nested regions stay inside.
  const gl::Target r = whole.region({150, 90}, {50, 50});
  EXPECT_EQ(r.size, ivec2(11, 7));
  EXPECT_EQ(r.region({5, 5}, {100, 100}).origin, ivec2(155, 95));
}

TEST_F(GlTest, CroppedCamerasTileTheWholePicture) {
  const gl::RenderTarget rt(kSize, GL_RGBA8, "split");
  const auto camera = glint::Camera::orbit(vec3(0.0f), 3.0f, 0.4f, 0.3f, 50.0f, float(kSize.x) / float(kSize.y));
  const Image whole = draw(rt, {{rt.target(), camera}});

  std::vector<std::pair<gl::Target, glint::Camera>> columns;
  for (int i = 0; i < 3; ++i) {
    const gl::Target c = rt.target().column(i, 3);
    columns.push_back({c, camera.cropped(kSize, c.origin, c.size)});
  }
  const Image tiled = draw(rt, columns);
  // The crops move every vertex by at most float rounding (≈1e-6 px), so only pixels whose
  // centres lie on an edge can change: allow a handful, none in the middle of a face.
  const auto diff = compareImages(tiled, whole);
  EXPECT_LE(double(diff.differingPixels) / double(whole.pixelCount()), 0.003)
      << diff.differingPixels << " pixels differ, max " << diff.maxAbs * 255.0 << "/255";

  // The same columns drawn with the uncropped camera squeeze the whole view into each
  // column: a control that the comparison above can fail.
  std::vector<std::pair<gl::Target, glint::Camera>> squeezed;
  for (const auto& [target, cropped] : columns) squeezed.push_back({target, camera});
  EXPECT_GT(double(compareImages(draw(rt, squeezed), whole).differingPixels) / double(whole.pixelCount()), 0.1);
}

TEST_F(GlTest, ARegionClipsClearsAndBindingTheWholeTargetEndsIt) {
  const gl::RenderTarget rt(kSize, GL_RGBA8, "clip");
  rt.target().bind();
  render::clear(GL_COLOR_BUFFER_BIT, vec4(0.0f, 0.0f, 0.0f, 1.0f));
  rt.target().region({10, 20}, {30, 40}).bind();
  render::clear(GL_COLOR_BUFFER_BIT, vec4(1.0f, 1.0f, 1.0f, 1.0f));  // only the rectangle
  rt.target().bind();
  EXPECT_FALSE(glIsEnabled(GL_SCISSOR_TEST));
  const Image image = gl::readColor(rt.framebuffer(), kSize);
  int white = 0;
  for (int y = 0; y < kSize.y; ++y)
    for (int x = 0; x < kSize.x; ++x) white += image.at(x, y, 0) > 0.5f;
  EXPECT_EQ(white, 30 * 40);
  // Image row 0 is the top: GL row 20 is image row kSize.y − 1 − 20.
  EXPECT_GT(image.at(10, kSize.y - 1 - 20, 0), 0.5f);
  EXPECT_LT(image.at(9, kSize.y - 1 - 20, 0), 0.5f);
}

TEST_F(GlTest, PipelineStateSetsSeamlessCubeMapsAndResetTurnsThemOff) {
  render::PipelineState{.seamlessCubeMap = true}.apply();
  EXPECT_TRUE(glIsEnabled(GL_TEXTURE_CUBE_MAP_SEAMLESS));
  EXPECT_TRUE(render::stateLeftBehind().empty());  // PipelineState's own: not left behind
  render::resetState();
  EXPECT_FALSE(glIsEnabled(GL_TEXTURE_CUBE_MAP_SEAMLESS));
}

TEST_F(GlTest, StateLeftBehindNamesWhatAPassDidNotRestore) {
  render::resetState();
  EXPECT_EQ(render::stateLeftBehind(), std::vector<std::string>{});
  glEnable(GL_SCISSOR_TEST);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  EXPECT_EQ(render::stateLeftBehind(), (std::vector<std::string>{"GL_SCISSOR_TEST", "GL_UNPACK_ALIGNMENT"}));
  glDisable(GL_SCISSOR_TEST);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  EXPECT_TRUE(render::stateLeftBehind().empty());
}
