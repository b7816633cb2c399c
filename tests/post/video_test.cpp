// The video layer without GL: lavfi sources, FFV1 and H.264 files written and read back,
// timestamps and frame counts, --frames ranges and their lossless concatenation, audio
// passthrough, the transcode pipeline's ordering and live dropping, and bad input.
#include "glint/core/error.h"
#include "glint/image/image.h"
#include "glint/video/sink.h"
#include "glint/video/source.h"
#include "glint/video/transcode.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using namespace glint::video;

namespace {
fs::path dir(const char* name) {
  const fs::path d = fs::path(GLINT_TEST_OUTPUT_DIR) / "post-video" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// 48 frames of FFmpeg's testsrc2 (moving colour bars and a counter) at 24 fps, 160×120.
const std::string kPattern = "lavfi:testsrc2=size=160x120:rate=24:duration=2";

std::vector<Frame> readAll(const std::string& name, const SourceOptions& options = {}) {
  Source source = Source::open(name, options);
  std::vector<Frame> frames;
  Frame f;
  while (source.read(f)) frames.push_back(f);
  return frames;
}

// The processor the pipeline tests use: inverts RGB on the CPU, and holds `delay` frames
// back like the GPU stream does.
class InvertProcessor final : public FrameProcessor {
public:
  explicit InvertProcessor(std::size_t delay = 2, int sleepMs = 0) : m_delay(delay), m_sleepMs(sleepMs) {}
  void process(Frame&& frame, const Emit& emit) override {
    if (m_sleepMs) std::this_thread::sleep_for(std::chrono::milliseconds(m_sleepMs));
    auto px = frame.image.pixels<std::uint8_t>();
    for (std::size_t i = 0; i < px.size(); ++i)
      if (i % 4 != 3) px[i] = std::uint8_t(255 - px[i]);
    m_held.push_back(std::move(frame));
    if (m_held.size() > m_delay) {
      emit(std::move(m_held.front()));
      m_held.pop_front();
    }
  }
  void flush(const Emit& emit) override {
    while (!m_held.empty()) {
      emit(std::move(m_held.front()));
      m_held.pop_front();
    }
  }

private:
  std::deque<Frame> m_held;
  std::size_t m_delay;
  int m_sleepMs;
};

Image inverted(const Image& image) {
  Image out = image;
  auto px = out.pixels<std::uint8_t>();
  for (std::size_t i = 0; i < px.size(); ++i)
    if (i % 4 != 3) px[i] = std::uint8_t(255 - px[i]);
  return out;
}
}  // namespace

TEST(PostVideo, LavfiSourceDescribesItselfAndIsDeterministic) {
  Source source = Source::open(kPattern);
  EXPECT_EQ(source.info().kind, SourceKind::Lavfi);
  EXPECT_EQ(source.info().size, ivec2(160, 120));
  EXPECT_EQ(source.info().frameRate, (Rational{24, 1}));
  EXPECT_FALSE(source.info().live);
  const auto a = readAll(kPattern), b = readAll(kPattern);
  ASSERT_EQ(a.size(), 48u);
  ASSERT_EQ(b.size(), 48u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].index, std::int64_t(i));
    EXPECT_NEAR(a[i].seconds, double(i) / 24.0, 1e-9);
    EXPECT_EQ(a[i].image.width(), 160);
    EXPECT_EQ(a[i].image, b[i].image) << "frame " << i;
  }
  EXPECT_NE(a[0].image, a[1].image) << "testsrc2 moves";
}

TEST(PostVideo, Ffv1RoundTripIsExactWithTimestamps) {
  const fs::path d = dir("ffv1");
  const auto frames = readAll(kPattern);
  const Rational tb = Source::open(kPattern).info().timeBase;
  {
    Sink sink(d / "out.mkv", {.codec = Codec::Ffv1, .size = {160, 120}, .frameRate = {24, 1}, .timeBase = tb});
    for (const auto& f : frames) sink.write(f);
    EXPECT_FALSE(fs::exists(d / "out.mkv")) << "only finish() puts the file in place";
    sink.finish();
  }
  Source back = Source::open((d / "out.mkv").string());
  EXPECT_EQ(back.info().codec, "ffv1");
  EXPECT_EQ(back.info().frameRate, (Rational{24, 1}));
  Frame f;
  std::size_t n = 0;
  while (back.read(f)) {
    ASSERT_LT(n, frames.size());
    EXPECT_EQ(f.index, std::int64_t(n));
    EXPECT_NEAR(f.seconds, frames[n].seconds, 1e-3);
    EXPECT_EQ(f.image, frames[n].image) << "FFV1 in bgr0 is lossless, frame " << n;
    ++n;
  }
  EXPECT_EQ(n, frames.size());
}

TEST(PostVideo, H264RoundTripIsClose) {
  const fs::path d = dir("h264");
  const auto frames = readAll(kPattern);
  {
    Sink sink(d / "out.mp4", {.codec = Codec::H264, .size = {160, 120}, .frameRate = {24, 1},
                              .timeBase = Source::open(kPattern).info().timeBase, .crf = 12, .preset = "fast"});
    for (const auto& f : frames) sink.write(f);
    sink.finish();
  }
  const auto back = readAll((d / "out.mp4").string());
  ASSERT_EQ(back.size(), frames.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].index, std::int64_t(i));
    // Lossy (yuv420p halves the chroma resolution; testsrc2 has sharp coloured edges): the
    // mean difference stays small, a wrong matrix or a shifted frame would be ~0.1.
    EXPECT_LT(compareImages(back[i].image, frames[i].image).meanAbs, 0.02) << "frame " << i;
  }
}

TEST(PostVideo, FrameRangesAndLosslessConcatenation) {
  const fs::path d = dir("ranges");
  const auto whole = readAll(kPattern);
  const Rational tb = Source::open(kPattern).info().timeBase;
  // The pattern into a file first (a file seeks; a lavfi graph cannot).
  {
    Sink sink(d / "src.mkv", {.codec = Codec::Ffv1, .size = {160, 120}, .frameRate = {24, 1}, .timeBase = tb});
    for (const auto& f : whole) sink.write(f);
    sink.finish();
  }
  std::vector<fs::path> parts;
  for (auto [a, b] : {std::pair{0, 17}, std::pair{17, 30}, std::pair{30, 48}}) {
    Source source = Source::open((d / "src.mkv").string(), {.firstFrame = a, .lastFrame = b});
    parts.push_back(d / fmt::format("part{}.mkv", a));
    Sink sink(parts.back(), {.codec = Codec::Ffv1, .size = {160, 120}, .frameRate = {24, 1},
                             .timeBase = source.info().timeBase});
    Frame f;
    std::int64_t expected = a;
    while (source.read(f)) {
      EXPECT_EQ(f.index, expected++);
      EXPECT_EQ(f.image, whole[std::size_t(f.index)].image);
      sink.write(f);
    }
    EXPECT_EQ(expected, b);
    sink.finish();
  }
  EXPECT_EQ(concatenate(parts, d / "joined.mkv"), 48);
  const auto joined = readAll((d / "joined.mkv").string());
  ASSERT_EQ(joined.size(), whole.size());
  for (std::size_t i = 0; i < joined.size(); ++i) {
    EXPECT_EQ(joined[i].index, std::int64_t(i));
    EXPECT_NEAR(joined[i].seconds, whole[i].seconds, 1e-3);
    EXPECT_EQ(joined[i].image, whole[i].image) << "frame " << i;
  }
  // Out of order or with a gap: refused, nothing written.
  const std::vector<fs::path> gap{parts[0], parts[2]};
  try {
    concatenate(gap, d / "gap.mkv");
    ADD_FAILURE() << "a gap was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("does not start where"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(d / "gap.mkv"));
}

TEST(PostVideo, TranscodeKeepsEveryFrameInOrder) {
  const fs::path d = dir("transcode");
  const auto input = readAll(kPattern);
  Source source = Source::open(kPattern);
  Sink sink(d / "out.mkv", {.codec = Codec::Ffv1, .size = {160, 120}, .frameRate = {24, 1},
                            .timeBase = source.info().timeBase});
  InvertProcessor invert(3, 1);
  std::int64_t progress = 0;
  const auto stats = transcode(source, sink, invert, {.queueDepth = 2, .progress = [&](std::int64_t n) { progress = n; }});
  EXPECT_EQ(stats.framesRead, 48);
  EXPECT_EQ(stats.framesWritten, 48);
  EXPECT_EQ(stats.droppedFrames, 0);
  EXPECT_EQ(progress, 48);
  EXPECT_FALSE(stats.interrupted);
  EXPECT_FALSE(stats.inputError);
  const auto out = readAll((d / "out.mkv").string());
  ASSERT_EQ(out.size(), input.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].index, std::int64_t(i));
    EXPECT_EQ(out[i].image, inverted(input[i].image)) << "frame " << i;
  }
}

TEST(PostVideo, InterruptedTranscodeFinishesAPlayablePartialVideo) {
  const fs::path d = dir("interrupt");
  Source source = Source::open("lavfi:testsrc2=size=160x120:rate=24");  // endless
  Sink sink(d / "out.mp4", {.codec = Codec::H264, .size = {160, 120}, .frameRate = {24, 1},
                            .timeBase = source.info().timeBase, .preset = "ultrafast"});
  std::atomic<bool> cancel{false};
  InvertProcessor invert(2);
  const auto stats = transcode(source, sink, invert,
                               {.cancel = &cancel, .progress = [&](std::int64_t n) { if (n == 30) cancel = true; }});
  EXPECT_TRUE(stats.interrupted);
  EXPECT_GE(stats.framesWritten, 30);
  EXPECT_EQ(stats.framesWritten, stats.framesRead) << "frames in flight are finished, not lost";
  const auto back = readAll((d / "out.mp4").string());
  EXPECT_EQ(std::int64_t(back.size()), stats.framesWritten) << "the partial video plays to its last frame";
}

TEST(PostVideo, LiveSourceDropsFramesItCannotKeepUpWith) {
  const fs::path d = dir("live");
  // 100 fps paced like a camera, processed at ~25 fps: most frames must be dropped, and
  // counted; the ones kept stay in order with their own timestamps.
  Source source = Source::open("lavfi:testsrc2=size=160x120:rate=100:duration=1", {.realtime = true});
  EXPECT_TRUE(source.info().live);
  Sink sink(d / "out.mkv", {.codec = Codec::Ffv1, .size = {160, 120}, .frameRate = {100, 1},
                            .timeBase = source.info().timeBase});
  InvertProcessor slow(0, 40);
  const auto stats = transcode(source, sink, slow, {.queueDepth = 2});
  EXPECT_EQ(stats.framesRead, 100);
  EXPECT_GT(stats.droppedFrames, 30);
  EXPECT_EQ(stats.framesWritten + stats.droppedFrames, 100);
  const auto back = readAll((d / "out.mkv").string());
  ASSERT_EQ(std::int64_t(back.size()), stats.framesWritten);
  for (std::size_t i = 1; i < back.size(); ++i) EXPECT_GT(back[i].seconds, back[i - 1].seconds);
}

TEST(PostVideo, AudioIsCopiedOrDroppedWithANote) {
  const fs::path d = dir("audio");
  // A file with a PCM audio track: lavfi's movie-less graph makes video and audio together.
  const std::string av = "lavfi:testsrc2=size=160x120:rate=24:duration=1[out0];sine=frequency=440:duration=1[out1]";
  Source source = Source::open(av);
  ASSERT_TRUE(source.info().hasAudio);
  {
    Sink sink(d / "with.mkv", {.codec = Codec::Ffv1, .size = {160, 120}, .frameRate = {24, 1},
                               .timeBase = source.info().timeBase, .audio = source.audio()});
    EXPECT_TRUE(sink.audioNote().empty());
    InvertProcessor invert(0);
    const auto stats = transcode(source, sink, invert);
    EXPECT_GT(stats.audioPackets, 0);
  }
  Source back = Source::open((d / "with.mkv").string());
  EXPECT_TRUE(back.info().hasAudio);
  EXPECT_EQ(back.info().audioCodec, source.info().audioCodec);
  // PCM cannot go into MP4: dropped, and said so.
  Sink mp4(d / "without.mp4", {.codec = Codec::H264, .size = {160, 120}, .audio = back.audio()});
  EXPECT_NE(mp4.audioNote().find("dropped"), std::string::npos) << mp4.audioNote();
}

TEST(PostVideo, BadInputIsOneLineError) {
  const fs::path d = dir("bad");
  const auto expectError = [](ErrorKind kind, const std::function<void()>& f, const char* what) {
    try {
      f();
      ADD_FAILURE() << what << ": no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), kind) << what << ": " << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  expectError(ErrorKind::Input, [&] { Source::open((d / "missing.mp4").string()); }, "missing file");
  { std::ofstream(d / "garbage.mp4") << "this is not a video"; }
  expectError(ErrorKind::Input, [&] { Source::open((d / "garbage.mp4").string()); }, "garbage");
  expectError(ErrorKind::Input, [&] { Source::open("/dev/video-none", {.camera = true}); }, "no camera");
  expectError(ErrorKind::Usage, [&] { Source::open("lavfi:nosuchfilter=1"); }, "bad lavfi");
  expectError(ErrorKind::Usage, [&] { Sink(d / "odd.mp4", {.codec = Codec::H264, .size = {161, 120}}); }, "odd H.264");
  expectError(ErrorKind::Usage, [&] { Sink(d / "x.mp4", {.codec = Codec::Ffv1, .size = {160, 120}}); }, "FFV1 in MP4");
  expectError(ErrorKind::Usage, [&] { Sink(d / "x.unknownext", {.codec = Codec::Ffv1, .size = {160, 120}}); }, "ext");
  expectError(ErrorKind::Output, [&] { Sink(d / "no/such/dir.mkv", {.codec = Codec::Ffv1, .size = {160, 120}}); }, "dir");
  expectError(ErrorKind::Usage, [&] { parseCodec("vp9"); }, "codec");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1) << "only garbage.mp4: no temporary files left";

  // A truncated file: the frames before the cut come out, then the end (no crash, no hang).
  {
    const auto frames = readAll(kPattern);
    Sink sink(d / "whole.mkv", {.codec = Codec::Ffv1, .size = {160, 120}, .frameRate = {24, 1},
                                .timeBase = Source::open(kPattern).info().timeBase});
    for (const auto& f : frames) sink.write(f);
    sink.finish();
  }
  const auto size = fs::file_size(d / "whole.mkv");
  fs::copy_file(d / "whole.mkv", d / "cut.mkv");
  fs::resize_file(d / "cut.mkv", size / 2);
  std::size_t n = 0;
  try {
    n = readAll((d / "cut.mkv").string()).size();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
  }
  EXPECT_LT(n, 48u);
}
