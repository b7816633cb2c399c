// The post/* scenes through the registry, as `glint render` and the viewer run them: the
// camera scene shows the source's frame at the requested time, through the effect; the
// before/after split puts the original left of the divider; keys step the options; the
// panel's options come from the effect table; a missing camera is a one-line error.
#include "glint/core/error.h"
#include "glint/image/post.h"
#include "glint/render/post/effects.h"
#include "glint/scenes/runner.h"
#include "glint/video/source.h"

#include "post_test_util.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <variant>

using namespace glint;
using glint::testing::compareSteps;
using glint::testing::crop;

namespace {
scenes::ContextPool& contexts() {
  static scenes::ContextPool pool(/*debug=*/true);
  pool.use(gl::Profile::Core);
  return pool;
}

// The lavfi frame with this index, as the scene's default input gives it.
Image patternFrame(int index) {
  video::Source source = video::Source::open("lavfi:testsrc2=size=640x480:rate=30");
  video::Frame frame;
  for (int i = 0; i <= index; ++i) EXPECT_TRUE(source.read(frame));
  return frame.image;
}
}  // namespace

TEST(PostScenes, CameraShowsTheFrameAtTheRequestedTime) {
  contexts();
  const auto ref = scenes::Registry::builtin().resolve("post/camera/sepia");
  // 640×480 target = the frame's size: no letterbox, pixels map 1:1.
  for (const auto& [time, index] : {std::pair{0.0, 0}, std::pair{1.0, 30}, std::pair{2.51, 75}}) {
    const auto result = scenes::renderVariant(ref, {.size = {640, 480}, .time = time});
    EXPECT_LE(compareSteps(result.image, sepiaReference(patternFrame(index))).maxSteps, 1) << "time " << time;
  }
}

TEST(PostScenes, BeforeAfterSplitShowsTheOriginalOnTheLeft) {
  contexts();
  const auto ref = scenes::Registry::builtin().resolve("post/camera/edges");
  const auto split = scenes::renderVariant(ref, {.size = {640, 480}, .options = {"before-after=1", "divider=0.5"}});
  const Image original = patternFrame(0);
  const Image edges = sobelReference(original);
  EXPECT_LE(compareSteps(crop(split.image, 0, 0, 300, 480), crop(original, 0, 0, 300, 480)).maxSteps, 1);
  EXPECT_LE(compareSteps(crop(split.image, 340, 0, 300, 480), crop(edges, 340, 0, 300, 480)).maxSteps, 1);
  // The effect option switches the chain without a new variant: 0 is no effect.
  const auto none = scenes::renderVariant(ref, {.size = {640, 480}, .options = {"effect=0"}});
  EXPECT_EQ(compareSteps(none.image, original).maxSteps, 0);
}

TEST(PostScenes, OptionsHaveKeysAndMissingCamerasAreOneLineErrors) {
  contexts();
  const auto ref = scenes::Registry::builtin().resolve("post/camera/sepia");
  auto scene = ref.scene->create(ref.variant);
  bool effectKey = false, splitKey = false;
  for (const auto& o : scene->options()) {
    effectKey |= o.name == "effect" && o.key == 'E';
    splitKey |= o.name == "before-after" && o.key == 'B';
  }
  EXPECT_TRUE(effectKey);
  EXPECT_TRUE(splitKey);
  try {
    scenes::renderVariant(ref, {.options = {"input=/dev/video-none"}});
    ADD_FAILURE() << "no error for a missing camera";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("/dev/video-none"), std::string::npos) << e.what();
  }
}

TEST(PostScenes, ThePanelComesFromTheEffectTable) {
  contexts();
  // post/photo/posterize: kuwahara then edges; every parameter of both, with the table's
  // slider ranges, pointing at the chain's values (an int for an Int parameter).
  const auto ref = scenes::Registry::builtin().resolve("post/photo/posterize");
  auto scene = ref.scene->create(ref.variant);
  const auto options = scene->options();
  std::size_t found = 0;
  for (const char* effect : {"kuwahara", "edges"}) {
    for (const auto& p : render::post::findEffect(effect)->params) {
      for (const auto& o : options) {
        if (o.name != p.name) continue;
        ++found;
        EXPECT_EQ(o.min, p.sliderMin) << p.name;
        EXPECT_EQ(o.max, p.sliderMax) << p.name;
        EXPECT_EQ(std::holds_alternative<int*>(o.value), p.type != render::post::ParamType::Float) << p.name;
      }
    }
  }
  EXPECT_EQ(found, 3u) << "size, scale, threshold";
  scenes::setOption(*scene, "threshold=0.5");
  EXPECT_NE(scene->notes().find("edges(scale=2,threshold=0.5)"), std::string::npos) << scene->notes();
}
