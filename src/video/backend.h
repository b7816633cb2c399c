#pragma once
// backend.h — the private ABI between glint_video (video.cpp: the public classes) and the
// glint_ffmpeg module (ffmpeg_*.cpp), the only code that touches FFmpeg.
//
// Why a module: FFmpeg's libraries pull in ~200 shared libraries (every codec Debian
// builds in); linked into glint, the dynamic loader spent ~0.1 s on them before main() of
// every command — `glint list` took 0.11 s instead of 0.01 s. video.cpp dlopen()s the module
// on the first Source, Sink or concatenate(), like image_io.cpp does OpenImageIO's.
//
// Rules: both sides are built from the same headers by the same compiler, so glint's own
// types (Frame, Image, SourceOptions, std::string) cross as they are; no exception crosses
// (every entry point catches and fills a Status, the caller rethrows it as glint::Error);
// objects made on one side are destroyed through the side that made them (close*,
// freePacket). Bump kVideoAbiVersion on any change to this file or to the types it names.
#include "glint/core/error.h"
#include "glint/video/sink.h"
#include "glint/video/source.h"
#include "glint/video/packet.h"

#include <cstdint>
#include <deque>
#include <filesystem>
#include <span>
#include <string>

namespace glint::video::backend {

constexpr int kVideoAbiVersion = 6;

/// An entry point's outcome: ok, or the Error it would have thrown.
struct Status {
  bool ok = true;
  ErrorKind kind = ErrorKind::Internal;
  std::string message;
};

struct SourceHandle;  // the module's FfmpegSource
struct SinkHandle;    // the module's FfmpegSink

struct Api {
  int abiVersion = 0;
  /// glint's log level (log::Level as int): the module has its own copy of the logger.
  void (*setLogLevel)(int level) = nullptr;

  SourceHandle* (*openSource)(const std::string& name, const SourceOptions& options, Status& status) = nullptr;
  void (*closeSource)(SourceHandle* source) = nullptr;
  const SourceInfo* (*sourceInfo)(const SourceHandle* source) = nullptr;
  bool (*read)(SourceHandle* source, Frame& frame, Status& status) = nullptr;
  void (*takeAudio)(SourceHandle* source, std::deque<Packet>& packets) = nullptr;
  const AudioTrack* (*audio)(const SourceHandle* source) = nullptr;
  /// dropped, corrupt, delivered, decoder error lines, the last frame's time in µs (-1: none)
  void (*counters)(const SourceHandle* source, std::int64_t out[5]) = nullptr;
  /// The first error line the decoder logged ("" when none).
  std::string (*firstDecoderError)(const SourceHandle* source) = nullptr;

  /// Writes into `target` (a temporary the caller owns and renames: glint_video's AtomicFile,
  /// so the run's OutputSet stages it; "-" for stdout); `destination` names the file in
  /// messages and picks the container.
  SinkHandle* (*openSink)(const std::filesystem::path& destination, const std::filesystem::path& target,
                          const SinkOptions& options, Status& status) = nullptr;
  void (*closeSink)(SinkHandle* sink) = nullptr;
  void (*write)(SinkHandle* sink, const Frame& frame, Status& status) = nullptr;
  void (*writeAudio)(SinkHandle* sink, Packet& packet, Status& status) = nullptr;
  void (*finish)(SinkHandle* sink, Status& status) = nullptr;
  std::int64_t (*framesWritten)(const SinkHandle* sink) = nullptr;
  const std::string* (*audioNote)(const SinkHandle* sink) = nullptr;

  std::int64_t (*concatenate)(std::span<const std::filesystem::path> parts, const std::filesystem::path& destination,
                              const std::filesystem::path& target, Status& status) = nullptr;
  /// video::indexFrames
  FrameIndex (*indexFrames)(const std::string& name, Status& status) = nullptr;
  /// av_packet_free, for Packets made by the module and destroyed by glint_video.
  void (*freePacket)(AVPacket* packet) = nullptr;
};

}  // namespace glint::video::backend

// The module's one export, loaded by core/locations.h's loadModule:
//   extern "C" const glint::video::backend::Api* glint_video_api();
