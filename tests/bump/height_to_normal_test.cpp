// The GPU height → normal pass (render/bump/height_to_normal.h) against the CPU function
// (image/normalmap.h): within one 8-bit step for every texel, every option, odd sizes.
#include "support/gl_test.h"

#include "glint/core/error.h"
#include "glint/image/heightfield.h"
#include "glint/image/normalmap.h"
#include "glint/render/bump/height_to_normal.h"
#include "glint/render/bump/textures.h"

#include <cmath>

using namespace glint;
using glint::testing::GlTest;

namespace {
// Both compute the same float expression; rounding to 8 bits can land on either side of a
// half step, so one step (1/255) of difference is allowed, never more.
void expectWithinOneStep(const Image& gpu, const Image& cpu, const char* what) {
  ASSERT_EQ(gpu.width(), cpu.width());
  ASSERT_EQ(gpu.height(), cpu.height());
  const ImageDifference d = compareImages(gpu, cpu);
  EXPECT_LE(d.maxAbs, 1.0 / 255 + 1e-6) << what;
  // Most texels are identical; a small share sits on a rounding boundary.
  EXPECT_LT(double(d.differingPixels) / double(gpu.pixelCount()), 0.02) << what;
}
}  // namespace

TEST_F(GlTest, HeightToNormalGpuMatchesCpu) {
  const Image bricks = makeBrickHeight(128);
  for (const NormalMapOptions& o : {NormalMapOptions{}, NormalMapOptions{.scale = 20.0f, .wrap = true},
                                    NormalMapOptions{.scale = 2.0f, .formula = NormalFormula::Slide},
                                    NormalMapOptions{.scale = -5.0f, .wrap = true}}) {
    expectWithinOneStep(render::bump::heightToNormalMapGpu(bricks, o), heightToNormalMap(bricks, o), "bricks");
  }
}

TEST_F(GlTest, HeightToNormalGpuHandlesOddSizesAndFormats) {
  // Non-power-of-two, 8-bit, 16-bit, float and colour inputs.
  Image h8(37, 23, 1, PixelType::U8), h16(61, 5, 1, PixelType::U16);
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) h8.set(x, y, 0, 0.5f + 0.5f * std::sin(0.4f * float(x)) * std::cos(0.3f * float(y)));
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 61; ++x) h16.set(x, y, 0, float((x * 7 + y * 13) % 61) / 61.0f);
  const Image colour = makeBrickAlbedo(40);
  for (bool wrap : {false, true}) {
    const NormalMapOptions o{.scale = 6.0f, .wrap = wrap};
    expectWithinOneStep(render::bump::heightToNormalMapGpu(h8, o), heightToNormalMap(h8, o), "8-bit 37x23");
    expectWithinOneStep(render::bump::heightToNormalMapGpu(h16, o), heightToNormalMap(h16, o), "16-bit 61x5");
    expectWithinOneStep(render::bump::heightToNormalMapGpu(colour, o), heightToNormalMap(colour, o), "colour 40x40");
  }
}

TEST_F(GlTest, HeightToNormalGpuOrientation) {
  // A ramp rising to the east and to the north (up in the picture): the normal leans west
  // and south, i.e. red < 0.5 and green < 0.5 — after upload, pass and readback.
  Image ramp(16, 16, 1, PixelType::F32);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) ramp.set(x, y, 0, 0.02f * float(x) + 0.03f * float(15 - y));
  const Image n = render::bump::heightToNormalMapGpu(ramp, {.scale = 10.0f});
  const vec3 v = decodeNormal({n.at(8, 8, 0), n.at(8, 8, 1), n.at(8, 8, 2)});
  const vec3 expected = glm::normalize(vec3(-10.0f * 0.02f, -10.0f * 0.03f, 1.0f));
  EXPECT_NEAR(v.x, expected.x, 1.0f / 255);
  EXPECT_NEAR(v.y, expected.y, 1.0f / 255);
}

TEST_F(GlTest, HeightToNormalPassRejectsMismatchedSizes) {
  const gl::Texture height = render::bump::uploadImage(makeBumpsHeight(32), {.mipmaps = false});
  gl::Texture normals(GL_TEXTURE_2D, "too-small");
  normals.storage(GL_RGBA8, 16, 16);
  render::bump::HeightToNormalPass pass;
  EXPECT_THROW(pass.run(height, normals), Error);
}
