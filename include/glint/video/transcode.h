#pragma once
// glint/video/transcode.h — decode → process → encode, overlapped on three threads.
//
/// ```cpp
/// #include <glint/video/sink.h>
/// #include <glint/video/source.h>
/// // A FrameProcessor of one's own: here one that hands every frame on unchanged.
/// struct Copy final : glint::video::FrameProcessor {
///   void process(glint::video::Frame&& frame, const Emit& emit) override { emit(std::move(frame)); }
///   void flush(const Emit&) override {}
/// };
/// glint::video::Source source = glint::video::Source::open("in.mp4");
/// glint::video::SinkOptions options;
/// options.size = source.info().size;
/// options.frameRate = source.info().frameRate;
/// options.timeBase = source.info().timeBase;
/// glint::video::Sink sink("out.mp4", options);
/// Copy copy;
/// std::atomic<bool> cancel{false};  // set by Ctrl-C: ToolRun::cancelFlag()
/// glint::video::TranscodeOptions run;
/// run.cancel = &cancel;
/// const glint::video::TranscodeStats stats = glint::video::transcode(source, sink, copy, run);
/// ```
//
// Threads: a reader decodes (and converts to RGBA) into a queue; the calling thread runs
// the processor (it owns the GL context: render/post's FrameStream uploads through pixel
// buffer objects and reads back asynchronously, so it may hand frames back a few calls
// later); a writer encodes and muxes, and copies the source's audio packets. Frame images
// are recycled through a pool, so a long video allocates a handful of frames.
//
// Frames are never dropped from a file: a full queue makes the reader wait. A live source
// (a camera, or realtime) cannot wait: when the processor falls behind, the reader drops
// the oldest waiting frame and counts it (TranscodeStats::droppedFrames, with the frames
// the device itself dropped), so the output shows the newest picture with its own time.
//
// Stopping: when `cancel` becomes true (Ctrl-C) the reader stops, the frames in flight are
// processed and encoded, and the sink is finished: a complete, playable, partial video
// (stats.interrupted says so). When the source breaks mid-stream (a camera unplugged,
// a truncated file) the same happens and the error is returned in stats.inputError for the
// caller to report after the output is safe. Errors in the processor or the sink are
// thrown after the threads are joined; the sink is then not finished (no output file).

#include "glint/video/frame.h"

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>

namespace glint::video {

class Source;
class Sink;

/// The middle stage, run on the thread that called transcode().
class FrameProcessor {
public:
  using Emit = std::function<void(Frame&&)>;
  virtual ~FrameProcessor() = default;
  /// Takes a decoded frame (moved in). Finished frames, in input order and with their index
  /// and pts unchanged, go to emit() — during this call or a later one.
  virtual void process(Frame&& frame, const Emit& emit) = 0;
  /// Emits every frame still in flight.
  virtual void flush(const Emit& emit) = 0;
};

/// A FrameProcessor around a pipelined stream with render/post's FrameStream interface —
/// push(const Image&), pop(Image&), full(), empty() — keeping each frame's index and
/// timestamps and reusing the input frames' images for the results. A template, so the
/// video layer needs nothing of the GPU side (scenes/post/gpu_backend.cpp runs glint post's
/// FrameStream through it):
///
/// ```cpp
/// #include <glint/render/post/chain.h>
/// #include <glint/video/sink.h>
/// #include <glint/video/source.h>
/// glint::video::Source source = glint::video::Source::open("in.mp4");
/// glint::video::SinkOptions options;
/// options.size = source.info().size;
/// options.timeBase = source.info().timeBase;
/// glint::video::Sink sink("out.mp4", options);
/// const std::vector<std::string> specs = {"sepia"};
/// glint::render::post::FrameStream stream(source.info().size, glint::render::post::parseEffects(specs));
/// glint::video::StreamProcessor processor(stream);
/// glint::video::transcode(source, sink, processor);
/// ```
template <typename Stream>
class StreamProcessor final : public FrameProcessor {
public:
  explicit StreamProcessor(Stream& stream) : m_stream(stream) {}
  void process(Frame&& frame, const Emit& emit) override {
    if (m_stream.full()) popOne(emit);
    m_stream.push(frame.image);
    m_waiting.push_back(std::move(frame));  // its image becomes a result's storage
  }
  void flush(const Emit& emit) override {
    while (!m_stream.empty()) popOne(emit);
  }

private:
  void popOne(const Emit& emit) {
    Frame out = std::move(m_waiting.front());
    m_waiting.pop_front();
    m_stream.pop(out.image);
    emit(std::move(out));
  }
  Stream& m_stream;
  std::deque<Frame> m_waiting;
};

struct TranscodeOptions {
  const std::atomic<bool>* cancel = nullptr;  ///< stop cleanly when it becomes true
  int queueDepth = 4;                         ///< frames between stages
  /// Called on the calling thread after each processed frame, with the number of frames
  /// processed so far (for a progress bar).
  std::function<void(std::int64_t framesDone)> progress;
};

struct TranscodeStats {
  std::int64_t framesRead = 0;
  std::int64_t framesWritten = 0;
  std::int64_t droppedFrames = 0;   ///< live sources: dropped by glint (behind) or by the device
  std::int64_t audioPackets = 0;    ///< audio packets copied
  bool interrupted = false;         ///< stopped by `cancel`: the output is a partial video
  std::optional<std::string> inputError;  ///< the source broke mid-stream (output finished up to there)
  /// Whether the sink was finished (its file renamed into place): only when at least one
  /// frame was written. With none, nothing is written and an existing file is left alone.
  bool finished = false;
  double readSeconds = 0, processSeconds = 0, writeSeconds = 0;  ///< busy time of each stage
  double seconds = 0;               ///< wall time
};

/// Runs the pipeline until the source ends (or lastFrame), `cancel` is set or the source
/// breaks; finishes the sink in those three cases when it holds at least one frame (a video
/// without frames is not a result: the sink is abandoned, its temporary file removed).
TranscodeStats transcode(Source& source, Sink& sink, FrameProcessor& processor, const TranscodeOptions& options = {});

}  // namespace glint::video
