// DOT3 bump mapping on the GPU (render/bump/dot3.h): the fixed-function GL_COMBINE path
// and the shader path, each against the OpenGL spec's formula computed by hand on the CPU,
// and against each other. The classic path needs a compatibility-profile context; where
// the driver has none those tests are skipped.
#include "glint/core/error.h"
#include "glint/gl/context.h"
#include "glint/gl/debug.h"
#include "glint/gl/render_target.h"
#include "glint/image/dot3.h"
#include "glint/render/bump/dot3.h"
#include "glint/render/bump/textures.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace glint;
using namespace glint::render::bump;

namespace {
constexpr int kSize = 32;  // texels of the test textures = pixels of the viewport: 1:1

struct Contexts {
  std::unique_ptr<gl::HeadlessContext> core, compat;
  std::string compatMissing;
};
Contexts& contexts() {
  static Contexts c = [] {
    Contexts r;
    r.core = gl::HeadlessContext::create({.profile = gl::Profile::Core, .debug = true});
    try {
      r.compat = gl::HeadlessContext::create({.profile = gl::Profile::Compatibility, .debug = true});
    } catch (const Error& e) {
      r.compatMissing = e.what();
    }
    return r;
  }();
  return c;
}

// Random texels (8-bit): every combination of signs and magnitudes gets exercised.
Image randomImage(unsigned seed) {
  Image img(kSize, kSize, 4);
  std::mt19937 rng(seed);
  for (auto& v : img.pixels<std::uint8_t>()) v = std::uint8_t(rng() & 0xFF);
  return img;
}

// An orthographic camera that maps the polygon's [−1, 1]² exactly onto the viewport, so pixel
// (x, y) samples texel (x, y) with nearest filtering.
glint::Camera fullViewport() {
  glint::Camera c;
  c.projection = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, -1.0f, 1.0f);
  return c;
}

// Renders the polygon with every vertex colour = `light` and returns the picture (row 0 top).
Image renderPolygon(bool classic, Dot3Stage stage, u8vec3 light, const Image& normalMap, const Image& base,
             const Dot3ShaderOptions& options = {}) {
  const Dot3Polygon polygon;
  const std::vector<u8vec3> colors(polygon.positions().size(), light);
  const UploadOptions nearest{.mipmaps = false, .nearest = true};
  const gl::Texture normals = uploadImage(normalMap, nearest), baseTexture = uploadImage(base, nearest);
  const gl::RenderTarget target({kSize, kSize});
  target.target().bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (classic) {
    Dot3Classic().draw(polygon, colors, fullViewport(), normals, baseTexture, stage);
  } else {
    Dot3Shader(polygon, options).draw(colors, polygon.model(), fullViewport(), normals, baseTexture, stage);
  }
  return gl::readColor(target.framebuffer(), target.size());
}

// The spec's arithmetic on the bytes, independently of both GPU paths.
vec3 expected(Dot3Stage stage, u8vec3 light, const Image& normalMap, const Image& base, int x, int y) {
  const vec3 c = vec3(light) / 255.0f;
  if (stage == Dot3Stage::LightVectors) return c;
  const vec3 n{normalMap.at(x, y, 0), normalMap.at(x, y, 1), normalMap.at(x, y, 2)};
  const float d = combineDot3Rgb(c, n);
  if (stage == Dot3Stage::DotProduct) return vec3(d);
  return combineModulate(vec3(d), {base.at(x, y, 0), base.at(x, y, 1), base.at(x, y, 2)});
}

// Both paths compute in float and round once when writing the 8-bit target; Mesa's
// fixed-function texenv and our shader may order the multiply-adds differently, so allow
// one 8-bit step.
constexpr float kTolerance = 1.0f / 255.0f + 1e-6f;

void checkAgainstSpec(bool classic) {
  const Image normalMap = randomImage(1), base = randomImage(2);
  const u8vec3 lights[] = {{128, 128, 255}, {255, 128, 128}, {40, 200, 170}, {0, 0, 0}, {255, 255, 255}};
  for (Dot3Stage stage : {Dot3Stage::LightVectors, Dot3Stage::DotProduct, Dot3Stage::Modulated}) {
    for (u8vec3 light : lights) {
      const auto errorsBefore = gl::debugErrorCount();
      const Image got = renderPolygon(classic, stage, light, normalMap, base);
      EXPECT_EQ(gl::debugErrorCount(), errorsBefore);
      int bad = 0;
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          // Texture row 0 is the image's last row after upload; readColor flips back, so
          // picture (x, y) shows texel (x, y) of the images as given.
          const vec3 e = expected(stage, light, normalMap, base, x, y);
          for (int k = 0; k < 3; ++k)
            if (std::abs(got.at(x, y, k) - e[k]) > kTolerance && bad++ < 5) {
              ADD_FAILURE() << (classic ? "classic" : "shader") << " stage " << int(stage) << " light "
                            << int(light.x) << "," << int(light.y) << "," << int(light.z) << " pixel " << x << ","
                            << y << " channel " << k << ": got " << got.at(x, y, k) * 255 << ", spec "
                            << e[k] * 255;
            }
        }
    }
  }
}
}  // namespace

TEST(Dot3Gl, ShaderPathComputesTheSpecFormula) {
  contexts().core->makeCurrent();
  checkAgainstSpec(false);
}

TEST(Dot3Gl, ClassicCombinersComputeTheSpecFormula) {
  if (!contexts().compat) GTEST_SKIP() << "no compatibility-profile context: " << contexts().compatMissing;
  contexts().compat->makeCurrent();
  checkAgainstSpec(true);
}

TEST(Dot3Gl, ClassicPathNeedsACompatibilityContext) {
  contexts().core->makeCurrent();
  try {
    Dot3Classic classic;
    FAIL() << "constructing the classic path on a core context must fail";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::NoGpu);
  }
}

TEST(Dot3Gl, PerPixelNormalizationRestoresUnitLength) {
  contexts().core->makeCurrent();
  // A short vector (the average of two opposite-ish unit vectors) gives a dim dot product;
  // normalized per pixel it gives the full one. Normal map = straight up everywhere.
  Image up(kSize, kSize, 4), white(kSize, kSize, 4);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int k = 0; k < 4; ++k) {
        up.set(x, y, k, k == 0 || k == 1 ? 128.0f / 255 : 1.0f);
        white.set(x, y, k, 1.0f);
      }
  const u8vec3 shortUp = encodeLightVector({0.0f, 0.0f, 0.4f});  // length 0.4, pointing up
  const Image raw = renderPolygon(false, Dot3Stage::DotProduct, shortUp, up, white);
  const Image fixed = renderPolygon(false, Dot3Stage::DotProduct, shortUp, up, white, {.normalizePerPixel = true});
  EXPECT_NEAR(raw.at(5, 5, 0), 0.4f, 2.0f / 255);
  EXPECT_NEAR(fixed.at(5, 5, 0), 1.0f, 2.0f / 255);
}
