#pragma once
// glint/scenes/clip.h — a variant's animation to a video file: `glint render SCENE -o
// clip.mp4 --frames FIRST:END --fps F`, as a library call.
//
/// ```cpp
/// glint::scenes::ContextPool contexts;
/// const glint::scenes::VariantRef ref = glint::scenes::Registry::builtin().resolve("pipedream");
/// contexts.use(ref.scene->profile);
/// glint::scenes::ClipRequest clip;
/// clip.frames = {0, 300};  // frames 0..299: ten seconds at 30 fps
/// clip.size = {960, 540};
/// glint::ToolRun run("render", {});  // Ctrl-C, phases
/// const glint::scenes::ClipStats stats = glint::scenes::renderClip(ref, clip, "pipedream.mp4", run);
/// ```
//
// Time. Frame i is the picture at scene time i / fps exactly — VariantRenderer::frame, the
// picture `glint render SCENE --time i/fps -o frame.png` gives — never the wall clock. Its
// timestamp is i in the time base 1/fps, as `glint post --frames` writes its parts. So a
// clip can be split over machines and joined with `glint post --concat`, by copying packets:
//
//   glint render pipedream -o a.mkv --codec ffv1 --frames 0:150
//   glint render pipedream -o b.mkv --codec ffv1 --frames 150:300
//   glint post --concat a.mkv b.mkv -o whole.mkv
//
// For FFV1 (every frame a keyframe) whole.mkv is byte for byte the file one run with
// --frames 0:300 writes (tests/scenes/render_clip_test.cpp).
// H.264 clips are always written without B-frames (any clip may be a part): the joined
// video has every frame, in time.
//
// Output. The sink (video/sink.h) writes a temporary file beside the destination and renames
// it into place only when the last frame is in: an error or Ctrl-C (run's cancel flag,
// polled between frames) leaves no file and an existing one as it was, and throws
// Error(Interrupted) (exit 130). Unlike `glint post`, which finishes a playable partial
// video when interrupted: a part missing its end frames would not join the next one, and a
// render can always be run again.
//
// Progress: a bar with the frame rate (core/progress.h, silent without a terminal or with
// -q); the run's phases are "open" (sink, scene), "render" (drawing and reading back) and
// "encode" (the sink, its trailer included).

#include "glint/core/text.h"
#include "glint/core/tool.h"
#include "glint/scenes/runner.h"
#include "glint/video/sink.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint::scenes {

struct ClipRequest {
  FrameRange frames{0, 0};          ///< frames [first, end), end > first (`--frames FIRST:END`)
  int fps = 30;                     ///< frames per second, 1..1000: frame i is at i / fps seconds
  ivec2 size{0};                    ///< 0: the scene's default size (even for H.264)
  std::vector<std::string> options;  ///< "name=value" scene options (--set)
  video::Codec codec = video::Codec::H264;
  int crf = 18;                     ///< H.264 quality, 0..51
  std::string preset = "medium";    ///< H.264 speed/size trade-off (x264's presets)
  int threads = 0;                  ///< encoder threads; 0: FFmpeg's choice
};

/// What renderClip did: the command's one-line report.
struct ClipStats {
  std::string scene;        ///< "group/name/variant"
  std::string output;
  ivec2 size{0};
  FrameRange frames;
  int fps = 0;
  std::string codec;        ///< "h264" or "ffv1"
  std::int64_t framesWritten = 0;
  double seconds = 0;       ///< wall time, scene creation and encoding included
  double renderSeconds = 0;  ///< drawing and reading back
  double encodeSeconds = 0;  ///< the sink
  std::string notes;        ///< Scene::notes() after the last frame
};

/// Renders frames clip.frames of `variant` into the video `output` (its container from the
/// extension: .mp4 .mkv .mov for H.264, .mkv .avi .nut for FFV1). Needs a current context of
/// the scene's profile (ContextPool::use). Checks before any frame: the range selects frames
/// and the rate is in range (Error(Usage)); the sink then refuses what cannot be written
/// (Error(Usage): a container that cannot hold the codec, an odd size for H.264, a --crf or
/// --preset out of range; Error(Output): an unwritable destination) before the scene is made.
ClipStats renderClip(const VariantRef& variant, const ClipRequest& clip, const std::filesystem::path& output,
                     ToolRun& run);

}  // namespace glint::scenes
