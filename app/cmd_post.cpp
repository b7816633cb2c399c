// glint post IN -o OUT -e EFFECT... — seed 001's post-processing on an image, every frame of
// a video, a camera or an FFmpeg lavfi source. Thin: options → a render::post::PostJob, run
// and reported by the library (render/post/job.h).
#include "common.h"

#include "glint/core/error.h"
#include "glint/render/post/job.h"

#include <fmt/format.h>

namespace glint::app {

namespace {

struct PostArgs {
  std::string input, output, format, camera, lavfi, codec = "h264", preset = "medium", frames, size, rate,
      backend = "auto";
  std::vector<std::string> effects, settings, concat;
  int crf = 18, channels = 0;
  bool realtime = false, noAudio = false, listEffects = false;
  ToolSettings tool;
};

/// The job the options describe (parsed: effects, codec, frames, camera size and rate).
render::post::PostJob makeJob(const PostArgs& a, const GlobalOptions& global) {
  render::post::PostJob job{.input = a.input, .camera = a.camera, .lavfi = a.lavfi, .parts = a.concat,
                            .output = a.output, .crf = a.crf, .preset = a.preset, .realtime = a.realtime,
                            .keepAudio = !a.noAudio, .channels = a.channels, .glDebug = global.glDebug};
  job.format = a.format;
  job.effects = render::post::parseEffects(a.effects, a.settings);
  job.codec = video::parseCodec(a.codec);
  job.backend = render::post::parseBackend(a.backend);
  if (!a.frames.empty()) job.frames = parseFrameRange(a.frames, "--frames");
  if (!a.size.empty()) job.cameraSize = parseSize(a.size);
  if (!a.rate.empty()) job.cameraRate = parseFloat(a.rate, "--fps");
  return job;
}

constexpr const char* kPostFooter = R"(Examples:
  glint post photo.jpg -o sepia.png -e sepia
  glint post street.png -o npr.png -e posterize --set size=4
  glint post clip.mp4 -o clip-edges.mp4 -e kuwahara -e edges
  glint post clip.mp4 -o part2.mkv --codec ffv1 --frames 250:500 -e sepia:i=0.25
  glint post clip.mp4 -o sepia.mp4 -e sepia --backend cpu
  glint post --concat part1.mkv part2.mkv -o whole.mkv
  glint post --camera /dev/video0 --size 640x480 -o live.mp4 -e sobel
  glint post --input lavfi:testsrc2=size=1280x720:duration=5 -o test.mp4 -e spectrum
  glint post - -o - -e sobel < photo.png > edges.png
  ffmpeg -i clip.mp4 -f nut - | glint post - -o - --format nut -e sepia | ffplay -

Inputs: an image (.png .jpg .tga .tif .exr .hdr .bmp .webp, through OpenImageIO), any video
file FFmpeg reads, a V4L2 camera (--camera), or a lavfi filter graph (--input lavfi:GRAPH, or
as IN). Frames are processed as 8-bit RGB (sRGB-encoded values, like the seed's camera).
Outputs: an image for an image (for a video: its first frame, or the first of --frames);
a video for a video: H.264 (--crf, --preset; .mp4 .mkv .mov)
or FFV1, lossless (.mkv .avi .nut). Audio is copied when the output container holds its
codec, else dropped with a warning. Timestamps are kept: parts made with --frames join
losslessly with --concat (FFV1 parts at any frame; H.264 parts are written without B-frames).

Frames are decoded, processed on the GPU (pixel buffer objects, a few frames in flight) and
encoded on three overlapped threads. --backend auto (the default) runs the effects on the CPU
instead (threaded, FFTW, OpenCV) when the GL renderer is a software one (llvmpipe: no GPU),
as --backend cpu always does (every effect has a CPU version); --backend gpu keeps OpenGL. On
the CPU, sepia, sobel and the FFT filters (one effect) work on a video's YUV planes directly,
skipping the RGB round trip; glint -v post says which backend ran. No frame of a file is ever dropped; a live source
(camera, --realtime) drops what the GPU cannot keep up with and the report counts it.

Exit status: 0 done, 2 bad option or effect, 3 unreadable input (or an input that broke off:
the video written so far is complete), 4 output not writable, 5 no OpenGL 4.5,
130 interrupted (Ctrl-C: a video is finished and playable up to the last frame processed,
reported as partial; an image is not written).)";

}  // namespace

Command postCommand(CLI::App& app, const GlobalOptions& global) {
  auto a = std::make_shared<PostArgs>();
  auto* cmd = app.add_subcommand("post", "Post-process an image, a video, a camera or a lavfi source on the GPU "
                                         "(sepia, Sobel, Kuwahara, FFT filters)");
  cmd->footer(std::string(kPostFooter) + "\n\n" + render::post::effectHelp());
  cmd->add_option("file", a->input, "Image or video file to read (or lavfi:GRAPH; '-': stdin, an image when the "
                                    "output is one, else a video stream)");
  cmd->add_option("-o,--output", a->output, "Image or video to write; format from the extension ('-': stdout, see --format)");
  cmd->add_option("--format", a->format, "The format of -o - (stdout): an image (png, the default; jpg, tga, tif, exr) "
                                         "or a video container that streams (mkv, nut, ts)");
  cmd->add_option("-e,--effect", a->effects, "An effect, in chain order: NAME or NAME:param=value,... (list below)");
  cmd->add_option("--set", a->settings, "param=value (every effect that has it) or effect.param=value");
  cmd->add_option("--camera", a->camera, "Read a V4L2 camera, e.g. /dev/video0 (a live source)");
  cmd->add_option("--input", a->lavfi, "An FFmpeg source: lavfi:GRAPH, e.g. lavfi:testsrc2=size=1280x720:duration=5");
  cmd->add_option("--size", a->size, "Camera: the size to ask for, WIDTHxHEIGHT (the seed's camera: 640x480)");
  cmd->add_option("--fps", a->rate, "Camera: the frame rate to ask for");
  cmd->add_flag("--realtime", a->realtime, "Pace a file or lavfi source at its frame rate and treat it as live "
                                           "(frames the GPU cannot keep up with are dropped and counted)");
  cmd->add_option("--backend", a->backend, "Where the effects run: auto (the CPU on a software GL renderer such as "
                  "llvmpipe, else the GPU), gpu (OpenGL) or cpu (threads, FFTW, OpenCV)")->capture_default_str();
  cmd->add_option("--codec", a->codec, "h264 (libx264, yuv420p) or ffv1 (lossless RGB)")->capture_default_str();
  cmd->add_option("--crf", a->crf, "H.264 quality: 0 (lossless) .. 51; 18 is visually lossless")->capture_default_str();
  cmd->add_option("--preset", a->preset, "H.264 speed/size trade-off: ultrafast .. placebo")->capture_default_str();
  cmd->add_option("--frames", a->frames, "Only frames FIRST:END (END excluded; 250: = to the end): split a long video "
                                         "over machines, join the parts with --concat");
  cmd->add_option("--concat", a->concat, "Join parts made with --frames (in order) into -o, copying packets");
  cmd->add_flag("--no-audio", a->noAudio, "Do not copy the input's audio");
  cmd->add_option("--channels", a->channels, "Image output: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA (default: the "
                                             "input's; colour when an effect colours a grey input)");
  cmd->add_flag("--effects", a->listEffects, "List the effects and their parameters, and exit");
  addToolOptions(*cmd, a->tool, "input, output, effects, frames read/written/dropped, fps, audio, partial");

  return Command{.run = [a, &global] {
                   if (a->listEffects) {
                     fmt::print("{}", render::post::effectHelp());
                     return 0;
                   }
                   ToolRun run("post", a->tool);
                   const render::post::PostJob job = makeJob(*a, global);
                   return render::post::finishJob(render::post::runJob(job, run), run);
                 },
                 .readsImages = false};  // images load OpenImageIO themselves (runImage, runStill)
}

}  // namespace glint::app
