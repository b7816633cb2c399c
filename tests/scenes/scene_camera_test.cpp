// The camera hook (FrameInput::camera, what `glint view`'s mouse moves), over the whole
// registry: every variant that draws through a 3D camera asks for it and moves when the
// view is turned; every 2D view (images, NDC geometry, the light's own views) asks for
// none and does not change. Without a moved view, frames are the defined camera's.
#include "glint/core/error.h"
#include "glint/gl/debug.h"
#include "glint/gl/render_target.h"
#include "glint/image/metrics.h"
#include "glint/render/state.h"
#include "glint/scenes/runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

using namespace glint;

namespace {

// Views with no camera to move, named here independently of the scenes' code.
const std::set<std::string> k2dViews = {
    "env/faces/cross", "env/spheremap/image", "env/spheremap/hemispheres", "env/bubble/faces",
    "water/height/rain", "water/height/one-drop", "water/normals/rain", "water/normals/one-drop",
    "bump/object-space/maps", "shadows/map/light-view", "shadows/map/light-depth", "shadows/planar/texture",
};
bool is2d(const scenes::VariantRef& ref) {
  // basics: NDC geometry; post: image processing of a fixed photograph, pattern, frame or camera
  return ref.scene->name.rfind("basics/", 0) == 0 || ref.scene->name.rfind("post/", 0) == 0 ||
         k2dViews.count(ref.fullName()) > 0;
}

// Big enough for rtt's 256² copy-to-texture, small enough to render the registry quickly.
constexpr ivec2 kSize{320, 256};

scenes::ContextPool& contexts() {
  static scenes::ContextPool pool(/*debug=*/true);
  return pool;
}

struct Frame {
  Image image;
  bool askedForCamera = false;
};

Frame renderFrame(scenes::Scene& scene, const scenes::VariantRef& ref, const glint::OrbitControl& view) {
  gl::RenderTarget target(kSize);
  render::resetState();
  // An early time: the camera does not depend on it, and the water scenes simulate up to it.
  const scenes::FrameInput frame{.target = target.target(), .time = std::min(ref.scene->defaultTime, 0.25), .view = view};
  scene.render(frame);
  return {gl::readColor(target.framebuffer(), kSize), frame.definedCamera.has_value()};
}

double differingFraction(const Image& a, const Image& b) {
  return double(compareImages(a, b).differingPixels) / double(a.pixelCount());
}

class SceneCamera : public ::testing::TestWithParam<const scenes::SceneDesc*> {};

std::string testName(const ::testing::TestParamInfo<const scenes::SceneDesc*>& info) {
  std::string name = info.param->name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

std::vector<const scenes::SceneDesc*> allScenes() {
  std::vector<const scenes::SceneDesc*> out;
  for (const auto& s : scenes::Registry::builtin().scenes()) out.push_back(&s);
  return out;
}

}  // namespace

namespace glint::scenes {
// Readable test parameters in ctest's list (the scene's name, not a pointer).
void PrintTo(const SceneDesc* desc, std::ostream* os) { *os << desc->name; }
}  // namespace glint::scenes

TEST_P(SceneCamera, ThreeDViewsMoveWithTheViewAndTwoDViewsDoNot) {
  const scenes::SceneDesc& desc = *GetParam();
  if (!contexts().available(desc.profile)) GTEST_SKIP() << contexts().unavailableReason(desc.profile);
  contexts().use(desc.profile);
  const auto errorsBefore = gl::debugErrorCount();
  glint::OrbitControl turned;
  turned.yaw = 0.5f;
  turned.pitch = 0.15f;
  for (int v = 0; v < int(desc.variants.size()); ++v) {
    const scenes::VariantRef ref{&desc, v};
    SCOPED_TRACE(ref.fullName());
    const auto scene = desc.create(v);
    const Frame defined = renderFrame(*scene, ref, {});
    const Frame moved = renderFrame(*scene, ref, turned);
    const Frame again = renderFrame(*scene, ref, {});
    // The scene draws the same frame twice: what changes below is the view's doing.
    ASSERT_EQ(differingFraction(defined.image, again.image), 0.0);
    if (is2d(ref)) {
      EXPECT_FALSE(defined.askedForCamera) << "a 2D view asked for a camera: the viewer would take its drags";
      EXPECT_EQ(differingFraction(defined.image, moved.image), 0.0) << "a 2D view moved with the camera";
    } else {
      EXPECT_TRUE(defined.askedForCamera && moved.askedForCamera) << "a 3D view did not pass its camera through frame.camera()";
      // Turned by 29° around the target (and 9° up): most of the picture moves.
      EXPECT_GT(differingFraction(defined.image, moved.image), 0.2);
    }
  }
  EXPECT_EQ(gl::debugErrorCount(), errorsBefore) << "GL errors while rendering (see log)";
}

INSTANTIATE_TEST_SUITE_P(Registry, SceneCamera, ::testing::ValuesIn(allScenes()), testName);
