// The glint_ffmpeg module's one export: the table of entry points backend.h describes.
#include "ffmpeg.h"

#include "glint/core/log.h"
#include "glint/video/packet.h"

#include <cstdint>
#include <deque>
#include <filesystem>
#include <span>
#include <string>

namespace glint::video::backend {
// Defined in ffmpeg_source.cpp and ffmpeg_sink.cpp.
SourceHandle* openSource(const std::string& name, const SourceOptions& options, Status& status);
void closeSource(SourceHandle* source);
const SourceInfo* sourceInfo(const SourceHandle* source);
bool read(SourceHandle* source, Frame& frame, Status& status);
void takeAudio(SourceHandle* source, std::deque<Packet>& packets);
const AudioTrack* audio(const SourceHandle* source);
void counters(const SourceHandle* source, std::int64_t out[5]);
std::string firstDecoderError(const SourceHandle* source);
SinkHandle* openSink(const std::filesystem::path& destination, const std::filesystem::path& target,
                     const SinkOptions& options, Status& status);
void closeSink(SinkHandle* sink);
void write(SinkHandle* sink, const Frame& frame, Status& status);
void writeAudio(SinkHandle* sink, Packet& packet, Status& status);
void finish(SinkHandle* sink, Status& status);
std::int64_t framesWritten(const SinkHandle* sink);
const std::string* audioNote(const SinkHandle* sink);
std::int64_t concatenate(std::span<const std::filesystem::path> parts, const std::filesystem::path& destination,
                         const std::filesystem::path& target, Status& status);
FrameIndex indexFrames(const std::string& name, Status& status);
}  // namespace glint::video::backend

extern "C" __attribute__((visibility("default"))) const glint::video::backend::Api* glint_video_api() {
  using namespace glint::video::backend;
  static const Api api = [] {
    Api a;
    a.abiVersion = kVideoAbiVersion;
    a.setLogLevel = [](int level) { glint::log::setLevel(glint::log::Level(level)); };
    a.openSource = openSource;
    a.closeSource = closeSource;
    a.sourceInfo = sourceInfo;
    a.read = read;
    a.takeAudio = takeAudio;
    a.audio = audio;
    a.counters = counters;
    a.firstDecoderError = firstDecoderError;
    a.openSink = openSink;
    a.closeSink = closeSink;
    a.write = write;
    a.writeAudio = writeAudio;
    a.finish = finish;
    a.framesWritten = framesWritten;
    a.audioNote = audioNote;
    a.concatenate = concatenate;
    a.indexFrames = indexFrames;
    a.freePacket = [](AVPacket* p) { av_packet_free(&p); };
    return a;
  }();
  return &api;
}
