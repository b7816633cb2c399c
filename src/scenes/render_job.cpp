// `glint render`'s options and its farm plan (scenes/render_job.h).
#include "glint/scenes/render_job.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/text.h"
#include "glint/scenes/scene.h"
#include "glint/video/source.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <sstream>

namespace glint::scenes {

namespace {
constexpr const char* kFooter = R"(Examples:
  glint render basics/triangle/depth -o depth.png
  glint render basics/depth/greater --size 1024x1024 -o greater.png
  glint render pipedream -o clip.mp4 --frames 0:600 --fps 30 --size 640x360
  glint render pipedream -o part1.mkv --codec ffv1 --frames 150:300 --fps 30
  glint post --concat part0.mkv part1.mkv -o whole.mkv
  glint farm render pipedream -o clip.mkv --codec ffv1 --frames 0:600 --chunks 8
  glint render crate.glb -o crate.png --camera 30,20   # a model file (.glb .gltf .obj .ply .fbx)
  glint render crate.glb -o ao.png --set show=2 --set normal-map=false

A model file renders as `glint view FILE` shows it: framed by its bounding sphere, a studio
light rig, its options (`glint view FILE` lists them: normal-map, ao, show, wireframe,
uv-seams, hard-edges, misses, yaw, pitch, zoom) set with --set, the camera with --camera.

Rendering is deterministic: animation follows --time, never the clock. A video (-o .mp4
.mkv .mov .avi .nut) holds frames FIRST..END-1 of --frames, frame i rendered at time
i / --fps (exactly what --time i/fps gives) with timestamp i: parts rendered on several
machines join losslessly with `glint post --concat` (FFV1 parts into the very bytes of one
run; H.264 is written without B-frames, so its parts join too). The video is written
atomically: Ctrl-C (exit 130) or an error leaves no file, and an existing one as it was.)";
}  // namespace

void addOptions(CLI::App& cmd, RenderArgs& args, std::vector<const void*>* videoOnly) {
  cmd.add_option("scene", args.scene, "scene/variant, or scene for its first variant (see `glint list`)")->required();
  cmd.add_option("-o,--output", args.output, "Output image or video; the format follows the extension "
                                             "(default: SCENE-VARIANT.png)");
  cmd.add_option("--size", args.size, "WIDTHxHEIGHT in pixels (default: the scene's own size)");
  cmd.add_option("--time", args.time, "Image: scene time in seconds for animated scenes (default: the scene's own)")
      ->each([&args](const std::string&) { args.timeSet = true; });
  cmd.add_option("--set", args.options, "Scene option as name=value (repeatable; the viewer lists them)");
  cmd.add_option("--camera", args.camera, "A model file's camera: YAW,PITCH[,ZOOM] (degrees around and above the "
                 "model; a factor on the framing distance)");
  const CLI::Option* video[] = {
      cmd.add_option("--frames", args.frames, "Video: frames FIRST:END (END excluded; required), frame i at time i / fps"),
      cmd.add_option("--fps", args.fps, "Video: frames per second")->capture_default_str(),
      cmd.add_option("--codec", args.codec, "Video: h264 (libx264, yuv420p) or ffv1 (lossless RGB)")->capture_default_str(),
      cmd.add_option("--crf", args.crf, "H.264 quality: 0 (lossless) .. 51; 18 is visually lossless")->capture_default_str(),
      cmd.add_option("--preset", args.preset, "H.264 speed/size trade-off: ultrafast .. placebo")->capture_default_str()};
  if (videoOnly)
    for (const CLI::Option* o : video) videoOnly->push_back(o);
}

const char* helpFooter() { return kFooter; }

std::vector<std::string> cameraSettings(const std::string& text, const VariantRef& ref) {
  if (ref.scene->name.rfind("model/", 0) != 0)
    fail(ErrorKind::Usage, "--camera is for a model file (glint render FILE.glb --camera YAW,PITCH[,ZOOM]); {} has its "
         "own camera", ref.fullName());
  std::vector<std::string> parts;
  std::string part;
  for (std::istringstream in(text); std::getline(in, part, ',');) parts.push_back(part);
  if (parts.size() < 2 || parts.size() > 3)
    fail(ErrorKind::Usage, "--camera takes YAW,PITCH or YAW,PITCH,ZOOM (e.g. 30,20), got '{}'", text);
  const char* names[] = {"yaw", "pitch", "zoom"};
  std::vector<std::string> settings;
  for (std::size_t i = 0; i < parts.size(); ++i)
    settings.push_back(fmt::format("{}={}", names[i], parseFloat(parts[i], "--camera")));
  return settings;
}

ClipRequest clipRequest(const RenderArgs& args) {
  if (args.frames.empty()) fail(ErrorKind::Usage, "a video output needs --frames FIRST:END (e.g. --frames 0:300)");
  if (args.timeSet) fail(ErrorKind::Usage, "--time is for an image; in a video frame i is at time i / --fps");
  ClipRequest clip{.frames = parseFrameRange(args.frames, "--frames"), .fps = args.fps, .options = args.options,
                   .codec = video::parseCodec(args.codec), .crf = args.crf, .preset = args.preset};
  const FrameRange range = clip.frames;  // as renderClip says it
  if (range.end < 0) fail(ErrorKind::Usage, "--frames {}: needs an END (FIRST:END, END excluded, e.g. 0:300)", range.first);
  if (range.end <= range.first) {
    fail(ErrorKind::Usage, "--frames {}:{} selects no frame (END is excluded: {}:{} is one frame)", range.first,
         range.end, range.first, range.first + 1);
  }
  if (clip.fps < 1 || clip.fps > 1000) fail(ErrorKind::Usage, "--fps must be 1..1000, got {}", clip.fps);
  if (!args.size.empty()) clip.size = parseSize(args.size);
  if (clip.codec == video::Codec::H264) video::checkPreset(clip.preset);
  return clip;
}

farm::Plan farmPlan(const RenderArgs& args, const farm::Split& split) {
  if (args.output.empty()) fail(ErrorKind::Usage, "farm render: give -o OUT (a video) and --frames A:B");
  const std::string out = farm::absolutePath(args.output);
  if (!video::isVideoPath(out))
    fail(ErrorKind::Usage, "farm render: -o must be a video (.mp4, .mkv, ...), got '{}'", printable(args.output));
  const ClipRequest clip = clipRequest(args);
  const VariantRef ref = Registry::builtin().resolve(args.scene);  // Error(Usage) for an unknown scene
  checkWritable(out);
  farm::Plan plan{.tool = "render"};
  // Rendering is GPU (or llvmpipe) work whose memory the scene decides; 2 GiB holds the
  // Pipe Dream at 1080p on llvmpipe with room to spare.
  plan.memoryMiB = farm::taskMemoryMiB(split, 1640.0);
  plan.title = fmt::format("{} frames {}:{} → {}", ref.fullName(), clip.frames.first, clip.frames.end,
                           std::filesystem::path(out).filename().string());
  plan.outputs = {out};
  std::vector<std::string> common{"render", args.scene, "--fps", std::to_string(clip.fps), "--codec",
                                  video::codecName(clip.codec)};
  if (clip.codec == video::Codec::H264) common.insert(common.end(), {"--crf", std::to_string(clip.crf), "--preset", clip.preset});
  if (!args.size.empty()) common.insert(common.end(), {"--size", fmt::format("{}x{}", clip.size.x, clip.size.y)});
  for (const auto& o : clip.options) common.insert(common.end(), {"--set", o});
  const std::string extension = std::filesystem::path(out).extension().string();
  for (const auto& [a, b] : farm::splitEvenly(clip.frames.first, clip.frames.end, split.pieces)) {
    farm::Piece piece{.label = fmt::format("frames {}:{}", a, b), .command = common, .extension = extension};
    piece.command.insert(piece.command.end(), {"--frames", fmt::format("{}:{}", a, b), "-o", farm::kPieceOutput});
    plan.pieces.push_back(std::move(piece));
  }
  plan.join = {"post", "--concat", farm::kAllPieceOutputs, "-o", out};
  return plan;
}

}  // namespace glint::scenes
