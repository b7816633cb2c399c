// Reference-image tests, one per registered scene variant (a new scene gets its test
// without extra code). Each renders the variant headless at its default size and time
// and compares it with tests/golden/<scene>/<variant>.png.
//
// Tolerance: scenes::checkAgainstReference's (runner.h; `glint gallery --references`
// applies the same). llvmpipe renders the same picture bit for bit on one Mesa build, so
// on a CI machine like this one the difference is exactly zero. The slack (mean channel
// difference ≤ 0.5/255, at most 0.2% of pixels differing by more than 1/255) absorbs
// what legitimately moves between Mesa/LLVM versions — rounding of interpolants on
// edge pixels, SIMD width — while any visible change (a moved edge, a wrong colour, a
// missing object) exceeds it by orders of magnitude.
//
// A variant whose picture GL leaves to the implementation (VariantDesc::implementationDefined:
// anisotropic filtering, whose samples Mesa 22 and Mesa 25 place differently) is held to a
// looser mean (4/255) and no pixel count; tests/filtering checks what GL specifies of it.
//
// On failure the actual image and an amplified difference are written to
// build/test-output/golden/<scene>/<variant>.{actual,diff}.png. Look at them, then
// accept with `scripts/accept-golden [filter]`.
#include "glint/core/error.h"
#include "glint/gl/debug.h"
#include "glint/render/state.h"
#include "glint/scenes/runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;

namespace {
constexpr double kMaxMeanDifference = scenes::ReferenceCheck::kMaxMeanDifference;
constexpr double kMaxDifferingFraction = scenes::ReferenceCheck::kMaxDifferingFraction;

scenes::ContextPool& contexts() {
  static scenes::ContextPool pool(/*debug=*/true);
  return pool;
}

std::string testName(const ::testing::TestParamInfo<scenes::VariantRef>& info) {
  std::string name = info.param.fullName();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class Golden : public ::testing::TestWithParam<scenes::VariantRef> {};
}  // namespace

namespace glint::scenes {
// Readable test parameters in ctest's list ("basics/triangle/color", not bytes).
void PrintTo(const VariantRef& ref, std::ostream* os) { *os << ref.fullName(); }
}  // namespace glint::scenes

TEST_P(Golden, MatchesReference) {
  const auto ref = GetParam();
  if (!contexts().available(ref.scene->profile)) {
    GTEST_SKIP() << "no context for this variant: " << contexts().unavailableReason(ref.scene->profile);
  }
  contexts().use(ref.scene->profile);
  const auto errorsBefore = gl::debugErrorCount(), notableBefore = gl::debugNotableCount();
  const auto result = scenes::renderVariant(ref);
  EXPECT_EQ(gl::debugErrorCount(), errorsBefore) << "GL errors while rendering (see log)";
  // Zero driver messages of medium severity or above too, for every gallery variant.
  EXPECT_EQ(gl::debugNotableCount(), notableBefore) << "GL messages of medium or high severity (see log)";
  // Polite: what PipelineState does not set, the variant put back (render/state.h).
  EXPECT_EQ(render::stateLeftBehind(), std::vector<std::string>{}) << "state the variant did not restore";

  const fs::path golden = fs::path(GLINT_GOLDEN_DIR) / (ref.fullName() + ".png");
  const fs::path outBase = fs::path(GLINT_TEST_OUTPUT_DIR) / "golden" / ref.fullName();
  fs::create_directories(outBase.parent_path());
  const fs::path actualPath = outBase.string() + ".actual.png";
  if (!fs::exists(golden)) {
    saveImage(result.image, actualPath);
    FAIL() << "no reference image " << golden << "; look at " << actualPath
           << " and accept it with scripts/accept-golden " << ref.fullName();
  }
  const Image expected = loadImage(golden);
  ASSERT_EQ(expected.width(), result.image.width());
  ASSERT_EQ(expected.height(), result.image.height());
  const bool implementationDefined = ref.desc().implementationDefined;
  const auto diff = scenes::checkAgainstReference(expected, result.image, implementationDefined);
  const double differingFraction = diff.differingFraction;
  const bool pass = diff.pass;
  if (!pass) {
    saveImage(result.image, actualPath);
    saveImage(diff.visual, outBase.string() + ".diff.png");
  } else {
    fs::remove(actualPath);
  }
  if (implementationDefined) {  // anisotropic filtering: what GL leaves open (runner.h)
    EXPECT_TRUE(pass) << ref.fullName() << " (its sampling is the implementation's): mean difference " << diff.meanAbs * 255.0
                      << "/255 (limit " << scenes::ReferenceCheck::kMaxMeanDifferenceImplementationDefined * 255.0
                      << "); see " << actualPath;
    return;
  }
  EXPECT_TRUE(pass) << ref.fullName() << ": mean difference " << diff.meanAbs * 255.0 << "/255 (limit "
                    << kMaxMeanDifference * 255.0 << "), " << differingFraction * 100.0 << "% pixels differ (limit "
                    << kMaxDifferingFraction * 100.0 << "%), max " << diff.maxAbs * 255.0 << "/255; see "
                    << actualPath;
}

INSTANTIATE_TEST_SUITE_P(Registry, Golden, ::testing::ValuesIn(scenes::Registry::builtin().allVariants()), testName);
