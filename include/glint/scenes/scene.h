#pragma once
// glint/scenes/scene.h — the spine of glint: scenes, variants, options, the registry.
//
// Every technique is shown through a scene with named variants ("shadows/zfail").
// One registry feeds every front end: `glint render`, `glint gallery`, `glint view`,
// the reference-image tests and the benchmarks. Writing a scene once gives it all
// of those.
//
// Adding a scene
//   1. Write a class deriving from Scene in src/scenes/<group>/<name>.cpp; its
//      constructor creates its GL objects for one variant; render() draws a frame.
//   2. Describe it with a SceneDesc (name, one-line summary, variants each with a
//      line on what it shows) and add it in that file's register function, listed in
//      src/scenes/registry.cpp.
//   3. Add the .cpp to glint_scenes in src/scenes/CMakeLists.txt (sources are listed
//      explicitly); its shaders under shaders/<technique>/ are embedded automatically.
//   4. Render it (`glint render group/name/variant -o x.png`), look at it, and accept
//      its reference images (README, "Tests"): every variant gets a golden test.
//
// Rules for scenes
//   - Deterministic: everything animated is a function of FrameInput::time, never
//     the wall clock, so `--time 1.5` always gives the same picture.
//   - Draw into FrameInput::target, at its size; set all state you rely on.
//   - A 3D scene passes its camera through FrameInput::camera() once per frame, so the
//     viewer's mouse can move it; 2D views (images, NDC geometry) do not call it.
//   - Options are data (Option), so the viewer shows them as widgets and the CLI
//     sets them with `--set name=value`.

#include "glint/core/math.h"
#include "glint/gl/context.h"
#include "glint/gl/render_target.h"
#include "glint/core/camera.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace glint::scenes {

struct FrameInput {
  gl::Target target;     ///< where to draw, and its size
  double time = 0.0;     ///< seconds since the scene started; drives all animation
  double deltaTime = 0;  ///< seconds since the previous frame (0 for a single headless frame)
  glint::OrbitControl view{};  ///< the viewer user's orbit, pan and zoom; the identity everywhere else

  /// The scene's own camera as the user moved it: `view.apply(defined)`, which is `defined`
  /// itself in headless renders. Call it once per frame with the camera the scene defines
  /// (before Camera::cropped for split screens):
  ///
  /// ```cpp
  /// const glint::scenes::FrameInput frame{};  // what Scene::render receives
  /// const glint::Camera camera =
  ///     frame.camera(glint::Camera::orbit({0, 0, 0}, 3.0f, 0.0f, 0.35f, 45.0f, frame.target.aspect()));
  /// ```
  glint::Camera camera(const glint::Camera& defined) const {
    definedCamera = defined;
    return view.apply(defined);
  }
  /// Set by camera(): the camera the scene defined this frame. Empty after a frame of a
  /// 2D view — the viewer then leaves the mouse alone.
  mutable std::optional<glint::Camera> definedCamera;
};

/// A tweakable parameter a scene exposes. `value` points into the scene.
struct Option {
  std::string name;         ///< identifier for --set, e.g. "light-height"
  std::string description;  ///< one line for tooltips and --help
  std::variant<float*, int*, bool*, std::string*> value;  ///< a string is a text field (a file, a device)
  float min = 0.0f;  ///< slider range for float and int options
  float max = 1.0f;
  /// A key for the viewer (an uppercase letter or a digit, e.g. 'B'): it toggles a bool
  /// option and steps an int option through min..max (wrapping), as the sources' demos
  /// switched effects on keys. 0: none. R is the viewer's (reload).
  char key = 0;
};

class Scene {
public:
  virtual ~Scene() = default;
  /// Draws one frame.
  virtual void render(const FrameInput& frame) = 0;
  /// Parameters shown in the viewer and settable with --set.
  virtual std::vector<Option> options() { return {}; }
  /// Extra text the gallery and viewer show under the picture (measurements, notes).
  virtual std::string notes() const { return {}; }
  /// A key the viewer does not use itself ('A'..'Z' other than C and R, '0'..'9'; GLFW's
  /// key codes for them are these characters): true when the scene used it. The default
  /// toggles or steps the option whose Option::key it is (post/camera's effects); scenes
  /// with a demo's own keys (pipedream: the talk's toggles) override it and switch views
  /// without a reload, falling back to Scene::keyPressed for their options.
  virtual bool keyPressed(int key);
};

struct VariantDesc {
  std::string name;         ///< e.g. "depth"
  std::string description;  ///< one line: what this variant shows
  /// Its picture depends on what GL leaves to the implementation (anisotropic filtering's
  /// sample count and placement, GL 4.6 §8.14.3.1): its reference image is checked with
  /// ReferenceCheck's looser tolerance for such pictures, and what GL does specify is tested
  /// apart (tests/filtering: sharper and closer to the truth than trilinear, no less sharp
  /// with each level, trilinear where the footprint is square).
  bool implementationDefined = false;
};

struct SceneDesc {
  std::string name;      ///< e.g. "basics/triangle" (group/name)
  std::string summary;   ///< one line: the technique and which source describes it (docs/sources.md)
  std::vector<VariantDesc> variants;
  gl::Profile profile = gl::Profile::Core;  ///< Compatibility: needs a compatibility context
  /// Reads its frames through the video module (FFmpeg): post/camera, whose default input is
  /// an FFmpeg test pattern. `glint gallery` skips it, marked, where the module cannot load.
  bool needsVideo = false;
  ivec2 defaultSize{640, 360};
  double defaultTime = 0.0;                 ///< time rendered when --time is not given
  /// Builds the scene for variants[variant]. Called with a current context of `profile`.
  std::function<std::unique_ptr<Scene>(int variant)> create;
};

/// A resolved "scene/variant" name.
struct VariantRef {
  const SceneDesc* scene = nullptr;
  int variant = 0;
  std::string fullName() const { return scene->name + "/" + scene->variants[std::size_t(variant)].name; }
  const VariantDesc& desc() const { return scene->variants[std::size_t(variant)]; }
};

class Registry {
public:
  /// The registry with every built-in scene.
  static const Registry& builtin();

  void add(SceneDesc desc);
  const std::vector<SceneDesc>& scenes() const { return m_scenes; }
  /// Every scene/variant in registration order.
  std::vector<VariantRef> allVariants() const;
  /// Resolves "group/name/variant" or "group/name" (first variant). Error(Usage) listing
  /// close names when unknown.
  VariantRef resolve(const std::string& name) const;
  /// Variants whose full name contains `filter` (all when empty).
  std::vector<VariantRef> match(const std::string& filter) const;

private:
  std::vector<SceneDesc> m_scenes;
};

/// Applies "name=value" to a scene's options. Error(Usage) for unknown names or bad values.
void setOption(Scene& scene, const std::string& assignment);

}  // namespace glint::scenes
