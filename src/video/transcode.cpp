#include "glint/video/transcode.h"

#include "glint/core/error.h"
#include "glint/video/sink.h"
#include "glint/video/source.h"
#include "glint/video/packet.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <variant>
#include <vector>

namespace glint::video {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// A queue between two stages. `capacity` bounds the frames in it; audio packets (small,
// and needed by the muxer to interleave) are not counted. close(): no more items; the
// consumer drains what is left. abort(): a stage failed; everyone stops now.
class StageQueue {
public:
  using Item = std::variant<Frame, Packet>;
  explicit StageQueue(std::size_t capacity) : m_capacity(capacity) {}

  /// Blocks while full. False when aborted.
  bool push(Item item) {
    std::unique_lock lock(m_mutex);
    const bool isFrame = std::holds_alternative<Frame>(item);
    m_notFull.wait(lock, [&] { return m_aborted || !isFrame || m_frames < m_capacity; });
    if (m_aborted) return false;
    m_frames += isFrame ? 1 : 0;
    m_items.push_back(std::move(item));
    m_notEmpty.notify_one();
    return true;
  }

  /// Live sources: never blocks; when full, the oldest waiting frame is taken out and
  /// returned (dropped). False in `accepted` when aborted.
  std::optional<Frame> pushDroppingOldest(Frame frame, bool& accepted) {
    std::unique_lock lock(m_mutex);
    accepted = !m_aborted;
    if (m_aborted) return std::nullopt;
    std::optional<Frame> dropped;
    if (m_frames >= m_capacity) {
      for (auto it = m_items.begin(); it != m_items.end(); ++it) {
        if (auto* f = std::get_if<Frame>(&*it)) {
          dropped = std::move(*f);
          m_items.erase(it);
          --m_frames;
          break;
        }
      }
    }
    ++m_frames;
    m_items.emplace_back(std::move(frame));
    m_notEmpty.notify_one();
    return dropped;
  }

  /// Blocks until an item comes; nullopt when closed and empty, or aborted.
  std::optional<Item> pop() {
    std::unique_lock lock(m_mutex);
    m_notEmpty.wait(lock, [&] { return m_aborted || m_closed || !m_items.empty(); });
    if (m_aborted || m_items.empty()) return std::nullopt;
    Item item = std::move(m_items.front());
    m_items.pop_front();
    if (std::holds_alternative<Frame>(item)) --m_frames;
    m_notFull.notify_one();
    return item;
  }

  void close() {
    std::lock_guard lock(m_mutex);
    m_closed = true;
    m_notEmpty.notify_all();
  }
  void abort() {
    std::lock_guard lock(m_mutex);
    m_aborted = true;
    m_notEmpty.notify_all();
    m_notFull.notify_all();
  }

private:
  std::mutex m_mutex;
  std::condition_variable m_notEmpty, m_notFull;
  std::deque<Item> m_items;
  std::size_t m_capacity, m_frames = 0;
  bool m_closed = false, m_aborted = false;
};

// Frame images go round: reader → processor → writer → back here.
class ImagePool {
public:
  Image take() {
    std::lock_guard lock(m_mutex);
    if (m_free.empty()) return {};
    Image image = std::move(m_free.back());
    m_free.pop_back();
    return image;
  }
  void give(Image image) {
    std::lock_guard lock(m_mutex);
    if (!image.empty()) m_free.push_back(std::move(image));
  }

private:
  std::mutex m_mutex;
  std::vector<Image> m_free;
};

// The three stages (reader thread, processing here, writer thread) share one Pipeline: the
// queues, the image pool, the failure flag and the stats. Both threads are joined before
// any stage's error is rethrown.
struct Pipeline {
  Source& source;
  Sink& sink;
  FrameProcessor& processor;
  const TranscodeOptions& options;
  TranscodeStats stats;
  StageQueue decoded, processed;
  ImagePool pool;
  const bool live;
  std::atomic<bool> failed{false};
  std::exception_ptr writerError;
  std::int64_t droppedHere = 0;

  Pipeline(Source& from, Sink& to, FrameProcessor& by, const TranscodeOptions& with, std::size_t depth)
      : source(from), sink(to), processor(by), options(with), decoded(depth), processed(depth),
        live(from.info().live) {}

  bool cancelled() const { return options.cancel && options.cancel->load(); }

  /// A stage failed: the others stop now.
  void abortAll() {
    failed = true;
    decoded.abort();
    processed.abort();
  }

  /// The reader thread: frames from the source into `decoded`, its audio into `processed`.
  void readFrames() {
    while (!cancelled() && !failed) {
      Frame frame;
      frame.image = pool.take();
      const auto t = Clock::now();
      bool ok = false;
      try {
        ok = source.read(frame);
      } catch (const Error& e) {
        stats.inputError = e.what();  // reported after the output is finished
      }
      stats.readSeconds += since(t);
      for (Packet& p : source.takeAudio())
        if (!processed.push(std::move(p))) break;
      if (!ok) break;
      ++stats.framesRead;
      if (live) {
        bool accepted = false;
        if (auto old = decoded.pushDroppingOldest(std::move(frame), accepted)) {
          ++droppedHere;
          pool.give(std::move(old->image));
        }
        if (!accepted) break;
      } else if (!decoded.push(std::move(frame))) {
        break;
      }
    }
    decoded.close();
  }

  /// The writer thread: frames and audio from `processed` into the sink.
  void writeItems() {
    try {
      while (auto item = processed.pop()) {
        const auto t = Clock::now();
        if (auto* frame = std::get_if<Frame>(&*item)) {
          sink.write(*frame);
          ++stats.framesWritten;
          pool.give(std::move(frame->image));
        } else {
          sink.writeAudio(std::move(std::get<Packet>(*item)));
          ++stats.audioPackets;
        }
        stats.writeSeconds += since(t);
      }
    } catch (...) {
      writerError = std::current_exception();
      abortAll();
    }
  }

  /// Processing, on the calling thread: `decoded` through the processor into `processed`.
  /// The processor's error, if any.
  std::exception_ptr processFrames() {
    std::exception_ptr processorError;
    std::int64_t processedFrames = 0;
    const FrameProcessor::Emit emit = [&](Frame&& frame) {
      ++processedFrames;
      processed.push(std::move(frame));
      if (options.progress) options.progress(processedFrames);
    };
    try {
      while (auto item = decoded.pop()) {
        const auto t = Clock::now();
        processor.process(std::move(std::get<Frame>(*item)), emit);
        stats.processSeconds += since(t);
      }
      if (!failed) {
        const auto t = Clock::now();
        processor.flush(emit);
        stats.processSeconds += since(t);
      }
    } catch (...) {
      processorError = std::current_exception();
      abortAll();
    }
    return processorError;
  }

  /// After the threads: the audio demuxed after the last frame, then the sink finished.
  void finishOutput() {
    for (Packet& p : source.takeAudio()) {  // demuxed after the last frame
      sink.writeAudio(std::move(p));
      ++stats.audioPackets;
    }
    if (stats.framesWritten > 0) {  // an empty video is no result: the sink's temporary file goes
      const auto t = Clock::now();
      sink.finish();
      stats.writeSeconds += since(t);
      stats.finished = true;
    }
  }
};
}  // namespace

TranscodeStats transcode(Source& source, Sink& sink, FrameProcessor& processor, const TranscodeOptions& options) {
  const auto start = Clock::now();
  Pipeline pipeline(source, sink, processor, options, std::size_t(std::max(1, options.queueDepth)));
  std::thread reader([&] { pipeline.readFrames(); });
  std::thread writer([&] { pipeline.writeItems(); });
  const std::exception_ptr processorError = pipeline.processFrames();
  pipeline.processed.close();
  reader.join();
  writer.join();
  if (processorError) std::rethrow_exception(processorError);
  if (pipeline.writerError) std::rethrow_exception(pipeline.writerError);

  pipeline.finishOutput();
  TranscodeStats& stats = pipeline.stats;
  stats.interrupted = pipeline.cancelled();
  stats.droppedFrames = pipeline.droppedHere + source.droppedFrames();
  stats.seconds = since(start);
  return stats;
}

}  // namespace glint::video
