#pragma once
// glint/scenes/render_job.h — `glint render`'s options and its farm plan: one variant to an
// image, or its animation to a video (scenes/clip.h), split over machines by frame ranges
// that `glint post --concat` joins into the bytes of one run (FFV1).
//
/// ```cpp
/// glint::scenes::RenderArgs args;
/// args.scene = "pipedream";
/// args.output = "/shared/pipedream.mkv";
/// args.frames = "0:600";
/// args.codec = "ffv1";
/// glint::farm::Split split;
/// split.pieces = 8;
/// const glint::farm::Plan plan = glint::scenes::farmPlan(args, split);  // 8 x `glint render --frames a:b`, then the concat
/// ```
#include "glint/core/tool.h"
#include "glint/farm/farm.h"
#include "glint/scenes/clip.h"

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace glint::scenes {

/// `glint render`'s options as typed.
struct RenderArgs {
  std::string scene;                 ///< "scene/variant", or a scene for its first variant
  std::string output;                ///< an image or a video; empty: SCENE-VARIANT.png
  std::string size;                  ///< WIDTHxHEIGHT; empty: the scene's own
  double time = 0;
  bool timeSet = false;              ///< --time was given (an image's scene time)
  std::vector<std::string> options;  ///< --set name=value
  std::string camera;                ///< --camera YAW,PITCH[,ZOOM]: a model file's camera (scenes/model.h)
  std::string frames, codec = "h264", preset = "medium";
  int fps = 30, crf = 18;
};

/// The options of `glint render`, bound to `args` (`videoOnly`, when given, receives the
/// options that only a video takes, so the command can refuse them for an image).
void addOptions(CLI::App& command, RenderArgs& args, std::vector<const void*>* videoOnly = nullptr);
/// `glint render --help`'s footer.
const char* helpFooter();

/// --camera YAW,PITCH[,ZOOM] as the model scene's --set settings ("yaw=30", ...).
/// Error(Usage) for another scene or a malformed value.
std::vector<std::string> cameraSettings(const std::string& text, const VariantRef& ref);
/// The clip the options describe for a video output: --frames FIRST:END required, no
/// --time, the codec and preset checked. Error(Usage) naming the option.
ClipRequest clipRequest(const RenderArgs& args);

/// The animation split into `split.pieces` even frame ranges (`glint render --frames a:b`)
/// and their join (`glint post --concat`), after the command's checks (a known scene, a
/// video output in a writable folder, a clip request as clipRequest checks it).
farm::Plan farmPlan(const RenderArgs& args, const farm::Split& split);

}  // namespace glint::scenes
