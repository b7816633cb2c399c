// The basics scenes against the lecture's own arithmetic (the OpenGL III lecture), computed here
// independently of the renderer.
#include "support/gl_test.h"

#include "glint/gl/render_target.h"
#include "glint/scenes/runner.h"

#include <utility>

using namespace glint;
using glint::testing::GlTest;

namespace {
// Image row of GL window row y in a picture of height h (GL's origin is the lower left).
int row(int y, int h) { return h - 1 - y; }

vec3 pixel(const Image& img, int glX, int glY) {
  const int r = row(glY, img.height());
  return {img.at(glX, r, 0), img.at(glX, r, 1), img.at(glX, r, 2)};
}

double area(vec2 a, vec2 b, vec2 c) { return 0.5 * double((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y)); }

Image renderImage(const char* name) { return scenes::renderVariant(scenes::Registry::builtin().resolve(name)).image; }
}  // namespace

TEST_F(GlTest, TriangleCentrePixelIsTheBarycentricBlendOfVertexColours) {
  const Image img = renderImage("basics/triangle/color");
  ASSERT_EQ(img.width(), 500);
  // Window coordinates from the lecture: L (50,450) red, M (450,450) green, N (250,50) blue.
  const vec2 L{50, 450}, M{450, 450}, N{250, 50};
  const vec2 P{250.5f, 250.5f};  // centre of window pixel (250, 250)
  const double total = area(L, M, N);
  const double alpha = area(P, M, N) / total, beta = area(L, P, N) / total, gamma = area(L, M, P) / total;
  EXPECT_NEAR(alpha + beta + gamma, 1.0, 1e-12);
  const vec3 expected{float(alpha), float(beta), float(gamma)};  // red, green, blue weights
  const vec3 actual = pixel(img, 250, 250);
  // 8-bit output: rounding is half a code; one more code for the rasterizer's
  // fixed-point interpolation.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], 1.5 / 255.0) << "channel " << c;
  // Outside the triangle: the (non-black) clear colour.
  const vec3 corner = pixel(img, 5, 5);
  EXPECT_NEAR(corner.r, 0.12f, 1.0 / 255.0);
  EXPECT_NEAR(corner.b, 0.18f, 1.0 / 255.0);
}

TEST_F(GlTest, TriangleDepthFollowsTheLecturesZPlane) {
  const auto ref = scenes::Registry::builtin().resolve("basics/triangle/color");
  auto scene = ref.scene->create(ref.variant);
  gl::RenderTarget target({500, 500});
  scene->render({.target = target.target()});
  const Image depth = gl::readDepth(target.framebuffer(), target.size());
  // Z(x, y) = -0.000625 x + 0.0003125 y + 0.540625 (window z, depth range [0, 1]).
  auto plane = [](double x, double y) { return -0.000625 * x + 0.0003125 * y + 0.540625; };
  for (auto [x, y] : {std::pair{250, 250}, {100, 420}, {400, 430}, {250, 80}}) {
    // 24-bit depth: quantization 6e-8; the rest is interpolation rounding.
    EXPECT_NEAR(depth.at(x, row(y, 500), 0), plane(x + 0.5, y + 0.5), 2e-6) << x << "," << y;
  }
  EXPECT_FLOAT_EQ(depth.at(2, 2, 0), 1.0f);  // cleared to far
}

TEST_F(GlTest, DepthFunctionsDecideWhoWins) {
  // NDC → window for 500×500: (x + 1) · 250. Red at window z 0.65; blue z = 0.72 + 0.4 (x − 0.2).
  auto at = [](const Image& img, float x, float y) { return pixel(img, int((x + 1) * 250), int((y + 1) * 250)); };
  auto isRed = [](vec3 c) { return c.r > 0.7f && c.b < 0.3f; };
  auto isBlue = [](vec3 c) { return c.b > 0.3f && c.r < c.b * 0.7f; };
  auto isBackground = [](vec3 c) { return std::abs(c.r - 0.12f) < 0.01f && std::abs(c.b - 0.18f) < 0.01f; };

  const Image less = renderImage("basics/depth/less");
  EXPECT_TRUE(isRed(at(less, -0.5f, 0.5f)));        // red only: 0.65 < 0.8
  EXPECT_TRUE(isBlue(at(less, -0.2f, 0.0f)));       // overlap, blue 0.56 < red 0.65
  EXPECT_TRUE(isRed(at(less, 0.15f, 0.0f)));        // overlap, blue 0.70 is rejected (the lecture's 0.72 case)
  EXPECT_TRUE(isBackground(at(less, 0.55f, 0.0f)));  // blue 0.86 loses to the cleared 0.8

  const Image greater = renderImage("basics/depth/greater");
  EXPECT_TRUE(isBackground(at(greater, -0.5f, 0.5f)));  // red 0.65 > 0.8 fails
  EXPECT_TRUE(isBlue(at(greater, 0.55f, 0.0f)));        // 0.86 > 0.8 passes

  const Image maskOff = renderImage("basics/depth/mask-off");
  EXPECT_TRUE(isBlue(at(maskOff, 0.15f, 0.0f)));  // red left 0.8 in the depth buffer

  const Image never = renderImage("basics/depth/never");
  EXPECT_TRUE(isBackground(at(never, -0.5f, 0.5f)));
  const Image always = renderImage("basics/depth/always");
  EXPECT_TRUE(isBlue(at(always, 0.15f, 0.0f)));  // painter's order
}

TEST_F(GlTest, ScenesDoNotInheritStateFromThePreviousScene) {
  // triangle/depth ends with a full-screen pass that turns depth writes off; glClear
  // honours the depth mask, so a scene drawn next must still get a cleared depth buffer.
  const Image fresh = renderImage("basics/depth/less");
  renderImage("basics/triangle/depth");
  const Image after = renderImage("basics/depth/less");
  EXPECT_EQ(compareImages(fresh, after).maxAbs, 0.0);
}
