#pragma once
// glint/video/sink.h — RGBA frames into a video file: H.264 (libx264) or FFV1 (lossless),
// audio copied from a source, written atomically.
//
/// ```cpp
/// glint::video::SinkOptions options;
/// options.codec = glint::video::Codec::H264;
/// options.size = {1280, 720};
/// options.frameRate = {30, 1};
/// options.timeBase = {1, 30};
/// glint::video::Sink sink("out.mp4", options);
/// for (std::int64_t i = 0; i < 30; ++i) {
///   glint::video::Frame frame;
///   frame.image = glint::Image(1280, 720, 4, glint::PixelType::U8);  // RGBA8
///   frame.index = frame.pts = i;                                      // pts in timeBase units
///   sink.write(frame);
/// }
/// sink.finish();  // flushes the encoder, writes the trailer, renames into place
/// ```
//
// The file is written to a temporary name beside the destination (core/file.h) and
// renamed only by finish(): a crash or an exception leaves no half-written video under the
// final name, and a Sink destroyed without finish() removes its temporary file. An
// interrupted job calls finish() on what it has: the result is a complete, playable video
// of the frames written so far (a partial video, which the caller reports as such).
//
// Codecs
//   H264  libx264, yuv420p (BT.709 matrix, limited range, tagged so in the stream), --crf
//         and --preset as x264 has them; needs even width and height. .mp4 .mkv .mov
//   FFV1  lossless, stored as bgr0 (8-bit RGB): decoding gives back exactly the RGB that was
//         written; every frame a keyframe (GOP 1), so parts concatenate at any frame.
//         .mkv .avi .nut
//
// Timestamps are kept: frame pts are taken in `timeBase` (the source's), so a part of a
// split video (--frames a:b) keeps its place in time and parts concatenate by copying
// packets (concatenate(), below).
//
// Audio: with `audio` (Source::audio()) the packets given to writeAudio() are copied
// unchanged when the container can hold the codec; otherwise the sink drops them and
// audioNote() says why (e.g. "pcm_s16le audio cannot go into mp4: dropped").

#include "glint/core/math.h"
#include "glint/video/frame.h"
#include "glint/video/packet.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace glint::video {

class AudioTrack;

enum class Codec {
  H264,  ///< libx264, yuv420p: small files, lossy
  Ffv1   ///< FFV1, bgr0: lossless RGB
};

/// "h264" / "ffv1" → Codec; Error(Usage) otherwise.
Codec parseCodec(const std::string& name);
/// Error(Usage) naming the choices unless `preset` is one of x264's (ultrafast .. placebo).
void checkPreset(const std::string& preset);
inline const char* codecName(Codec codec) { return codec == Codec::H264 ? "h264" : "ffv1"; }

struct SinkOptions {
  Codec codec = Codec::H264;
  ivec2 size{0};               ///< frame size (required)
  Rational frameRate{30, 1};   ///< nominal rate (stream metadata; timestamps decide timing)
  Rational timeBase{0, 1};     ///< units of Frame::pts; invalid: 1/frameRate
  int crf = 18;                ///< H264: constant rate factor (0 lossless .. 51; 18 ≈ visually lossless)
  std::string preset = "medium";  ///< H264: x264 preset (ultrafast .. placebo)
  int threads = 0;             ///< encoder threads; 0: FFmpeg's choice
  /// H264: no B-frames, so decoding order is display order (dts = pts). Parts of a split
  /// video (--frames a:b) are written so: their timestamps then join without overlap.
  bool noReordering = false;
  const AudioTrack* audio = nullptr;  ///< copy this audio stream (packets through writeAudio)
  /// For the destination "-" (standard output): the container, as an extension ("mkv",
  /// "nut", "ts"). Written as it is made, not atomically; MP4 and MOV cannot stream (their
  /// index is written at the end, which needs seeking): Error(Usage).
  std::string format;
  /// The display matrix to write on the video stream (SourceInfo::displayMatrix: a rotated
  /// source's stays rotated). MP4 and MOV hold it; with another container the sink fails
  /// with Error(Usage) naming the container, so the caller can turn the frames instead.
  std::vector<std::int32_t> displayMatrix;
};

/// Whether a video written to `destination` (or stdout as `format`) can hold a display
/// matrix: MP4 and MOV can.
bool holdsDisplayMatrix(const std::filesystem::path& destination, const std::string& format = {});

class Sink {
public:
  /// Creates the temporary file and the streams. Error(Usage) for a container that cannot
  /// hold the codec or an odd size for H.264; Error(Output) when the file cannot be made.
  Sink(const std::filesystem::path& destination, const SinkOptions& options);
  Sink(Sink&&) noexcept;
  Sink& operator=(Sink&&) noexcept;
  ~Sink();

  /// Encodes one frame of the sink's size: RGBA8, or Yuv420 (copied as it is into an H.264
  /// stream when its matrix is BT.709, converted otherwise). Frames must come in pts order.
  void write(const Frame& frame);
  /// Copies one audio packet (from the source given as options.audio).
  void writeAudio(Packet packet);
  /// Flushes the encoder, writes the trailer and renames the file into place.
  void finish();

  std::int64_t framesWritten() const;
  /// Why audio was dropped (empty when it is copied, or there was none).
  const std::string& audioNote() const;
  const std::filesystem::path& destination() const;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// Joins video files made from consecutive frame ranges of one source (`glint post
/// --frames a:b` on several machines) by copying their packets — no decoding, no
/// re-encoding: lossless. The parts must have the same codec, size and streams, and each
/// must start where the previous one ended (its first timestamp is the previous part's
/// last plus one frame); Error(Input) naming the part otherwise. Writes atomically.
/// Returns the number of video frames in the result.
std::int64_t concatenate(std::span<const std::filesystem::path> parts, const std::filesystem::path& destination);

}  // namespace glint::video
