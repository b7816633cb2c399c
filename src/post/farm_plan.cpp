// `glint farm post` (post/job.h): a video's frames split at keyframes into pieces, each a
// plain `glint post --frames` call, joined by `glint post --concat`.
#include "glint/post/job.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/video/source.h"

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace glint::post {

farm::Plan farmPlan(const PostJob& given, const ToolSettings& settings, const farm::Split& split) {
  if (!given.camera.empty() || !given.lavfi.empty() || given.input.starts_with("lavfi:"))
    fail(ErrorKind::Usage, "farm post: a camera or lavfi source cannot be split over machines; farm a video file");
  if (!given.parts.empty()) fail(ErrorKind::Usage, "farm post: --concat is what the farm's join runs; farm a video file");
  if (given.realtime) fail(ErrorKind::Usage, "farm post: --realtime cannot be split over machines; farm a video file");
  if (given.input.empty() || given.input == "-") fail(ErrorKind::Usage, "farm post: give a video file every node can read");
  if (given.output.empty() || given.output == "-") fail(ErrorKind::Usage, "farm post: give -o, a video file");
  checkJob(given, settings);  // the command's own checks, before anything is submitted
  if (inputKind(given) == InputKind::Image) fail(ErrorKind::Usage, "farm post: '{}' is an image; farm a video", given.input);
  if (imageOutput(given)) fail(ErrorKind::Usage, "farm post: -o '{}' is an image; farm a video into a video", given.output);
  PostJob job = given;
  job.input = farm::absolutePath(job.input);
  job.output = farm::absolutePath(job.output);
  const video::FrameIndex index = video::indexFrames(job.input);
  std::int64_t first = job.frames ? job.frames->first : 0;
  std::int64_t end = job.frames ? job.frames->end : -1;
  if (end < 0 || end > index.frameCount) end = index.frameCount;
  if (first >= end)
    fail(ErrorKind::Usage, "farm post: frames {}:{} of '{}' ({} frames) select none", first, end, given.input, index.frameCount);
  const auto ranges = farm::splitAtKeyframes(index.keyframes, first, end, split.pieces);
  if (int(ranges.size()) < split.pieces)
    log::warn("farm post: '{}' has keyframes for only {} chunk{} of frames {}:{} (asked for {})", given.input,
              ranges.size(), ranges.size() == 1 ? "" : "s", first, end, split.pieces);
  farm::Plan plan{.tool = "post"};
  {
    const video::Source source = video::Source::open(job.input);
    plan.memoryMiB = farm::taskMemoryMiB(split, estimatePeakMemoryMiB(source.info().size, false));
  }
  plan.title = fmt::format("{} → {}", std::filesystem::path(job.input).filename().string(),
                           std::filesystem::path(job.output).filename().string());
  plan.outputs = {job.output};
  const std::vector<std::string> limits = farm::pieceSettings(settings, split, plan.memoryMiB);
  const std::string extension = std::filesystem::path(job.output).extension().string();
  for (const auto& [a, b] : ranges) {
    PostJob piece = job;
    piece.output = farm::kPieceOutput;
    piece.frames = FrameRange{a, b};
    farm::Piece p{.label = fmt::format("frames {}:{}", a, b), .command = {"post"}, .extension = extension};
    const auto args = arguments(piece);
    p.command.insert(p.command.end(), args.begin(), args.end());
    p.command.insert(p.command.end(), limits.begin(), limits.end());
    p.inputs = {job.input};
    plan.pieces.push_back(std::move(p));
  }
  plan.join = {"post", "--concat", farm::kAllPieceOutputs, "-o", job.output};
  if (settings.quiet) plan.join.push_back("-q");
  if (!settings.json.empty()) {
    plan.join.insert(plan.join.end(), {"--json", farm::absolutePath(settings.json)});
    if (settings.json != "-") plan.outputs.push_back(farm::absolutePath(settings.json));
  }
  return plan;
}

}  // namespace glint::post
