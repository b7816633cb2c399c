#pragma once
// glint/post/job.h — `glint post` as a library call: one job (an image, every frame
// of a video, a camera or a lavfi source through an effect chain, or --frames parts joined),
// with the command's checks, memory estimate, warnings and report. The command parses its
// options into a PostJob and calls runJob and finishJob; so can any program (library
// glint::post: GL-free; its GPU backend comes from glint::scenes, scenes/post_gpu.h, and is
// handed to runJob: a program without it runs the effects on the CPU).
//
/// ```cpp
/// glint::post::PostJob job;
/// job.input = "photo.png";
/// job.output = "npr.png";
/// const std::vector<std::string> specs = {"posterize"};
/// job.effects = glint::post::parseEffects(specs);
/// glint::ToolSettings settings;
/// settings.json = "report.json";
/// glint::ToolRun run("post", settings);
/// const glint::post::PostStats stats = glint::post::runJob(job, run);  // the CPU backend (no GPU given)
/// glint::post::finishJob(stats, run);  // writes report.json; returns the exit status
/// ```
//
// Checks, before anything is opened: one input (input, camera, lavfi or parts), an output,
// camera options only for a camera, a --frames range that selects frames, an image output
// for an image input, outputs (and the --json report) writable; then, once the size is known,
// the memory estimate against --max-memory, the GPU's largest texture, and each effect at the
// frame size (post/effects.h). Errors are glint::Error, one line (core/error.h).

#include "glint/core/math.h"
#include "glint/core/text.h"
#include "glint/core/tool.h"
#include "glint/post/cpu.h"
#include "glint/post/effects.h"
#include "glint/post/gpu_backend.h"
#include "glint/video/sink.h"
#include "glint/video/transcode.h"

#include "glint/farm/farm.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace glint::post {

/// Where a job's frames come from: decided once, by inputKind().
enum class InputKind {
  Image,   ///< a still image file (video::isImagePath)
  Video,   ///< any other file: FFmpeg decodes it
  Camera,  ///< a V4L2 device: a live source
  Lavfi,   ///< an FFmpeg filter graph, "lavfi:GRAPH"
  Parts    ///< finished --frames parts, joined by copying packets (no effects)
};

/// Frames [first, end) of a video (`--frames first:end`, core/text.h's parseFrameRange);
/// end −1: to the end.
using FrameRange = glint::FrameRange;

struct PostJob {
  std::string input;               ///< an image or video file, or "lavfi:GRAPH"
  std::string camera;              ///< instead of input: a V4L2 device ("/dev/video0")
  std::string lavfi;               ///< instead of input: "lavfi:GRAPH" (`--input`)
  std::vector<std::string> parts;  ///< instead of input and effects: parts to join, in order
  std::string output;              ///< an image or a video; the format from its extension; "-": stdout
  /// The format of "-" (stdout): an image extension (png, jpg, ...; the default, PNG) or a
  /// streamable container (mkv, nut, ts). Input "-" (stdin) is read as an image when the
  /// output is one, else as a video stream.
  std::string format;
  std::vector<Effect> effects;     ///< in chain order (parseEffects)
  video::Codec codec = video::Codec::H264;
  int crf = 18;                    ///< H.264 quality, 0..51
  std::string preset = "medium";   ///< H.264 speed/size trade-off
  std::optional<FrameRange> frames;  ///< a part of a video (written without B-frames, to join)
  std::optional<ivec2> cameraSize;   ///< camera: the size to ask for (none: the device's default)
  std::optional<double> cameraRate;  ///< camera: the frame rate to ask for, positive
  bool realtime = false;           ///< pace a file or lavfi source and treat it as live
  bool keepAudio = true;           ///< copy the input's audio when the output can hold it
  /// Turn a rotated video's frames upright (its display matrix) instead of keeping the
  /// matrix on the output. Done anyway for an image output and for a container that cannot
  /// hold the matrix (only MP4 and MOV can), and said.
  bool applyRotation = false;
  /// Channels of an image written: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA; 0: the input's
  /// (a video's frames are RGB), in colour when the effects turn a grey input into colour.
  int channels = 0;
  bool glDebug = false;            ///< a GL debug context
  /// Where the effects run (post/cpu.h): auto picks the CPU on a software GL
  /// renderer (llvmpipe) when it has every effect of the chain.
  Backend backend = Backend::Auto;
};

/// `glint post`'s options as typed (the command, `glint farm post` and the Python module
/// bind them with addOptions and make the job with makeJob).
struct PostArgs {
  std::string input, output, format, camera, lavfi, codec = "h264", preset = "medium", frames, size, rate,
      backend = "auto";
  std::vector<std::string> effects, settings, concat;
  int crf = 18, channels = 0;
  bool realtime = false, noAudio = false, listEffects = false, applyRotation = false;
};

/// The options of `glint post` (the tool options are addToolOptions'), bound to `args`.
void addOptions(CLI::App& command, PostArgs& args);
/// `glint post --help`'s footer: examples, inputs and outputs, backends, exit codes.
std::string helpFooter();
/// The job the options describe (parsed: effects, codec, frames, camera size and rate).
/// Error(Usage) for a bad value.
PostJob makeJob(const PostArgs& args, bool glDebug = false);
/// The job as `glint post` arguments (every effect with all its parameters: Effect::spec).
std::vector<std::string> arguments(const PostJob& job);

/// The checks that need nothing opened (the list at the top of this header): Error(Usage)
/// or Error(Output), one line. runJob makes them first; so does farmPlan.
void checkJob(const PostJob& job, const ToolSettings& settings);

/// A video job split into `split.pieces` chunks of frames starting on keyframes (`glint post
/// --frames a:b`, each decodable on its own) and their join (`glint post --concat`): the
/// command's checks first, then a video file every node can read (no camera, lavfi source,
/// stdin or image). Reads the file's index for the keyframes.
farm::Plan farmPlan(const PostJob& job, const ToolSettings& settings, const farm::Split& split);

/// The one place the kind of input is worked out (after the one-input check).
InputKind inputKind(const PostJob& job);
/// Whether the job writes an image (by -o's extension, or --format for "-").
bool imageOutput(const PostJob& job);

/// Peak memory of processing frames of `size`, in MiB: measured with posterize on llvmpipe
/// (GL textures are process memory there): ~150 MiB, plus ~280 bytes per pixel for a video
/// (frames in flight, float targets, the encoder), ~45 for a single frame.
double estimatePeakMemoryMiB(ivec2 size, bool singleFrame);

/// What a job did; toJson() is the command's report (the fields beside ToolRun's own).
struct PostStats {
  InputKind kind = InputKind::Image;
  bool still = false;              ///< a video source, an image output: one frame processed
  std::string input;               ///< the file, device or graph
  std::string output;
  std::vector<std::string> parts;  ///< Parts: the joined files
  ivec2 size{0};
  double frameRate = 0.0;
  std::string codec;               ///< "h264" or "ffv1"
  std::string effects;             ///< Chain::describe()
  std::string backend;             ///< "cpu" or "gpu": where the effects ran (not in toJson)
  bool live = false;
  std::int64_t frame = 0;          ///< still: the frame's index
  std::int64_t firstFrame = 0;
  std::int64_t framesRead = 0;
  std::int64_t framesWritten = 0;
  std::int64_t framesExpected = -1;  ///< what the container announces for the range; −1: unknown
  std::int64_t droppedFrames = 0;
  std::int64_t corruptPackets = 0;
  std::int64_t decoderErrors = 0;
  std::string audio;               ///< "none", "copied", "dropped", "dropped (--no-audio)"
  std::int64_t audioPackets = 0;
  int rotation = 0;                ///< the input's display rotation, degrees counterclockwise (0: none)
  bool rotationApplied = false;    ///< the frames were turned upright (else the rotation was kept on the output)
  double fps = 0.0;
  double seconds = 0.0;            ///< wall time of the video pipeline
  bool interrupted = false;        ///< stopped by Ctrl-C: the video is complete up to there
  std::optional<std::string> inputError;  ///< the source broke off: the video is complete up to there

  bool partial() const { return interrupted || inputError.has_value(); }
  /// The report's fields for this kind of job, in the command's order: an image gives
  /// effects, input, output, width, height, frames; a still input, output, frame, effects;
  /// parts parts, output, frames; a video input … interrupted (and input_error).
  nlohmann::ordered_json toJson() const;
};

/// Runs the job: the checks above, then the work, with phases, progress and warnings on
/// `run` (its cancel flag stops a video cleanly: a playable partial video; an image is then
/// not written, Error(Interrupted)). `gpu`: the GPU backend (scenes/post_gpu.h's
/// postGpuBackend()), which makes its own headless context when used; null: the CPU only
/// (--backend gpu is then a usage error).
PostStats runJob(const PostJob& job, ToolRun& run, GpuBackend* gpu = nullptr);

/// One image through the job's effects in memory, as `glint post IMAGE -o OUT` processes the
/// image it loaded (the Python module's glint.post on arrays): `input` as loadImage gives one
/// (U8, U16 or F32; 1 to 4 channels; F32 is linear light), the result as the command saves
/// it (8-bit, the input's channels or job.channels; F32 when job.output names a float
/// format). Only job.effects, backend, channels, glDebug and output's format are used; no
/// file is read or written. `stats` gets the image job's fields.
Image processImage(const PostJob& job, Image input, ToolRun& run, GpuBackend* gpu, PostStats& stats);

/// Adds stats.toJson() to the report and finishes it (ToolRun::finish writes --json); then
/// Error(Input) when the source broke off, and the exit status: 0, or 130 when interrupted.
int finishJob(const PostStats& stats, ToolRun& run);

}  // namespace glint::post
