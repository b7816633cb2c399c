#include "glint/scenes/clip.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"

#include <fmt/format.h>

#include <chrono>
#include <optional>

namespace glint::scenes {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

ClipStats renderClip(const VariantRef& ref, const ClipRequest& clip, const std::filesystem::path& output, ToolRun& run) {
  const FrameRange range = clip.frames;
  if (range.end < 0) fail(ErrorKind::Usage, "--frames {}: needs an END (FIRST:END, END excluded, e.g. 0:300)", range.first);
  if (range.end <= range.first) {
    fail(ErrorKind::Usage, "--frames {}:{} selects no frame (END is excluded: {}:{} is one frame)", range.first,
         range.end, range.first, range.first + 1);
  }
  if (clip.fps < 1 || clip.fps > 1000) fail(ErrorKind::Usage, "--fps must be 1..1000, got {}", clip.fps);

  const auto start = Clock::now();
  ClipStats stats{.scene = ref.fullName(), .output = output.string(), .frames = range, .fps = clip.fps,
                  .codec = video::codecName(clip.codec)};
  stats.size = clip.size.x > 0 ? clip.size : ref.scene->defaultSize;
  std::optional<ToolRun::Phase> opening(std::in_place, run, "open");
  // The sink first: an unwritable or impossible output fails before the scene is built.
  // Always without B-frames: any clip may be a part of a longer one (post --concat).
  video::Sink sink(output, {.codec = clip.codec, .size = stats.size, .frameRate = {clip.fps, 1},
                            .timeBase = {1, clip.fps}, .crf = clip.crf, .preset = clip.preset,
                            .threads = clip.threads, .noReordering = true});
  VariantRenderer renderer(ref, {.size = stats.size, .options = clip.options});
  opening.reset();
  const std::int64_t count = range.end - range.first;
  log::info("render: {} frames {}..{} at {} fps ({}x{}, {}) → {}", stats.scene, range.first, range.end - 1, clip.fps,
            stats.size.x, stats.size.y, stats.codec, stats.output);

  Progress progress("render", std::uint64_t(count));
  const auto loop = Clock::now();
  for (std::int64_t i = range.first; i < range.end; ++i) {
    if (run.interrupted()) {  // the sink is abandoned: its temporary file goes, nothing is renamed
      fail(ErrorKind::Interrupted, "render: interrupted after {} of {} frame(s); '{}' {}", i - range.first, count,
           stats.output, std::filesystem::exists(output) ? "was left as it was" : "was not written");
    }
    auto t = Clock::now();
    RenderResult picture = renderer.frame(double(i) / double(clip.fps));  // i / fps: never the clock
    video::Frame frame{.image = std::move(picture.image), .index = i, .pts = i};
    stats.notes = std::move(picture.notes);
    stats.renderSeconds += since(t);
    t = Clock::now();
    sink.write(frame);
    stats.encodeSeconds += since(t);
    progress.advance();
    progress.setDetail(fmt::format("{:.1f} frames/s", double(i - range.first + 1) / since(loop)));
  }
  const auto t = Clock::now();
  sink.finish();
  stats.encodeSeconds += since(t);
  progress.finish();
  stats.framesWritten = sink.framesWritten();
  run.addSeconds("render", stats.renderSeconds);
  run.addSeconds("encode", stats.encodeSeconds);
  stats.seconds = since(start);
  return stats;
}

}  // namespace glint::scenes
