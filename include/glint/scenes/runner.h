#pragma once
// glint/scenes/runner.h — rendering registry variants headless: the one code path
// behind `glint render`, `glint gallery`, the reference-image tests and benchmarks.
//
/// ```cpp
/// glint::scenes::ContextPool contexts(/*debug=*/true);  // GL errors logged and counted
/// const glint::scenes::VariantRef ref = glint::scenes::Registry::builtin().resolve("basics/triangle/depth");
/// contexts.use(ref.scene->profile);
/// const glint::scenes::RenderResult result = glint::scenes::renderVariant(ref, {.size = {500, 500}});
/// glint::saveImage(result.image, "depth.png");
/// ```

#include "glint/gl/context.h"
#include "glint/image/image.h"
#include "glint/scenes/scene.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint::scenes {

/// Headless contexts by profile, created on first use. A profile the driver lacks
/// is remembered as unavailable (available() → false) rather than retried.
class ContextPool {
public:
  explicit ContextPool(bool debug = false) : m_debug(debug) {}
  /// Makes a context of `profile` current, creating it first. Error(NoGpu) when impossible.
  void use(gl::Profile profile);
  /// Whether a context of `profile` exists or can be created (creates it).
  bool available(gl::Profile profile);
  /// Why `profile` is unavailable (empty when it is available or untried).
  std::string unavailableReason(gl::Profile profile) const;

private:
  bool m_debug;
  std::map<gl::Profile, std::unique_ptr<gl::HeadlessContext>> m_contexts;
  std::map<gl::Profile, std::string> m_failures;
};

struct RenderRequest {
  ivec2 size{0};                       ///< 0 = the scene's default size
  std::optional<double> time;          ///< unset = the scene's default time
  std::vector<std::string> options;    ///< "name=value" assignments (--set)
  int timingRepeats = 0;               ///< > 0: also measure GPU and CPU time per frame
};

struct RenderResult {
  Image image;        ///< RGBA8, top row first
  double gpuMs = -1;  ///< median GPU time of one frame (GL_TIME_ELAPSED), when measured
  double cpuMs = -1;  ///< median wall time of one frame including glFinish, when measured
  std::string notes;  ///< Scene::notes() after rendering
};

/// Creates the variant's scene, applies options, renders one frame at the requested
/// time into an offscreen target and reads it back. Needs a current context of the
/// scene's profile (ContextPool::use). VariantRenderer, below, with one frame.
RenderResult renderVariant(const VariantRef& variant, const RenderRequest& request = {});

/// One variant's scene, created once, rendered at as many times as asked: the frames of a
/// clip (scenes/clip.h). Scenes are deterministic (scene.h), so frame(t) is the picture
/// renderVariant gives for --time t, whatever was rendered before — a scene that keeps state
/// between frames (water's simulation) keeps it only to go faster. Every frame is rendered
/// as a single headless frame: state reset first, deltaTime 0, the scene's own camera.
///
/// ```cpp
/// glint::scenes::ContextPool contexts;
/// const glint::scenes::VariantRef ref = glint::scenes::Registry::builtin().resolve("rtt/texture");
/// contexts.use(ref.scene->profile);
/// glint::scenes::VariantRenderer renderer(ref, {.size = {320, 180}});  // request.time unused
/// for (int i = 0; i < 30; ++i) glint::saveImage(renderer.frame(i / 30.0).image, "f" + std::to_string(i) + ".png");
/// ```
class VariantRenderer {
public:
  /// Creates the scene (current context of its profile needed) and applies request.options;
  /// Error(Usage) for a bad option. request.size 0: the scene's default size.
  VariantRenderer(const VariantRef& variant, const RenderRequest& request);
  ~VariantRenderer();
  VariantRenderer(const VariantRenderer&) = delete;
  VariantRenderer& operator=(const VariantRenderer&) = delete;

  /// Renders the frame at `time` seconds (finite; Error(Usage) otherwise) and reads it back:
  /// RGBA8, opaque. timingRepeats > 0 also measures GPU and CPU time (RenderResult).
  RenderResult frame(double time, int timingRepeats = 0);
  ivec2 size() const { return m_size; }

private:
  VariantRef m_ref;
  ivec2 m_size;
  std::unique_ptr<Scene> m_scene;
  std::unique_ptr<gl::RenderTarget> m_target;
};

/// A rendered variant against its reference image (tests/golden/<scene>/<variant>.png).
/// The tolerance is the reference-image tests': the mean channel difference at most
/// 0.5/255, and at most 0.2 % of the pixels differing by more than 1/255. llvmpipe renders
/// the same picture bit for bit on one Mesa build; the slack absorbs what legitimately
/// moves between Mesa/LLVM versions (interpolant rounding on edge pixels, SIMD width),
/// while a visible change (a moved edge, a wrong colour, a missing object) exceeds it by
/// orders of magnitude. Another GL (a GPU's) may also differ where GL allows it to
/// (anisotropic filtering, derivatives): the figures say by how much.
struct ReferenceCheck {
  static constexpr double kMaxMeanDifference = 0.5 / 255.0;
  static constexpr double kMaxDifferingFraction = 0.002;
  /// For a variant whose picture GL leaves to the implementation (VariantDesc::
  /// implementationDefined: anisotropic filtering): the mean channel difference at most
  /// 4/255, any number of pixels. Mesa 25's llvmpipe places its anisotropic samples
  /// otherwise than Mesa 22's: mean 2.0/255 over 17.7 % of the pixels of filtering/*/aniso*,
  /// where a missing texture or a wrong filter mode moves the mean by 20/255 and more.
  static constexpr double kMaxMeanDifferenceImplementationDefined = 4.0 / 255.0;
  double meanAbs = 0;            ///< mean absolute channel difference, 0..1
  double maxAbs = 0;             ///< largest channel difference, 0..1
  double differingFraction = 0;  ///< pixels differing by more than 1/255, 0..1
  bool pass = false;             ///< within the tolerance above
  Image visual;                  ///< |difference| × 8 per pixel, for eyes
};

/// Compares `actual` with `reference` (equal sizes; Error(Usage) otherwise); with
/// `implementationDefined` (the variant's VariantDesc flag) at that tolerance.
ReferenceCheck checkAgainstReference(const Image& reference, const Image& actual, bool implementationDefined = false);

}  // namespace glint::scenes
