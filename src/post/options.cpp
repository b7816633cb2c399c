// `glint post`'s options (post/job.h): the command line the command, `glint farm post` and
// the Python module bind, its help footer, the job they describe, and the job back as
// arguments (what a farm piece runs).
#include "glint/post/job.h"

#include "glint/core/error.h"
#include "glint/core/options.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <string>
#include <vector>

namespace glint::post {

namespace {
constexpr const char* kFooter = R"(Examples:
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
as IN). Frames are processed as 8-bit RGB (sRGB-encoded values, like WWDC 2003 session 212's camera); a
float image (EXR, HDR: linear light) is processed in float on the GPU and a float output
holds linear values again. A video's rotation (a phone's display matrix) is kept on the
output and named in the report; --apply-rotation turns the frames upright instead.
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
the video written so far is complete), 4 output not writable (a full disk: "no space left on
device"), 5 no OpenGL 4.5, 6 out of memory, 130 interrupted (Ctrl-C: a video is finished and
playable up to the last frame processed, reported as partial; when -o already existed it is
left as it was and the partial video is written beside it, OUT.partial.EXT; an image is not
written).)";
}  // namespace

void addOptions(CLI::App& cmd, PostArgs& a) {
  cmd.add_option("file", a.input, "Image or video file to read (or lavfi:GRAPH; '-': stdin, an image when the "
                                  "output is one, else a video stream)");
  cmd.add_option("-o,--output", a.output, "Image or video to write; format from the extension ('-': stdout, see --format)");
  cmd.add_option("--format", a.format, "The format of -o - (stdout): an image (png, the default; jpg, tga, tif, exr) "
                                       "or a video container that streams (mkv, nut, ts)");
  cmd.add_option("-e,--effect", a.effects, "An effect, in chain order: NAME or NAME:param=value,... (list below)");
  cmd.add_option("--set", a.settings, "param=value (every effect that has it) or effect.param=value");
  cmd.add_option("--camera", a.camera, "Read a V4L2 camera, e.g. /dev/video0 (a live source)");
  cmd.add_option("--input", a.lavfi, "An FFmpeg source: lavfi:GRAPH, e.g. lavfi:testsrc2=size=1280x720:duration=5");
  cmd.add_option("--size", a.size, "Camera: the size to ask for, WIDTHxHEIGHT (WWDC 2003 session 212's camera: 640x480)");
  cmd.add_option("--fps", a.rate, "Camera: the frame rate to ask for");
  cmd.add_flag("--realtime", a.realtime, "Pace a file or lavfi source at its frame rate and treat it as live "
                                         "(frames the GPU cannot keep up with are dropped and counted)");
  cmd.add_option("--backend", a.backend, "Where the effects run: auto (the CPU on a software GL renderer such as "
                 "llvmpipe, else the GPU), gpu (OpenGL) or cpu (threads, FFTW, OpenCV)")->capture_default_str();
  cmd.add_option("--codec", a.codec, "h264 (libx264, yuv420p) or ffv1 (lossless RGB)")->capture_default_str();
  cmd.add_option("--crf", a.crf, "H.264 quality: 0 (lossless) .. 51; 18 is visually lossless")->capture_default_str();
  cmd.add_option("--preset", a.preset, "H.264 speed/size trade-off: ultrafast .. placebo")->capture_default_str();
  cmd.add_option("--frames", a.frames, "Only frames FIRST:END (END excluded; 250: = to the end): split a long video "
                                       "over machines, join the parts with --concat");
  cmd.add_option("--concat", a.concat, "Join parts made with --frames (in order) into -o, copying packets");
  cmd.add_flag("--no-audio", a.noAudio, "Do not copy the input's audio");
  cmd.add_flag("--apply-rotation", a.applyRotation, "A rotated video (a phone's portrait clip): turn its frames upright "
               "instead of keeping its display matrix on the output (done anyway for an image or a container other "
               "than MP4/MOV)");
  cmd.add_option("--channels", a.channels, "Image output: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA (default: the "
                                           "input's; colour when an effect colours a grey input)");
  cmd.add_flag("--effects", a.listEffects, "List the effects and their parameters, and exit");
}

std::string helpFooter() { return std::string(kFooter) + "\n\n" + effectHelp(); }

PostJob makeJob(const PostArgs& a, bool glDebug) {
  PostJob job{.input = a.input, .camera = a.camera, .lavfi = a.lavfi, .parts = a.concat, .output = a.output,
              .crf = a.crf, .preset = a.preset, .realtime = a.realtime, .keepAudio = !a.noAudio,
              .applyRotation = a.applyRotation, .channels = a.channels, .glDebug = glDebug};
  job.format = a.format;
  job.effects = parseEffects(a.effects, a.settings);
  job.codec = video::parseCodec(a.codec);
  job.backend = parseBackend(a.backend);
  if (!a.frames.empty()) job.frames = parseFrameRange(a.frames, "--frames");
  if (!a.size.empty()) job.cameraSize = parseSize(a.size);
  if (!a.rate.empty()) job.cameraRate = parseFloat(a.rate, "--fps");
  return job;
}

std::vector<std::string> arguments(const PostJob& job) {
  std::vector<std::string> argv;
  if (!job.parts.empty()) {
    argv.push_back("--concat");
    argv.insert(argv.end(), job.parts.begin(), job.parts.end());
  }
  if (!job.input.empty()) argv.push_back(job.input);
  if (!job.camera.empty()) argv.insert(argv.end(), {"--camera", job.camera});
  if (!job.lavfi.empty()) argv.insert(argv.end(), {"--input", job.lavfi});
  argv.insert(argv.end(), {"-o", job.output});
  if (!job.format.empty()) argv.insert(argv.end(), {"--format", job.format});
  for (const Effect& e : job.effects) argv.insert(argv.end(), {"-e", e.spec()});
  if (job.parts.empty()) {
    argv.insert(argv.end(), {"--codec", video::codecName(job.codec)});
    if (job.codec == video::Codec::H264) argv.insert(argv.end(), {"--crf", std::to_string(job.crf), "--preset", job.preset});
    argv.insert(argv.end(), {"--backend", backendName(job.backend)});
  }
  if (job.frames) {
    argv.insert(argv.end(), {"--frames", job.frames->end >= 0 ? fmt::format("{}:{}", job.frames->first, job.frames->end)
                                                              : fmt::format("{}:", job.frames->first)});
  }
  if (job.cameraSize) argv.insert(argv.end(), {"--size", fmt::format("{}x{}", job.cameraSize->x, job.cameraSize->y)});
  if (job.cameraRate) argv.insert(argv.end(), {"--fps", fmt::format("{}", *job.cameraRate)});
  if (job.realtime) argv.push_back("--realtime");
  if (!job.keepAudio) argv.push_back("--no-audio");
  if (job.applyRotation) argv.push_back("--apply-rotation");
  if (job.channels > 0) argv.insert(argv.end(), {"--channels", std::to_string(job.channels)});
  return argv;
}

}  // namespace glint::post
