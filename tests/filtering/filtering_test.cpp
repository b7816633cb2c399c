// Texture filtering (render/filtering/filtering.h) measured against a 16×16-supersampled truth:
// the order the WWDC 2001 talk describes, and the anisotropy limit.
#include "../support/gl_test.h"

#include "glint/core/error.h"
#include "glint/image/pattern.h"
#include "glint/render/filtering/filtering.h"

#include <algorithm>
#include <string>

using namespace glint;
namespace flt = glint::render::filtering;

namespace {
class FilteringGl : public glint::testing::GlTest {};

flt::FilterMode mode(const char* name) {
  for (const auto& m : flt::standardModes())
    if (std::string(m.name) == name) return flt::clampedToDevice(m);
  ADD_FAILURE() << "no mode " << name;
  return {};
}
}  // namespace

TEST_F(FilteringGl, FiltersRankAsTheSeedDescribes) {
  for (const Image& texture : {makeCheckerboard(512, 8), makeTestChart(512)}) {
    const flt::GroundPlane ground(texture);
    const auto bilinear = flt::measureFiltering(ground, mode("bilinear"));
    const auto trilinear = flt::measureFiltering(ground, mode("trilinear"));
    const auto aniso = flt::measureFiltering(ground, mode("aniso16"));
    ::testing::Message figures;
    figures << "bilinear err " << bilinear.rmsError << " flicker " << bilinear.flicker << "; trilinear err "
            << trilinear.rmsError << " sharp " << trilinear.sharpnessRatio() << " flicker " << trilinear.flicker
            << "; aniso16 err " << aniso.rmsError << " sharp " << aniso.sharpnessRatio();
    SCOPED_TRACE(figures);
    if (flt::maxAnisotropy() >= 2.0f) {
      // "if I raise the anisotropic filtering level ... the image becomes sharp even when
      // it's viewed at a bleak angle": closer to the truth, and sharper than trilinear.
      EXPECT_LT(aniso.rmsError, 0.8 * trilinear.rmsError);
      EXPECT_LT(trilinear.sharpness, 0.9 * aniso.sharpness);
    }
    // "when you use trilinear filtering, the texture becomes blurred": below the truth's detail.
    EXPECT_LT(trilinear.sharpnessRatio(), 0.85);
    // "using bilinear filtering ... you can see some sparkling": flicker over a camera move
    // that mipmapping removes.
    EXPECT_GT(bilinear.flicker, 1.5 * trilinear.flicker);
    EXPECT_GT(bilinear.rmsError, trilinear.rmsError);
  }
}

TEST_F(FilteringGl, AnisotropyOutsideTheQueriedRangeIsAOneLineError) {
  const float maximum = flt::maxAnisotropy();
  EXPECT_GE(maximum, 1.0f);
  const auto sampler = gl::Sampler::create("test");
  flt::FilterMode m = mode("trilinear");
  m.anisotropy = maximum;
  EXPECT_NO_THROW(flt::applyFilterMode(sampler, m));
  for (float bad : {maximum * 2.0f, 0.5f}) {
    m.anisotropy = bad;
    try {
      flt::applyFilterMode(sampler, m);
      ADD_FAILURE() << "anisotropy " << bad << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage);
      EXPECT_NE(std::string(e.what()).find("GL_MAX_TEXTURE_MAX_ANISOTROPY"), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  // Variants ask for 16 whatever the GPU: they are clamped, not refused.
  EXPECT_LE(flt::clampedToDevice(mode("aniso16")).anisotropy, maximum);
}

// What GL specifies of anisotropic filtering, which the reference images cannot hold to bytes
// (the samples' count and placement are the implementation's: Mesa 22 and 25 differ, and
// VariantDesc::implementationDefined loosens those images' check): each level is no less
// sharp than the one below it and than trilinear, and no farther from the supersampled
// truth than trilinear. llvmpipe has one filter for every level above 1: equal there.
TEST_F(FilteringGl, AnisotropicLevelsAreNoLessSharpAndNoFartherFromTheTruth) {
  if (flt::maxAnisotropy() < 2.0f) GTEST_SKIP() << "no anisotropic filtering on this GL";
  for (const Image& texture : {makeCheckerboard(512, 8), makeTestChart(512)}) {
    const flt::GroundPlane ground(texture);
    const auto trilinear = flt::measureFiltering(ground, mode("trilinear"));
    double sharpness = trilinear.sharpness;
    for (const char* level : {"aniso2", "aniso4", "aniso8", "aniso16"}) {
      const auto m = flt::measureFiltering(ground, mode(level));
      SCOPED_TRACE(::testing::Message() << level << ": sharpness " << m.sharpness << ", error " << m.rmsError
                                        << " (trilinear: " << trilinear.sharpness << ", " << trilinear.rmsError << ")");
      EXPECT_GE(m.sharpness, 0.99 * sharpness) << "less sharp than the level below";
      EXPECT_LE(m.rmsError, 1.01 * trilinear.rmsError) << "farther from the truth than trilinear";
      sharpness = std::max(sharpness, m.sharpness);
    }
  }
}
