#include "ffmpeg.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/video/packet.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint::video {

namespace {
/// glint's rule for copying audio into a container, the same on every FFmpeg: an MP4 holds
/// the codecs its family registers (AAC, MP3, AC-3, E-AC-3, ALAC, Opus, FLAC), not PCM, which
/// FFmpeg 5.1 refused there and 7.1 writes where players do not expect it; every other
/// container takes what its muxer takes (Matroska, NUT and MOV take PCM).
bool audioFits(const AVOutputFormat& format, AVCodecID codec) {
  if (std::string_view(format.name) == "mp4") {
    return codec == AV_CODEC_ID_AAC || codec == AV_CODEC_ID_MP3 || codec == AV_CODEC_ID_AC3 ||
           codec == AV_CODEC_ID_EAC3 || codec == AV_CODEC_ID_ALAC || codec == AV_CODEC_ID_OPUS ||
           codec == AV_CODEC_ID_FLAC;
  }
  return avformat_query_codec(&format, codec, FF_COMPLIANCE_NORMAL) == 1;
}

/// Whether this FFmpeg's Matroska muxer stores any audio codec's initial padding as the
/// track's CodecDelay and keeps the packets inside it at negative timestamps (FFmpeg 6.1 and
/// later; 5.1 does so for Opus only). Asked of the muxer itself, once: a header written to
/// memory for a PCM track with 48 samples of padding holds CodecDelay's ID (0x56AA) or not.
bool matroskaKeepsCodecDelay() {
  static const bool keeps = [] {
    AVFormatContext* raw = nullptr;
    if (avformat_alloc_output_context2(&raw, nullptr, "matroska", nullptr) < 0 || !raw) return false;
    std::unique_ptr<AVFormatContext, void (*)(AVFormatContext*)> output(raw, avformat_free_context);
    AVStream* stream = avformat_new_stream(raw, nullptr);
    if (!stream) return false;
    AVCodecParameters& p = *stream->codecpar;
    p.codec_type = AVMEDIA_TYPE_AUDIO;
    p.codec_id = AV_CODEC_ID_PCM_S16LE;
    p.sample_rate = 48000;
    p.format = AV_SAMPLE_FMT_S16;
    av_channel_layout_default(&p.ch_layout, 1);
    p.initial_padding = 48;
    stream->time_base = {1, 48000};
    if (avio_open_dyn_buf(&raw->pb) < 0) return false;
    const bool written = avformat_write_header(raw, nullptr) >= 0 && av_write_trailer(raw) >= 0;
    std::uint8_t* bytes = nullptr;
    const int size = avio_close_dyn_buf(raw->pb, &bytes);
    raw->pb = nullptr;
    static constexpr std::uint8_t kCodecDelay[] = {0x56, 0xAA};
    const bool found = written && bytes && std::search(bytes, bytes + size, std::begin(kCodecDelay), std::end(kCodecDelay)) != bytes + size;
    av_free(bytes);
    return found;
  }();
  return keeps;
}

/// Whether glint hands a container the audio's negative timestamps as they are (AAC's
/// priming packet before the first frame), which then keeps the source's timeline: the MP4
/// family stores them in its edit list whatever FFmpeg's flags say (5.1 flags its muxer
/// AVFMT_TS_NEGATIVE, 7.1 does not, and would shift the audio by the lead), every container
/// that flags them, and Matroska where the lead lies within the audio's initial padding and
/// this FFmpeg writes that as CodecDelay (7.1's Matroska keeps AAC's -1024 samples so).
/// Elsewhere the file is offset by the source's lead instead (the caller).
bool keepsNegativeTimestamps(const AVOutputFormat& format, const AVCodecParameters& audio, double leadSeconds) {
  static constexpr std::string_view kMovFamily[] = {"mov", "mp4", "ipod", "3gp", "3g2", "psp", "ismv", "f4v"};
  const std::string_view name = format.name;
  if ((format.flags & AVFMT_TS_NEGATIVE) || std::find(std::begin(kMovFamily), std::end(kMovFamily), name) != std::end(kMovFamily))
    return true;
  const bool matroska = name.find("matroska") != std::string_view::npos || name == "webm";
  // Half a millisecond of slack: the lead was measured in the source's time base.
  return matroska && audio.sample_rate > 0 && audio.initial_padding > 0 &&
         leadSeconds <= double(audio.initial_padding) / audio.sample_rate + 0.0005 && matroskaKeepsCodecDelay();
}

/// FFmpeg's reason a write failed, or "no space left on device (N KiB free ...)" for a full disk.
std::string writeError(const std::filesystem::path& destination, int code) {
  if (code == AVERROR(ENOSPC) || code == AVERROR(EDQUOT)) return writeFailure(destination, ENOSPC);
  return ffmpegError(code);
}
}  // namespace

namespace fs = std::filesystem;

namespace {
struct OutputDeleter {
  void operator()(AVFormatContext* f) const {
    if (!f) return;
    if (f->pb && !(f->oformat->flags & AVFMT_NOFILE)) avio_closep(&f->pb);
    avformat_free_context(f);
  }
};
using OutputPtr = std::unique_ptr<AVFormatContext, OutputDeleter>;

// The muxer for a destination's extension; Error(Usage) when FFmpeg knows none.
OutputPtr createOutput(const fs::path& destination, const fs::path& tmp, const std::string& streamFormat = {}) {
  const bool toStdout = destination == "-";
  const AVOutputFormat* format =
      av_guess_format(nullptr, toStdout ? ("stdout." + streamFormat).c_str() : destination.filename().c_str(), nullptr);
  if (toStdout) {
    if (streamFormat.empty()) fail(ErrorKind::Usage, "-o - (stdout) needs --format: mkv, nut or ts for a video");
    if (!format) fail(ErrorKind::Usage, "--format {}: not a video container FFmpeg knows (mkv, nut or ts stream)", streamFormat);
    const std::string_view name = format->name;
    if (name.find("mp4") != std::string_view::npos || name.find("mov") != std::string_view::npos ||
        name == "ipod" || name == "3gp" || name == "ismv" || name == "f4v") {
      fail(ErrorKind::Usage, "an {} cannot be written to stdout: its index goes at the end of the file, which needs "
           "seeking; use --format mkv, nut or ts", streamFormat);
    }
  }
  if (!format) {
    fail(ErrorKind::Usage, "cannot tell the video format of '{}' from its extension (use .mp4, .mkv, .mov, .avi or .nut)",
         destination.string());
  }
  AVFormatContext* raw = nullptr;
  const int e = avformat_alloc_output_context2(&raw, format, nullptr, tmp.c_str());
  if (e < 0 || !raw) fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeError(destination, e));
  // The same frames give the same bytes: no random Matroska segment UID, no creation time,
  // no library version strings (found by tests/reliability's kill and determinism tests).
  raw->flags |= AVFMT_FLAG_BITEXACT;
  return OutputPtr(raw);
}

void openFile(AVFormatContext& output, const fs::path& tmp, const fs::path& destination) {
  if (output.oformat->flags & AVFMT_NOFILE) return;
  if (const int e = avio_open(&output.pb, tmp.c_str(), AVIO_FLAG_WRITE); e < 0) {
    fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeError(destination, e));
  }
}

/// Fails on options no encoder takes: the size, an odd size for H.264, the CRF.
void checkSinkOptions(const SinkOptions& options) {
  if (options.size.x <= 0 || options.size.y <= 0) fail(ErrorKind::Usage, "video size must be positive");
  if (options.codec == Codec::H264 && (options.size.x % 2 || options.size.y % 2)) {
    fail(ErrorKind::Usage, "H.264 (yuv420p) needs an even width and height, got {}x{}; use --codec ffv1",
         options.size.x, options.size.y);
  }
  if (options.crf < 0 || options.crf > 51) fail(ErrorKind::Usage, "--crf must be 0..51, got {}", options.crf);
}

/// The encoder of the options' codec, after checking that the destination's format holds it.
const AVCodec* findEncoder(const fs::path& destination, const SinkOptions& options) {
  // Fail on a format that cannot hold the codec before making any file.
  const AVOutputFormat* guessed = av_guess_format(nullptr, destination.filename().c_str(), nullptr);
  const AVCodecID id = options.codec == Codec::H264 ? AV_CODEC_ID_H264 : AV_CODEC_ID_FFV1;
  if (guessed && avformat_query_codec(guessed, id, FF_COMPLIANCE_NORMAL) != 1) {
    fail(ErrorKind::Usage, "{} video cannot go into a {} file ({}); use {}", codecName(options.codec),
         destination.extension().string(), guessed->name, options.codec == Codec::H264 ? ".mp4 or .mkv" : ".mkv");
  }
  const AVCodec* codec = options.codec == Codec::H264 ? avcodec_find_encoder_by_name("libx264")
                                                      : avcodec_find_encoder(AV_CODEC_ID_FFV1);
  if (!codec) fail(ErrorKind::Internal, "this FFmpeg has no {} encoder", options.codec == Codec::H264 ? "libx264" : "FFV1");
  return codec;
}

struct FfmpegSink {
  SinkOptions options;
  fs::path destination;
  OutputPtr output;
  CodecContextPtr encoder;
  AVStream* videoStream = nullptr;
  AVStream* audioStream = nullptr;
  const AudioTrack* audio = nullptr;
  bool matroska = false;  // the output is Matroska (or WebM)
  std::string audioNote;
  RgbaConverter converter;
  FramePtr frame{av_frame_alloc()};
  PacketPtr packet{av_packet_alloc()};
  std::int64_t written = 0;
  std::int64_t lastPts = kNoTimestamp;
  bool headerWritten = false, finished = false;

  FfmpegSink(const fs::path& destination, const fs::path& target, const SinkOptions& options);
  /// Sets up the encoder for the options' codec, size and rate, and opens it.
  void openEncoder(const AVCodec& codec, Rational rate, Rational timeBase);
  /// Adds the video stream (with the source's display matrix) to the output.
  void addVideoStream();
  /// Adds the audio stream when the container holds its codec (else notes why not), and
  /// offsets the file by the audio's lead where the container cannot keep it.
  void addAudioStream();
  /// Opens the file and writes the container's header.
  void writeHeader(const fs::path& target);
  void drain(bool flushing);
  void writePacket(AVPacket& p);
  void write(const Frame& frame);
  void writeAudio(Packet packet);
  void finish();
};
}  // namespace (FfmpegSink holds the deleters above: it is this file's alone too)

void FfmpegSink::writePacket(AVPacket& p) {
  if (const int e = av_interleaved_write_frame(output.get(), &p); e < 0) {
    fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeError(destination, e));
  }
}

void FfmpegSink::drain(bool flushing) {
  while (true) {
    const int r = avcodec_receive_packet(encoder.get(), packet.get());
    if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
    if (r < 0) fail(ErrorKind::Internal, "encoding '{}' failed: {}", destination.string(), ffmpegError(r));
    av_packet_rescale_ts(packet.get(), encoder->time_base, videoStream->time_base);
    packet->stream_index = videoStream->index;
    writePacket(*packet);
    (void)flushing;
  }
}

FfmpegSink::FfmpegSink(const fs::path& destination_, const fs::path& target_, const SinkOptions& options_) {
  initFfmpeg();
  FfmpegSink& s = *this;
  const fs::path& destination = destination_;
  const SinkOptions& options = options_;
  s.options = options;
  s.destination = destination;
  checkSinkOptions(options);
  const Rational rate = options.frameRate.valid() ? options.frameRate : Rational{30, 1};
  const Rational timeBase = options.timeBase.valid() ? options.timeBase : Rational{rate.den, rate.num};
  const AVCodec* codec = findEncoder(destination, options);

  // A file goes into the caller's temporary (renamed when the run's outputs are committed);
  // stdout ("-") is written as it is made.
  const fs::path target = destination == "-" ? fs::path("pipe:1") : target_;
  s.output = createOutput(destination, target, options.format);

  openEncoder(*codec, rate, timeBase);
  addVideoStream();
  addAudioStream();
  writeHeader(target);

  const AVCodecContext& e = *s.encoder;
  s.frame->format = e.pix_fmt;
  s.frame->width = e.width;
  s.frame->height = e.height;
  s.frame->colorspace = e.colorspace;
  s.frame->color_range = e.color_range;
}

void FfmpegSink::openEncoder(const AVCodec& codec, Rational rate, Rational timeBase) {
  encoder.reset(avcodec_alloc_context3(&codec));
  AVCodecContext& e = *encoder;
  e.width = options.size.x;
  e.height = options.size.y;
  e.time_base = toAv(timeBase);
  e.framerate = toAv(rate);
  e.sample_aspect_ratio = {1, 1};
  e.thread_count = options.threads;
  if (options.codec == Codec::H264) {
    e.pix_fmt = AV_PIX_FMT_YUV420P;
    e.colorspace = AVCOL_SPC_BT709;
    e.color_range = AVCOL_RANGE_MPEG;
    e.color_primaries = AVCOL_PRI_BT709;
    e.color_trc = AVCOL_TRC_BT709;
    av_opt_set(e.priv_data, "preset", options.preset.c_str(), 0);
    av_opt_set(e.priv_data, "crf", std::to_string(options.crf).c_str(), 0);
    if (options.noReordering) e.max_b_frames = 0;
  } else {
    e.pix_fmt = AV_PIX_FMT_0RGB32;  // bgr0 in memory on little-endian machines: 8-bit RGB
    e.gop_size = 1;                 // every frame a keyframe: cut and join anywhere
    e.level = 3;
    av_opt_set(e.priv_data, "slicecrc", "1", 0);
  }
  if (output->oformat->flags & AVFMT_GLOBALHEADER) e.flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  e.flags |= AV_CODEC_FLAG_BITEXACT;  // no encoder version string in the stream either
  if (const int o = avcodec_open2(&e, &codec, nullptr); o < 0) {
    fail(ErrorKind::Internal, "cannot start the {} encoder: {}", codec.name, ffmpegError(o));
  }
}

void FfmpegSink::addVideoStream() {
  videoStream = avformat_new_stream(output.get(), nullptr);
  avcodec_parameters_from_context(videoStream->codecpar, encoder.get());
  videoStream->time_base = encoder->time_base;
  videoStream->avg_frame_rate = encoder->framerate;
  if (options.displayMatrix.size() == 9) {  // a rotated source stays rotated
    std::uint8_t* m = newStreamSideData(*videoStream, AV_PKT_DATA_DISPLAYMATRIX, 9 * sizeof(std::int32_t));
    if (!m) fail(ErrorKind::Internal, "cannot add the display matrix to '{}'", destination.string());
    std::memcpy(m, options.displayMatrix.data(), 9 * sizeof(std::int32_t));
  }
}

void FfmpegSink::addAudioStream() {
  if (options.audio) {
    const AVCodecParameters& a = options.audio->parameters();
    if (audioFits(*output->oformat, a.codec_id)) {
      audioStream = avformat_new_stream(output.get(), nullptr);
      avcodec_parameters_copy(audioStream->codecpar, &a);
      audioStream->codecpar->codec_tag = 0;
      audioStream->time_base = options.audio->timeBase();
      audio = options.audio;
    } else {
      audioNote = fmt::format("{} audio cannot go into a {} file: dropped (use .mkv to keep it)",
                              avcodec_get_name(a.codec_id), destination.extension().string());
    }
  }

  // Audio that starts before the first frame (AAC priming) has negative timestamps; a
  // container that cannot store them (Matroska) would shift the whole file by the lead of
  // whatever it is given first. Shifting by the source's lead instead gives every part of a
  // split video (`--frames`) the same timeline as the whole, so the parts join with --concat
  // into the very bytes of one run.
  if (audio && audio->leadSeconds() > 0 &&
      !keepsNegativeTimestamps(*output->oformat, audio->parameters(), audio->leadSeconds()))
    output->output_ts_offset = std::llround(audio->leadSeconds() * AV_TIME_BASE);
}

void FfmpegSink::writeHeader(const fs::path& target) {
  matroska = std::string_view(output->oformat->name).find("matroska") != std::string_view::npos ||
             std::string_view(output->oformat->name) == "webm";
  openFile(*output, target, destination);
  if (const int h = avformat_write_header(output.get(), nullptr); h < 0) {
    fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeError(destination, h));
  }
  headerWritten = true;
}

void FfmpegSink::write(const Frame& frame) {
  FfmpegSink& s = *this;
  if (s.finished) fail(ErrorKind::Internal, "Sink::write after finish()");
  const int rows = frame.format == FrameFormat::Yuv420 ? s.encoder->height + s.encoder->height / 2 : s.encoder->height;
  if (frame.image.width() != s.encoder->width || frame.image.height() != rows) {
    fail(ErrorKind::Internal, "frame {}x{} does not match the video's {}x{}", frame.image.width(),
         frame.image.height(), s.encoder->width, s.encoder->height);
  }
  // Encoders keep references to frames they have not finished: write into a fresh buffer
  // when the previous one is still in use.
  if (const int w = av_frame_make_writable(s.frame.get()); w < 0 || !s.frame->data[0]) {
    av_frame_unref(s.frame.get());
    s.frame->format = s.encoder->pix_fmt;
    s.frame->width = s.encoder->width;
    s.frame->height = s.encoder->height;
    s.frame->colorspace = s.encoder->colorspace;
    s.frame->color_range = s.encoder->color_range;
    if (const int b = av_frame_get_buffer(s.frame.get(), 0); b < 0) {
      fail(ErrorKind::Internal, "out of memory for a video frame: {}", ffmpegError(b));
    }
  }
  if (frame.format == FrameFormat::Yuv420) s.converter.fromYuv420(frame.image, frame.matrix, *s.frame);
  else s.converter.fromRgba(frame.image, *s.frame);
  std::int64_t pts = frame.pts != kNoTimestamp ? frame.pts : (s.lastPts == kNoTimestamp ? 0 : s.lastPts + 1);
  if (s.lastPts != kNoTimestamp && pts <= s.lastPts) pts = s.lastPts + 1;  // encoders need increasing pts
  s.lastPts = pts;
  s.frame->pts = pts;
  s.frame->pict_type = AV_PICTURE_TYPE_NONE;
  if (const int r = avcodec_send_frame(s.encoder.get(), s.frame.get()); r < 0) {
    fail(ErrorKind::Internal, "encoding '{}' failed: {}", s.destination.string(), ffmpegError(r));
  }
  s.drain(false);
  ++s.written;
}

void FfmpegSink::writeAudio(Packet packet) {
  FfmpegSink& s = *this;
  if (!s.audioStream || !packet) return;
  AVPacket* p = packet.get();
  // Matroska reads only the end trim of an MP4's skip-samples note (as DiscardPadding); a
  // note with none would still turn the block into a BlockGroup with DiscardPadding 0, which
  // a file read back (a --frames part joined by --concat) no longer has.
  if (std::size_t size = 0; s.matroska) {
    const std::uint8_t* skip = av_packet_get_side_data(p, AV_PKT_DATA_SKIP_SAMPLES, &size);
    if (skip && size >= 8 && AV_RL32(skip + 4) == 0) {
      for (int i = 0; i < p->side_data_elems; ++i) {
        if (p->side_data[i].type != AV_PKT_DATA_SKIP_SAMPLES) continue;
        av_freep(&p->side_data[i].data);
        p->side_data[i] = p->side_data[--p->side_data_elems];
        break;
      }
    }
  }
  av_packet_rescale_ts(p, s.audio->timeBase(), s.audioStream->time_base);
  p->stream_index = s.audioStream->index;
  p->pos = -1;
  s.writePacket(*p);
}

void FfmpegSink::finish() {
  FfmpegSink& s = *this;
  if (s.finished) return;
  if (const int r = avcodec_send_frame(s.encoder.get(), nullptr); r < 0 && r != AVERROR_EOF) {
    fail(ErrorKind::Internal, "encoding '{}' failed: {}", s.destination.string(), ffmpegError(r));
  }
  s.drain(true);
  if (const int t = av_write_trailer(s.output.get()); t < 0) {
    fail(ErrorKind::Output, "cannot write '{}': {}", s.destination.string(), writeError(s.destination, t));
  }
  if (!(s.output->oformat->flags & AVFMT_NOFILE)) avio_closep(&s.output->pb);
  s.finished = true;
}


// ---------------------------------------------------------------------------
// Concatenation: packets copied from consecutive parts.

namespace {
struct InputDeleter {
  void operator()(AVFormatContext* f) const { avformat_close_input(&f); }
};
using InputPtr = std::unique_ptr<AVFormatContext, InputDeleter>;

InputPtr openPart(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", path.string());
  AVFormatContext* raw = nullptr;
  if (const int e = avformat_open_input(&raw, path.c_str(), nullptr, nullptr); e < 0) {
    fail(ErrorKind::Input, "cannot read '{}': {}", path.string(), ffmpegError(e));
  }
  InputPtr input(raw);
  if (const int e = avformat_find_stream_info(input.get(), nullptr); e < 0) {
    fail(ErrorKind::Input, "cannot read '{}': {}", path.string(), ffmpegError(e));
  }
  return input;
}

/// Fails unless every part has the first one's streams, codecs and size.
void checkPartsMatch(std::span<const fs::path> parts, const std::vector<InputPtr>& inputs) {
  const AVFormatContext& first = *inputs.front();
  for (std::size_t k = 1; k < inputs.size(); ++k) {
    const AVFormatContext& other = *inputs[k];
    bool same = other.nb_streams == first.nb_streams;
    for (unsigned i = 0; same && i < first.nb_streams; ++i) {
      const AVCodecParameters& a = *first.streams[i]->codecpar;
      const AVCodecParameters& b = *other.streams[i]->codecpar;
      same = a.codec_type == b.codec_type && a.codec_id == b.codec_id && a.width == b.width && a.height == b.height;
    }
    if (!same) {
      fail(ErrorKind::Input, "'{}' does not match '{}' (streams, codecs or size differ): not parts of one video",
           parts[k].string(), parts[0].string());
    }
  }
}

/// Adds a copy of each of the first part's streams to `output`, with its rotation.
void copyStreams(AVFormatContext& output, const AVFormatContext& first) {
  for (unsigned i = 0; i < first.nb_streams; ++i) {
    AVStream* out = avformat_new_stream(&output, nullptr);
    avcodec_parameters_copy(out->codecpar, first.streams[i]->codecpar);
    out->codecpar->codec_tag = 0;
    out->time_base = first.streams[i]->time_base;
    out->avg_frame_rate = first.streams[i]->avg_frame_rate;
    std::size_t matrixSize = 0;  // the parts' rotation, kept
    if (const std::uint8_t* m = streamSideData(*first.streams[i], AV_PKT_DATA_DISPLAYMATRIX, matrixSize);
        m && matrixSize > 0) {
      if (std::uint8_t* copy = newStreamSideData(*out, AV_PKT_DATA_DISPLAYMATRIX, matrixSize))
        std::memcpy(copy, m, matrixSize);
    }
  }
}

/// The joined file as the parts' packets are copied into it, one part after the other.
struct Joined {
  AVFormatContext& output;
  const fs::path& destination;
  int video;  // the video stream's index
  PacketPtr packet{av_packet_alloc()};
  std::int64_t frames = 0;
  std::int64_t previousEnd = kNoTimestamp;  // in the output video stream's time base
  std::vector<std::int64_t> lastDts;

  Joined(AVFormatContext& out, const fs::path& path, int videoIndex)
      : output(out), destination(path), video(videoIndex), lastDts(out.nb_streams, kNoTimestamp) {}

  /// Writes one packet to the joined file.
  void write(AVPacket& p) {
    if (const int w = av_interleaved_write_frame(&output, &p); w < 0) {
      fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeError(destination, w));
    }
  }

  /// Copies part k's packets; the last part's last packets are trimmed to its duration.
  void copyPart(AVFormatContext& in, std::span<const fs::path> parts, std::size_t k);
  /// Widens [partStart, partEnd) to the video packet in `packet` (rescaled to the output).
  void extendSpan(const AVStream& inStream, std::int64_t& partStart, std::int64_t& partEnd) const;
  /// Writes the packets held back from the last part, each trimmed to end where the part ends.
  void writeHeld(const AVFormatContext& in, std::vector<PacketPtr>& held);
  /// Fails unless part k begins where the part before it ended.
  void checkConsecutive(std::span<const fs::path> parts, std::size_t k, std::int64_t partStart) const;
};

void Joined::copyPart(AVFormatContext& in, std::span<const fs::path> parts, std::size_t k) {
  std::int64_t partStart = kNoTimestamp, partEnd = kNoTimestamp;
  const bool holdLast = k + 1 == parts.size() && in.duration > 0 &&
                        std::string_view(in.iformat->name).find("matroska") != std::string_view::npos;
  std::vector<PacketPtr> held(in.nb_streams);
  while (true) {
    const int r = av_read_frame(&in, packet.get());
    if (r == AVERROR_EOF) break;
    if (r < 0) fail(ErrorKind::Input, "cannot read '{}': {}", parts[k].string(), ffmpegError(r));
    const int index = packet->stream_index;
    AVStream* out = output.streams[index];
    av_packet_rescale_ts(packet.get(), in.streams[index]->time_base, out->time_base);
    if (index == video) {
      ++frames;
      extendSpan(*in.streams[index], partStart, partEnd);
    }
    if (packet->dts != AV_NOPTS_VALUE && lastDts[std::size_t(index)] != kNoTimestamp &&
        packet->dts <= lastDts[std::size_t(index)]) {
      fail(ErrorKind::Input, "'{}' overlaps the part before it in time: not the next range of frames",
           parts[k].string());
    }
    if (packet->dts != AV_NOPTS_VALUE) lastDts[std::size_t(index)] = packet->dts;
    packet->pos = -1;
    if (holdLast) {  // written one behind, so the last one can be trimmed at the end
      PacketPtr& h = held[std::size_t(index)];
      if (h) write(*h);
      else h.reset(av_packet_alloc());
      av_packet_move_ref(h.get(), packet.get());
    } else {
      write(*packet);
    }
  }
  if (holdLast) writeHeld(in, held);
  checkConsecutive(parts, k, partStart);
  previousEnd = partEnd;
}

void Joined::extendSpan(const AVStream& inStream, std::int64_t& partStart, std::int64_t& partEnd) const {
  if (packet->pts == AV_NOPTS_VALUE) return;
  if (partStart == kNoTimestamp || packet->pts < partStart) partStart = packet->pts;
  // An MP4's last sample often has no duration: it lasts a frame.
  const AVRational rate = inStream.avg_frame_rate.num > 0 ? inStream.avg_frame_rate : inStream.r_frame_rate;
  const std::int64_t duration = packet->duration > 0 ? packet->duration
                                : rate.num > 0       ? av_rescale_q(1, av_inv_q(rate), output.streams[video]->time_base)
                                                     : 0;
  const std::int64_t end = packet->pts + duration;
  if (partEnd == kNoTimestamp || end > partEnd) partEnd = end;
}

void Joined::writeHeld(const AVFormatContext& in, std::vector<PacketPtr>& held) {
  // Matroska keeps no audio durations: read back, a trimmed last packet (an encoder's end
  // padding) lasts a whole frame. The part's own duration still says where it ended, and
  // the joined file ends there too, as one run's would.
  for (unsigned i = 0; i < held.size(); ++i) {
    if (!held[i]) continue;
    AVPacket& last = *held[i];
    const std::int64_t end = av_rescale_q(in.duration, AV_TIME_BASE_Q, output.streams[i]->time_base);
    if (last.pts != AV_NOPTS_VALUE && last.pts < end && last.pts + last.duration > end) last.duration = end - last.pts;
    write(last);
  }
}

void Joined::checkConsecutive(std::span<const fs::path> parts, std::size_t k, std::int64_t partStart) const {
  // A part must begin where the previous one ended: within half a frame (containers
  // round timestamps and last-packet durations to their own time bases).
  const AVRational tb = output.streams[video]->time_base;
  const AVRational rate = output.streams[video]->avg_frame_rate;
  const std::int64_t slack = rate.num > 0 ? std::max<std::int64_t>(1, av_rescale_q(1, av_inv_q(rate), tb) / 2) : 1;
  if (k > 0 && previousEnd != kNoTimestamp && partStart != kNoTimestamp && std::abs(partStart - previousEnd) > slack) {
    const double gap = double(partStart - previousEnd) * av_q2d(tb);
    fail(ErrorKind::Input, "'{}' does not start where '{}' ends ({:+.3f} s): not consecutive --frames ranges",
         parts[k].string(), parts[k - 1].string(), gap);
  }
}
}  // namespace

std::int64_t concatenateFiles(std::span<const fs::path> parts, const fs::path& destination, const fs::path& target) {
  initFfmpeg();
  if (parts.empty()) fail(ErrorKind::Usage, "concatenate: no parts given");
  std::vector<InputPtr> inputs;
  for (const auto& p : parts) inputs.push_back(openPart(p));
  checkPartsMatch(parts, inputs);
  const AVFormatContext& first = *inputs.front();
  int video = av_find_best_stream(inputs.front().get(), AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (video < 0) fail(ErrorKind::Input, "'{}' has no video stream", parts[0].string());

  OutputPtr output = createOutput(destination, target);
  copyStreams(*output, first);
  openFile(*output, target, destination);
  if (const int h = avformat_write_header(output.get(), nullptr); h < 0) {
    fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeError(destination, h));
  }

  Joined joined(*output, destination, video);
  for (std::size_t k = 0; k < inputs.size(); ++k) joined.copyPart(*inputs[k], parts, k);
  if (const int t = av_write_trailer(output.get()); t < 0) {
    fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeError(destination, t));
  }
  if (!(output->oformat->flags & AVFMT_NOFILE)) avio_closep(&output->pb);
  return joined.frames;
}

// ---------------------------------------------------------------------------
// The module's entry points (backend.h).
namespace backend {
namespace {
FfmpegSink& cast(SinkHandle* h) { return *reinterpret_cast<FfmpegSink*>(h); }
const FfmpegSink& cast(const SinkHandle* h) { return *reinterpret_cast<const FfmpegSink*>(h); }
}  // namespace

SinkHandle* openSink(const fs::path& destination, const fs::path& target, const SinkOptions& options, Status& status) {
  return guarded(status, [&] { return reinterpret_cast<SinkHandle*>(new FfmpegSink(destination, target, options)); },
                 static_cast<SinkHandle*>(nullptr));
}
void closeSink(SinkHandle* h) { delete &cast(h); }  // the caller's AtomicFile removes an unfinished file
void write(SinkHandle* h, const Frame& frame, Status& status) {
  guarded(status, [&] { cast(h).write(frame); return true; }, false);
}
void writeAudio(SinkHandle* h, Packet& packet, Status& status) {
  guarded(status, [&] { cast(h).writeAudio(std::move(packet)); return true; }, false);
}
void finish(SinkHandle* h, Status& status) {
  guarded(status, [&] { cast(h).finish(); return true; }, false);
}
std::int64_t framesWritten(const SinkHandle* h) { return cast(h).written; }
const std::string* audioNote(const SinkHandle* h) { return &cast(h).audioNote; }
std::int64_t concatenate(std::span<const fs::path> parts, const fs::path& destination, const fs::path& target,
                         Status& status) {
  return guarded(status, [&] { return concatenateFiles(parts, destination, target); }, std::int64_t(0));
}
}  // namespace backend

}  // namespace glint::video
