// `glint post`'s report and its end (post/job.h): PostStats as the --json report's fields,
// and finishJob, which writes it and keeps a partial video beside a complete one.
#include "glint/post/job.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"

#include <fmt/format.h>

#include <filesystem>
#include <string>

namespace glint::post {

nlohmann::ordered_json PostStats::toJson() const {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  if (kind == InputKind::Parts) {
    j["parts"] = parts;
    j["output"] = output;
    j["frames"] = framesWritten;
    return j;
  }
  if (kind == InputKind::Image) {
    j["effects"] = effects;
    j["input"] = input;
    j["output"] = output;
    j["width"] = size.x;
    j["height"] = size.y;
    j["frames"] = framesWritten;
    return j;
  }
  if (still) {
    j["input"] = input;
    j["output"] = output;
    j["frame"] = frame;
    j["effects"] = effects;
    j["rotation"] = rotation;
    j["rotation_applied"] = rotationApplied;
    return j;
  }
  j["input"] = input;
  j["output"] = output;
  j["width"] = size.x;
  j["height"] = size.y;
  j["frame_rate"] = frameRate;
  j["codec"] = codec;
  j["effects"] = effects;
  j["live"] = live;
  j["first_frame"] = firstFrame;
  j["frames_read"] = framesRead;
  j["frames_written"] = framesWritten;
  j["frames_expected"] = framesExpected;
  j["dropped_frames"] = droppedFrames;
  j["corrupt_packets"] = corruptPackets;
  j["decoder_errors"] = decoderErrors;
  j["audio"] = audio;
  j["audio_packets"] = audioPackets;
  j["rotation"] = rotation;
  j["rotation_applied"] = rotationApplied;
  j["fps"] = fps;
  j["partial"] = partial();
  j["interrupted"] = interrupted;
  if (inputError) j["input_error"] = *inputError;
  return j;
}


namespace {
/// Where a partial video goes when the output already exists: beside it, never over it
/// ("graded.mkv" → "graded.partial.mkv", or the first of "graded.partial-2.mkv", ... that is free).
std::filesystem::path partialName(const std::filesystem::path& output) {
  for (int n = 1;; ++n) {
    const std::filesystem::path candidate =
        output.parent_path() / fitFileName(output.parent_path(), output.stem().string(),
                                           ".partial" + (n == 1 ? std::string() : fmt::format("-{}", n)) + output.extension().string());
    std::error_code ec;
    if (!std::filesystem::exists(candidate, ec)) return candidate;
  }
}
}  // namespace

int finishJob(const PostStats& stats, ToolRun& run) {
  // A partial video (Ctrl-C, an input that broke off) never replaces a file that was there:
  // a complete video is worth more than a part of one. The part goes beside it.
  std::string output = stats.output;
  bool keptExisting = false;
  std::error_code ec;
  if (stats.partial() && output != "-" && std::filesystem::exists(output, ec) && run.outputs().staged(output)) {
    const std::filesystem::path beside = partialName(output);
    run.outputs().redirect(output, beside);
    output = beside.string();
    keptExisting = true;
  }
  run.report().update(stats.toJson());
  if (keptExisting) run.report()["output"] = output;
  run.finish();
  const std::string kept = keptExisting ? fmt::format("'{}' was left as it was; ", stats.output) : "";
  if (stats.inputError) {
    fail(ErrorKind::Input, "{}; {}'{}' holds the {} frame(s) before it (a complete, playable video)", *stats.inputError,
         kept, output, stats.framesWritten);
  }
  if (stats.interrupted) {
    log::warn("post: interrupted after {} frame(s): {}'{}' is a complete, playable partial video", stats.framesWritten,
              kept, output);
    return exitCode(ErrorKind::Interrupted);
  }
  if (stats.kind != InputKind::Image && stats.kind != InputKind::Parts && !stats.still) {
    log::info("post: {} frame(s) in {:.2f} s ({:.1f} fps){}", stats.framesWritten, stats.seconds, stats.fps,
              stats.droppedFrames ? fmt::format(", {} dropped", stats.droppedFrames) : "");
  }
  return 0;
}

}  // namespace glint::post
