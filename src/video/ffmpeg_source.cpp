#include "ffmpeg.h"

extern "C" {
#include <libavutil/display.h>
}

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/video/packet.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

namespace glint::video {

namespace {
constexpr std::string_view kLavfiPrefix = "lavfi:";

struct FormatDeleter {
  void operator()(AVFormatContext* f) const { avformat_close_input(&f); }
};
using FormatPtr = std::unique_ptr<AVFormatContext, FormatDeleter>;

std::string describe(const std::string& name, SourceKind kind) {
  switch (kind) {
    case SourceKind::Camera: return fmt::format("camera '{}'", name);
    case SourceKind::Lavfi: return fmt::format("lavfi source '{}'", name);
    case SourceKind::File: break;
  }
  return fmt::format("'{}'", name);
}
/// `in` (U8 RGBA) turned counterclockwise by `quarters` quarter turns into `out`.
void turnCounterclockwise(const Image& in, int quarters, Image& out) {
  const int w = in.width(), h = in.height();
  const bool swap = quarters % 2 == 1;
  if (out.width() != (swap ? h : w) || out.height() != (swap ? w : h) || out.channels() != 4 || out.type() != PixelType::U8)
    out = Image(swap ? h : w, swap ? w : h, 4, PixelType::U8);
  const auto* src = reinterpret_cast<const std::uint32_t*>(in.bytes().data());
  auto* dst = reinterpret_cast<std::uint32_t*>(out.bytes().data());
  const int ow = out.width();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // Counterclockwise on screen (y down): a quarter turn takes (x, y) to (y, w - 1 - x).
      int tx = x, ty = y;
      switch (quarters) {
        case 1: tx = y, ty = w - 1 - x; break;
        case 2: tx = w - 1 - x, ty = h - 1 - y; break;
        case 3: tx = h - 1 - y, ty = x; break;
        default: break;
      }
      dst[std::size_t(ty) * std::size_t(ow) + std::size_t(tx)] = src[std::size_t(y) * std::size_t(w) + std::size_t(x)];
    }
  }
}

struct FfmpegSource {
  SourceOptions options;
  SourceInfo info;
  std::string what;  // for messages: "'clip.mp4'", "camera '/dev/video0'"
  FormatPtr format;
  DecoderErrorWatch decoderErrors;  // before decoder: outlives it (and its threads)
  CodecContextPtr decoder;
  RgbaConverter converter;
  FramePtr frame{av_frame_alloc()};
  PacketPtr packet{av_packet_alloc()};
  int videoStream = -1, audioStream = -1;
  std::unique_ptr<AudioTrack> audio;
  std::deque<Packet> audioPackets;
  std::int64_t startPts = kNoTimestamp;  // the stream's first timestamp: frame 0
  std::int64_t lastPts = kNoTimestamp;
  std::int64_t delivered = 0, dropped = 0, corrupt = 0, counter = 0;
  int quarterTurns = 0;  // counterclockwise quarter turns applied to every frame (applyRotation)
  Image unturned;        // a frame before it is turned
  bool flushing = false, done = false;
  // realtime pacing
  bool paceStarted = false;
  std::chrono::steady_clock::time_point paceWall;
  double paceSeconds = 0.0;

  double secondsOf(std::int64_t pts) const {
    const AVRational tb = format->streams[videoStream]->time_base;
    return double(pts - startPts) * av_q2d(tb);
  }

  std::int64_t indexOf(std::int64_t pts) {
    const Rational rate = info.frameRate;
    if (info.kind == SourceKind::Camera || !rate.valid() || pts == kNoTimestamp) return counter++;
    return std::llround(secondsOf(pts) * rate.value());
  }

  /// Where a name is read from: the URL, the input format and its options for avformat_open_input.
  struct Input {
    std::string url;
    const AVInputFormat* format = nullptr;
    AVDictionary* options = nullptr;
  };

  void open(const std::string& name);
  /// The input for `name` (a camera, a lavfi graph, stdin or a file), checked; sets info.kind.
  Input chooseInput(const std::string& name);
  /// Opens the container and finds its streams and the video stream.
  void openInput(const std::string& name);
  /// Opens the decoder of the video `stream`; fails on a video it cannot decode.
  const AVCodec* openDecoder(const std::string& name, AVStream& stream);
  /// Fills info with the video's size, rate, codec, duration and frame count.
  void describeVideo(const AVStream& stream, const AVCodec& codec);
  /// Reads the stream's display matrix: the rotation, applied here when asked.
  void applyDisplayMatrix(const AVStream& stream);
  /// Finds the audio stream (kept when asked) and discards the streams not read.
  void selectAudio();
  /// Fails on a --frames range that selects nothing.
  void checkFrameRange() const;
  double audioLead();
  void seekTo(std::int64_t frameIndex);
  bool decodeOne(Frame& frame);  // the next decoded frame, any index
  void keepAudio(AVPacket& packet);
  void pace(double seconds);
  bool read(Frame& frame);
};
}  // namespace (FfmpegSource holds the deleters above: it is this file's alone too)

void FfmpegSource::open(const std::string& name) {
  initFfmpeg();
  openInput(name);
  AVStream* stream = format->streams[videoStream];
  const AVCodec* codec = openDecoder(name, *stream);
  describeVideo(*stream, *codec);
  applyDisplayMatrix(*stream);
  startPts = stream->start_time != AV_NOPTS_VALUE ? stream->start_time : kNoTimestamp;
  selectAudio();
  checkFrameRange();
  if (options.firstFrame > 0) seekTo(options.firstFrame);
}

FfmpegSource::Input FfmpegSource::chooseInput(const std::string& name) {
  Input input{.url = name};
  if (options.camera) {
    info.kind = SourceKind::Camera;
    input.format = av_find_input_format("video4linux2");
    if (!input.format) fail(ErrorKind::Input, "this FFmpeg has no V4L2 input (libavdevice without video4linux2)");
    std::error_code ec;  // (checked before the options are made: an error here leaves nothing to free)
    if (!std::filesystem::exists(name, ec)) fail(ErrorKind::Input, "no camera at '{}' (no such device)", name);
    if (options.size.x > 0) {
      av_dict_set(&input.options, "video_size", fmt::format("{}x{}", options.size.x, options.size.y).c_str(), 0);
    }
    if (options.frameRate > 0) {
      av_dict_set(&input.options, "framerate", fmt::format("{}", options.frameRate).c_str(), 0);
    }
  } else if (name.starts_with(kLavfiPrefix)) {
    info.kind = SourceKind::Lavfi;
    input.url = name.substr(kLavfiPrefix.size());
    input.format = av_find_input_format("lavfi");
    if (!input.format) fail(ErrorKind::Input, "this FFmpeg has no lavfi input (libavdevice)");
    if (input.url.empty()) {
      fail(ErrorKind::Usage, "lavfi: needs a filter graph, e.g. lavfi:testsrc2=size=640x480:duration=2");
    }
  } else if (name == "-") {
    input.url = "pipe:0";  // a stream: no seeking (MP4 only with its index first)
  } else {
    std::error_code ec;
    if (!std::filesystem::exists(name, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", name);
    if (std::filesystem::is_directory(name, ec)) fail(ErrorKind::Input, "cannot read '{}': it is a directory", name);
  }
  return input;
}

void FfmpegSource::openInput(const std::string& name) {
  Input input = chooseInput(name);
  info.name = name;
  what = describe(name, info.kind);

  AVFormatContext* raw = nullptr;
  const int e = avformat_open_input(&raw, input.url.c_str(), input.format, &input.options);
  av_dict_free(&input.options);
  if (e < 0) {
    if (info.kind == SourceKind::Camera) fail(ErrorKind::Input, "cannot open camera '{}': {}", name, ffmpegError(e));
    if (info.kind == SourceKind::Lavfi) fail(ErrorKind::Usage, "bad lavfi graph '{}': {}", input.url, ffmpegError(e));
    fail(ErrorKind::Input, "cannot read '{}': {}", name, ffmpegError(e));
  }
  format.reset(raw);
  if (const int s = avformat_find_stream_info(format.get(), nullptr); s < 0) {
    fail(ErrorKind::Input, "cannot read {}: {}", what, ffmpegError(s));
  }
  videoStream = av_find_best_stream(format.get(), AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (videoStream < 0) fail(ErrorKind::Input, "{} has no video stream", what);
}

const AVCodec* FfmpegSource::openDecoder(const std::string& name, AVStream& stream) {
  const AVCodec* codec = avcodec_find_decoder(stream.codecpar->codec_id);
  if (!codec) {
    fail(ErrorKind::Input, "{}: no decoder for its '{}' video", what, avcodec_get_name(stream.codecpar->codec_id));
  }
  decoder.reset(avcodec_alloc_context3(codec));
  avcodec_parameters_to_context(decoder.get(), stream.codecpar);
  decoder->thread_count = options.threads;
  decoder->thread_type = FF_THREAD_FRAME | FF_THREAD_SLICE;
  decoder->pkt_timebase = stream.time_base;
  decoderErrors.attach(*decoder);
  if (const int o = avcodec_open2(decoder.get(), codec, nullptr); o < 0) {
    fail(ErrorKind::Input, "{}: cannot decode its {} video: {}", what, codec->name, ffmpegError(o));
  }
  if (decoder->width <= 0 || decoder->height <= 0) fail(ErrorKind::Input, "{}: the video has no size", what);
  if (decoder->pix_fmt == AV_PIX_FMT_NONE) {
    if (name == "-" && std::string_view(format->iformat->name).find("mp4") != std::string_view::npos) {
      fail(ErrorKind::Input, "an MP4 cannot be read from stdin unless its index comes first (ffmpeg -movflags "
           "+faststart): give the file's name, or pipe a container that streams (mkv, nut, ts)");
    }
    fail(ErrorKind::Input, "{}: unknown pixel format", what);
  }
  return codec;
}

void FfmpegSource::describeVideo(const AVStream& stream, const AVCodec& codec) {
  info.size = {decoder->width, decoder->height};
  AVRational rate = stream.avg_frame_rate.num > 0 ? stream.avg_frame_rate : stream.r_frame_rate;
  info.frameRate = toRational(rate);
  info.timeBase = toRational(stream.time_base);
  info.container = format->iformat->name;
  info.codec = codec.name;
  info.pixelFormat = av_get_pix_fmt_name(decoder->pix_fmt) ? av_get_pix_fmt_name(decoder->pix_fmt) : "?";
  info.live = info.kind == SourceKind::Camera || options.realtime;
  if (format->duration > 0 && info.kind == SourceKind::File) info.durationSeconds = double(format->duration) / AV_TIME_BASE;
  if (stream.duration > 0 && info.kind == SourceKind::File) info.durationSeconds = double(stream.duration) * av_q2d(stream.time_base);
  if (info.kind == SourceKind::File) {
    if (stream.nb_frames > 0) {
      info.frameCount = stream.nb_frames;
      info.frameCountExact = true;
    } else if (info.durationSeconds > 0 && info.frameRate.valid()) {
      info.frameCount = std::llround(info.durationSeconds * info.frameRate.value());
    }
  }
}

void FfmpegSource::applyDisplayMatrix(const AVStream& stream) {
  // A phone's portrait clip is stored sideways with a display matrix that turns it.
  std::size_t matrixSize = 0;
  if (const std::uint8_t* m = streamSideData(stream, AV_PKT_DATA_DISPLAYMATRIX, matrixSize);
      m && matrixSize >= 9 * sizeof(std::int32_t)) {
    const auto* values = reinterpret_cast<const std::int32_t*>(m);
    info.displayMatrix.assign(values, values + 9);
    const double degrees = av_display_rotation_get(values);
    if (std::isfinite(degrees)) info.rotation = int(((std::lround(degrees) % 360) + 360) % 360);
    // Turned here when asked, by quarter turns without a mirror (the matrices phones write).
    const bool mirrored = double(values[0]) * double(values[4]) - double(values[1]) * double(values[3]) < 0.0;
    if (options.applyRotation && info.rotation % 90 == 0 && !mirrored) {
      quarterTurns = info.rotation / 90;
      info.rotationApplied = true;
      info.displayMatrix.clear();
      if (quarterTurns % 2 == 1) std::swap(info.size.x, info.size.y);
      this->options.yuv420 = this->options.yuv420 && quarterTurns == 0;
    }
  }
}

void FfmpegSource::selectAudio() {
  // Found even when not kept, so a report can say "dropped (--no-audio)" rather than "none".
  if (const int found = av_find_best_stream(format.get(), AVMEDIA_TYPE_AUDIO, -1, videoStream, nullptr, 0); found >= 0) {
    AVStream* a = format->streams[found];
    info.hasAudio = true;
    info.audioCodec = avcodec_get_name(a->codecpar->codec_id);
    if (options.keepAudio) {
      audioStream = found;
    }
  }
  // Only the streams glint reads are demuxed.
  for (unsigned i = 0; i < format->nb_streams; ++i)
    if (int(i) != videoStream && int(i) != audioStream) format->streams[i]->discard = AVDISCARD_ALL;
  if (audioStream >= 0) {
    AVStream* a = format->streams[audioStream];
    audio = std::make_unique<AudioTrack>(*a->codecpar, a->time_base, audioLead());
  }
}

void FfmpegSource::checkFrameRange() const {
  if (options.firstFrame < 0) fail(ErrorKind::Usage, "--frames: the first frame must not be negative");
  if (options.lastFrame >= 0 && options.lastFrame <= options.firstFrame) {
    fail(ErrorKind::Usage, "--frames {}:{} selects no frames", options.firstFrame, options.lastFrame);
  }
}

// How long before the video's start the audio begins when it begins before 0 (AAC priming
// in an MP4: its first packet is stamped -1024 samples, though start_time says 0). Read
// from the first packets of the file through a second demuxer (this one stays where it is),
// so a part made with --frames knows the whole file's lead too. 0 for anything but a file,
// and for Opus, whose pre-skip Matroska keeps as CodecDelay.
double FfmpegSource::audioLead() {
  if (info.kind != SourceKind::File || info.name == "-") return 0.0;
  if (format->streams[audioStream]->codecpar->codec_id == AV_CODEC_ID_OPUS) return 0.0;
  AVFormatContext* raw = nullptr;
  if (avformat_open_input(&raw, info.name.c_str(), nullptr, nullptr) < 0) return 0.0;
  FormatPtr probe(raw);
  if (avformat_find_stream_info(probe.get(), nullptr) < 0) return 0.0;
  if (int(probe->nb_streams) <= std::max(videoStream, audioStream)) return 0.0;
  AVStream* video = probe->streams[videoStream];
  AVStream* a = probe->streams[audioStream];
  for (unsigned i = 0; i < probe->nb_streams; ++i)
    if (int(i) != videoStream && int(i) != audioStream) probe->streams[i]->discard = AVDISCARD_ALL;
  std::int64_t firstAudio = AV_NOPTS_VALUE, firstVideo = video->start_time;
  PacketPtr p{av_packet_alloc()};
  for (int i = 0; i < 4096 && (firstAudio == AV_NOPTS_VALUE || firstVideo == AV_NOPTS_VALUE); ++i) {
    if (av_read_frame(probe.get(), p.get()) < 0) break;
    if (p->stream_index == audioStream && firstAudio == AV_NOPTS_VALUE) firstAudio = p->pts;
    else if (p->stream_index == videoStream && firstVideo == AV_NOPTS_VALUE) firstVideo = p->pts;
    av_packet_unref(p.get());
  }
  if (firstAudio == AV_NOPTS_VALUE || firstVideo == AV_NOPTS_VALUE) return 0.0;
  // Only a negative first timestamp makes a muxer shift the file (positive ones are kept).
  const double audioStart = double(firstAudio) * av_q2d(a->time_base);
  return audioStart < 0.0 ? std::max(0.0, double(firstVideo) * av_q2d(video->time_base) - audioStart) : 0.0;
}

void FfmpegSource::seekTo(std::int64_t frameIndex) {
  if (info.kind != SourceKind::File || !info.frameRate.valid()) return;  // decode and skip instead
  if (startPts == kNoTimestamp) return;
  const AVRational tb = format->streams[videoStream]->time_base;
  // One frame early: the keyframe search is on timestamps, and rounding must not land past it.
  const double seconds = double(frameIndex - 1) / info.frameRate.value();
  const std::int64_t target = startPts + std::int64_t(std::floor(seconds / av_q2d(tb)));
  if (av_seek_frame(format.get(), videoStream, std::max(target, startPts), AVSEEK_FLAG_BACKWARD) >= 0) {
    avcodec_flush_buffers(decoder.get());
  } else {
    log::debug("{}: cannot seek; decoding from the start to frame {}", what, frameIndex);
  }
}

void FfmpegSource::keepAudio(AVPacket& p) {
  if (!audio) return;
  // Keep the audio of the selected frames: [first, last) in time.
  if (p.pts != AV_NOPTS_VALUE && info.frameRate.valid() && startPts != kNoTimestamp) {
    const double t = double(p.pts) * av_q2d(audio->timeBase()) - double(startPts) * av_q2d(format->streams[videoStream]->time_base);
    // From the first frame on, everything before it too: an encoder's priming packets have
    // negative timestamps (AAC's first 1024 samples, Opus's pre-skip), and a copy keeps them.
    const double from = options.firstFrame > 0 ? double(options.firstFrame) / info.frameRate.value() : -INFINITY;
    const double to = options.lastFrame >= 0 ? double(options.lastFrame) / info.frameRate.value() : INFINITY;
    if (t < from - 1e-6 || t >= to - 1e-6) return;
  }
  AVPacket* copy = av_packet_clone(&p);
  if (copy) audioPackets.emplace_back(copy);
}

void FfmpegSource::pace(double seconds) {
  if (!paceStarted) {
    paceStarted = true;
    paceWall = std::chrono::steady_clock::now();
    paceSeconds = seconds;
    return;
  }
  const auto due = paceWall + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(seconds - paceSeconds));
  std::this_thread::sleep_until(due);
}

bool FfmpegSource::decodeOne(Frame& out) {
  while (true) {
    const int r = avcodec_receive_frame(decoder.get(), frame.get());
    if (r == 0) {
      std::int64_t pts = frame->best_effort_timestamp;
      if (pts == AV_NOPTS_VALUE) pts = frame->pts;
      if (startPts == kNoTimestamp && pts != AV_NOPTS_VALUE) startPts = pts;
      if (pts == AV_NOPTS_VALUE) pts = kNoTimestamp;
      if (!options.yuv420 || !takeYuv420(*frame, out)) {
        if (quarterTurns == 0) {
          converter.toRgba(*frame, out.image);
        } else {
          converter.toRgba(*frame, unturned);
          turnCounterclockwise(unturned, quarterTurns, out.image);
        }
        out.format = FrameFormat::Rgba;
      }
      out.pts = pts;
      out.seconds = pts != kNoTimestamp ? secondsOf(pts) : 0.0;
      out.index = indexOf(pts);
      if (info.live && pts != kNoTimestamp && lastPts != kNoTimestamp && info.frameRate.valid()) {
        const double frames = double(pts - lastPts) * av_q2d(format->streams[videoStream]->time_base) *
                              info.frameRate.value();
        if (frames > 1.5) dropped += std::llround(frames) - 1;
      }
      if (pts != kNoTimestamp) lastPts = pts;
      av_frame_unref(frame.get());
      return true;
    }
    if (r == AVERROR_EOF) return false;
    if (r != AVERROR(EAGAIN)) fail(ErrorKind::Input, "{}: decoding failed: {}", what, ffmpegError(r));
    if (flushing) return false;

    const int read = av_read_frame(format.get(), packet.get());
    if (read == AVERROR_EOF || (read < 0 && info.kind != SourceKind::Camera && avio_feof(format->pb))) {
      flushing = true;
      avcodec_send_packet(decoder.get(), nullptr);
      continue;
    }
    if (read < 0) {
      if (info.kind == SourceKind::Camera) {
        fail(ErrorKind::Input, "camera '{}' stopped delivering frames: {}", info.name, ffmpegError(read));
      }
      fail(ErrorKind::Input, "cannot read {}: {}", what, ffmpegError(read));
    }
    if (packet->stream_index == videoStream) {
      const int s = avcodec_send_packet(decoder.get(), packet.get());
      if (s == AVERROR_INVALIDDATA) {
        ++corrupt;
        log::warn("{}: a corrupt video packet at {:.3f} s could not be decoded; its frame is missing", what,
                  packet->pts != AV_NOPTS_VALUE && startPts != kNoTimestamp ? secondsOf(packet->pts) : -1.0);
      } else if (s < 0 && s != AVERROR(EAGAIN)) {
        av_packet_unref(packet.get());
        fail(ErrorKind::Input, "{}: decoding failed: {}", what, ffmpegError(s));
      }
    } else if (packet->stream_index == audioStream) {
      keepAudio(*packet);
    }
    av_packet_unref(packet.get());
  }
}

// ---------------------------------------------------------------------------
bool FfmpegSource::read(Frame& frame) {
  if (done) return false;
  while (decodeOne(frame)) {
    if (frame.index < options.firstFrame) continue;  // decoded from the keyframe before it
    if (options.lastFrame >= 0 && frame.index >= options.lastFrame) break;
    if (options.realtime && info.kind != SourceKind::Camera) pace(frame.seconds);
    ++delivered;
    return true;
  }
  done = true;
  return false;
}

// The module's entry points (backend.h): FfmpegSource behind an opaque handle.
namespace backend {
namespace {
FfmpegSource& cast(SourceHandle* h) { return *reinterpret_cast<FfmpegSource*>(h); }
const FfmpegSource& cast(const SourceHandle* h) { return *reinterpret_cast<const FfmpegSource*>(h); }
}  // namespace

SourceHandle* openSource(const std::string& name, const SourceOptions& options, Status& status) {
  return guarded(status, [&] {
    auto source = std::make_unique<FfmpegSource>();
    source->options = options;
    source->open(name);
    return reinterpret_cast<SourceHandle*>(source.release());
  }, static_cast<SourceHandle*>(nullptr));
}
void closeSource(SourceHandle* h) { delete &cast(h); }
const SourceInfo* sourceInfo(const SourceHandle* h) { return &cast(h).info; }
bool read(SourceHandle* h, Frame& frame, Status& status) {
  return guarded(status, [&] { return cast(h).read(frame); }, false);
}
void takeAudio(SourceHandle* h, std::deque<Packet>& packets) { packets = std::exchange(cast(h).audioPackets, {}); }
const AudioTrack* audio(const SourceHandle* h) { return cast(h).audio.get(); }
void counters(const SourceHandle* h, std::int64_t out[5]) {
  const FfmpegSource& s = cast(h);
  out[0] = s.dropped;
  out[1] = s.corrupt;
  out[2] = s.delivered;
  out[3] = s.decoderErrors.count();
  out[4] = s.lastPts == kNoTimestamp || s.startPts == kNoTimestamp ? -1 : std::llround(s.secondsOf(s.lastPts) * 1e6);
}
std::string firstDecoderError(const SourceHandle* h) { return cast(h).decoderErrors.first(); }

FrameIndex indexFrames(const std::string& name, Status& status) {
  return guarded(status, [&] {
    // Packets only, no decoding: the same numbering as FfmpegSource::indexOf (the stream's
    // start time is frame 0, index = seconds × average rate).
    AVFormatContext* raw = nullptr;
    if (const int e = avformat_open_input(&raw, name.c_str(), nullptr, nullptr); e < 0)
      fail(ErrorKind::Input, "cannot read '{}': {}", name, ffmpegError(e));
    FormatPtr format(raw);
    if (const int s = avformat_find_stream_info(format.get(), nullptr); s < 0)
      fail(ErrorKind::Input, "cannot read '{}': {}", name, ffmpegError(s));
    const int video = av_find_best_stream(format.get(), AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
    if (video < 0) fail(ErrorKind::Input, "'{}' has no video stream", name);
    AVStream* stream = format->streams[video];
    for (unsigned i = 0; i < format->nb_streams; ++i)
      if (int(i) != video) format->streams[i]->discard = AVDISCARD_ALL;
    const AVRational rate = stream->avg_frame_rate.num > 0 ? stream->avg_frame_rate : stream->r_frame_rate;
    FrameIndex index;
    index.frameRate = toRational(rate);
    std::int64_t start = stream->start_time != AV_NOPTS_VALUE ? stream->start_time : kNoTimestamp;
    std::vector<std::pair<std::int64_t, bool>> packets;  // (pts or decode position, keyframe)
    bool timestamps = rate.num > 0;
    PacketPtr packet{av_packet_alloc()};
    std::int64_t counter = 0;
    while (av_read_frame(format.get(), packet.get()) >= 0) {
      if (packet->stream_index == video) {
        const std::int64_t pts = packet->pts;
        if (pts == AV_NOPTS_VALUE) timestamps = false;
        packets.emplace_back(pts == AV_NOPTS_VALUE ? counter : pts, (packet->flags & AV_PKT_FLAG_KEY) != 0);
        ++counter;
      }
      av_packet_unref(packet.get());
    }
    if (timestamps && start == kNoTimestamp && !packets.empty()) {
      start = packets.front().first;
      for (const auto& p : packets) start = std::min(start, p.first);
    }
    std::vector<std::int64_t> frames;
    for (std::size_t i = 0; i < packets.size(); ++i) {
      const std::int64_t frame =
          timestamps ? std::llround(double(packets[i].first - start) * av_q2d(stream->time_base) * av_q2d(rate))
                     : std::int64_t(i);
      frames.push_back(frame);
      if (packets[i].second) index.keyframes.push_back(frame);
    }
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    std::sort(index.keyframes.begin(), index.keyframes.end());
    index.keyframes.erase(std::unique(index.keyframes.begin(), index.keyframes.end()), index.keyframes.end());
    index.frameCount = std::int64_t(frames.size());
    return index;
  }, FrameIndex{});
}
}  // namespace backend

}  // namespace glint::video
