// The bump/* and water/* scenes through the registry, as `glint render` runs them: the
// classic and shader DOT3 paths give the same picture, tangent- and object-space normal
// mapping agree, the water is deterministic in time, and nothing raises a GL error.
#include "glint/gl/debug.h"
#include "glint/image/image.h"
#include "glint/scenes/runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

using namespace glint;
using namespace glint::scenes;

namespace {
ContextPool& contexts() {
  static ContextPool pool(true);
  return pool;
}

Image renderAt(const std::string& name, double time, ivec2 size = {320, 180}, std::vector<std::string> options = {}) {
  const VariantRef ref = Registry::builtin().resolve(name);
  contexts().use(ref.scene->profile);
  const auto errors = gl::debugErrorCount();
  RenderResult r = renderVariant(ref, {.size = size, .time = time, .options = std::move(options)});
  EXPECT_EQ(gl::debugErrorCount(), errors) << name;
  return std::move(r.image);
}

void saveForEyes(const Image& image, const std::string& name) {
  const auto dir = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "bump";
  std::filesystem::create_directories(dir);
  saveImage(image, dir / name);
}
}  // namespace

TEST(BumpScenes, ClassicCombinersAndShaderPathRenderTheSameImage) {
  if (!contexts().available(gl::Profile::Compatibility))
    GTEST_SKIP() << "no compatibility-profile context: " << contexts().unavailableReason(gl::Profile::Compatibility);
  for (const char* variant : {"bricks", "bumps"}) {
    for (double t : {0.0, 3.0, 5.5}) {
      const Image classic = renderAt(std::string("bump/dot3-classic/") + variant, t);
      const Image shader = renderAt(std::string("bump/dot3-shader/") + variant, t);
      const ImageDifference d = compareImages(classic, shader);
      // Same bytes in, same textures and sampling state, the same combiner arithmetic in
      // float; the one 8-bit rounding at the end may fall either way: 1/255 max.
      EXPECT_LE(d.maxAbs, 1.0 / 255 + 1e-6) << variant << " t=" << t;
      EXPECT_LT(d.meanAbs, 0.1 / 255) << variant << " t=" << t;
      if (d.maxAbs > 1.0 / 255 + 1e-6) {
        saveForEyes(classic, std::string("classic-") + variant + ".png");
        saveForEyes(shader, std::string("shader-") + variant + ".png");
        saveForEyes(d.visual, std::string("diff-") + variant + ".png");
      }
    }
  }
}

TEST(BumpScenes, NormalizationFixBrightensTheSpotUnderACloseLight) {
  // The light hangs low over the polygon's middle: interpolated vectors are short there.
  const Image raw = renderAt("bump/normalize/interpolated", 3.0, {320, 180}, {"show-light=0"});
  const Image fixed = renderAt("bump/normalize/normalized", 3.0, {320, 180}, {"show-light=0"});
  double sumRaw = 0, sumFixed = 0;
  for (int y = 70; y < 110; ++y)
    for (int x = 140; x < 180; ++x)
      for (int c = 0; c < 3; ++c) {
        sumRaw += raw.at(x, y, c);
        sumFixed += fixed.at(x, y, c);
      }
  EXPECT_GT(sumFixed, 1.5 * sumRaw);
}

TEST(BumpScenes, TangentAndObjectSpaceMapsLightTheModelAlike) {
  // Both maps are baked from the same high poly; they differ only in how the normal is
  // stored, so the lit pictures agree up to the maps' 8-bit quantization and filtering.
  const Image tangent = renderAt("bump/normal-map/baked", 2.0);
  const Image object = renderAt("bump/object-space/baked", 2.0);
  const ImageDifference d = compareImages(tangent, object);
  EXPECT_LT(d.meanAbs, 1.0 / 255) << "mean";
  EXPECT_LT(double(d.differingPixels) / double(tangent.pixelCount()), 0.05);
  const Image plain = renderAt("bump/normal-map/vertex-normals", 2.0);
  // The studs and the groove: a fifth of the model's pixels change by more than 1/255, some a lot.
  const ImageDifference withoutMap = compareImages(tangent, plain);
  EXPECT_GT(withoutMap.maxAbs, 0.3) << "the map must visibly change the shading";
  EXPECT_GT(double(withoutMap.differingPixels) / double(tangent.pixelCount()), 0.08);
}

TEST(BumpScenes, WaterIsDeterministicInTime) {
  // Rendering t = 1.5 twice, or after another time, gives the same picture.
  const Image a = renderAt("water/height/rain", 1.5);
  const Image b = renderAt("water/height/rain", 1.5);
  EXPECT_EQ(a, b);
  const Image later = renderAt("water/height/rain", 2.0);
  EXPECT_GT(compareImages(a, later).meanAbs, 0.5 / 255) << "the water must move";
  // Every water variant renders without GL errors and shows something.
  for (const char* v : {"water/normals/rain", "water/shaded/pool", "water/shaded/grazing", "water/height/one-drop"}) {
    const Image img = renderAt(v, 1.0);
    EXPECT_GT(compareImages(img, Image(img.width(), img.height(), 4)).meanAbs, 0.05) << v;
  }
}
