#pragma once
// glint/viewer/viewer.h — the interactive viewer behind `glint view`: a GLFW window with a
// Dear ImGui panel (scenes, variants, options, frame time) over any scene of a registry.
//
// Keys: ←/→ previous/next variant, ↑/↓ previous/next scene, Space pause time, R reload
// shaders, F12 screenshot (shotDir/glint-view-N.png), Tab hide/show the panel, Esc quit;
// other letters and digits go to the scene (Scene::keyPressed). In 3D scenes the mouse
// moves the camera: left drag orbits around its target, right or middle drag pans, the
// wheel zooms, C or Home returns to the scene's own camera (kept across one scene's
// variants, reset on another scene). Shaders are re-read whenever a file under
// gl::ShaderSources::directory() changes, when one is set (hot reload).
//
/// ```cpp
/// glint::viewer::ViewerOptions options;
/// options.scene = "pipedream/full";
/// options.screenshot = "shot.png";  // draw 2 frames, save the window, return
/// const int status = glint::viewer::run(options);
/// ```
//
// Needs a display (under a headless machine: xvfb-run); built with GLINT_BUILD_VIEWER.
#include "glint/core/math.h"
#include "glint/scenes/scene.h"

#include <string>
#include <vector>

namespace glint::viewer {

struct ViewerOptions {
  std::string scene;                  ///< scene or scene/variant to start with; empty: the first
  ivec2 size{1280, 800};              ///< the window, in pixels
  std::string screenshot;             ///< save the window (scene + panel) here after `frames` frames and return
  int frames = 0;                     ///< frames before `screenshot` (at least 2)
  std::string shotDir = ".";          ///< where F12 saves (glint-view-1.png, -2, ...)
  std::vector<std::string> settings;  ///< name=value, set in every scene that has the option
  bool glDebug = false;               ///< the GL debug callback on (glint --gl-debug)
};

/// Opens the window and runs until it is closed (or the screenshot is saved); returns the
/// exit status (0). Error(Usage) for an unknown scene or a shotDir that is not a
/// directory, before the window opens. A scene that fails to load (a shader typo while
/// hot-reloading) is shown as an error in the panel, and the viewer keeps running.
int run(const ViewerOptions& options, const scenes::Registry& registry = scenes::Registry::builtin());

/// The characters of the registry's scene names, summaries and variant descriptions that the
/// panel's font (DejaVu Sans, fonts-dejavu-core) has no glyph for: empty when every one is
/// drawn ("(no font)" when the font file is missing). Needs no window or GL.
std::u32string glyphsMissingFromPanelFont(const scenes::Registry& registry = scenes::Registry::builtin());

}  // namespace glint::viewer
