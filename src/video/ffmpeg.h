#pragma once
// Private to src/video: FFmpeg's headers, error text, owners for its objects, and the one
// RGBA converter both directions use.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavdevice/avdevice.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/intreadwrite.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "backend.h"

#include "glint/core/error.h"
#include "glint/video/frame.h"
#include "glint/video/packet.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <span>
#include <string>

namespace glint::video {

/// Registers libavdevice's inputs and routes FFmpeg's log to glint's (Debug level: FFmpeg's
/// chatter is for -v; glint reports what matters as its own warnings and errors). Once.
void initFfmpeg();

/// av_strerror's text for an FFmpeg error code.
std::string ffmpegError(int code);

/// Error lines a decoder logged while still returning frames. Decoders conceal damage
/// rather than fail (FFV1 copies a slice whose CRC does not match from the previous frame,
/// H.264 hides broken macroblocks) and flag nothing on the frame, so their log is the only
/// trace: FFmpeg's log callback counts the error-level lines of every decoder that has a
/// watch, including its frame-thread copies (they share `opaque`).
class DecoderErrorWatch {
public:
  DecoderErrorWatch();
  ~DecoderErrorWatch();
  DecoderErrorWatch(const DecoderErrorWatch&) = delete;
  DecoderErrorWatch& operator=(const DecoderErrorWatch&) = delete;

  /// Watches `decoder`; call before avcodec_open2 (which makes the thread copies).
  void attach(AVCodecContext& decoder) { decoder.opaque = this; }
  std::int64_t count() const;
  std::string first() const;

  /// From the log callback: a fragment of a line the watched decoder logged at error level.
  static void record(void* opaque, const char* text);

private:
  mutable std::mutex m_mutex;
  std::string m_pending, m_first;
  std::int64_t m_count = 0;
};

/// A stream's side data of `type` (a display matrix: a phone clip's rotation) and its size,
/// or null. FFmpeg 6.1 moved side data into the codec parameters (Debian 13's 7.1 warns of
/// the stream's, Debian 12's 5.1 has only those): the one place glint asks either.
inline const std::uint8_t* streamSideData(const AVStream& stream, AVPacketSideDataType type, std::size_t& size) {
#if LIBAVCODEC_VERSION_INT >= AV_VERSION_INT(60, 31, 102)
  const AVPacketSideData* data =
      av_packet_side_data_get(stream.codecpar->coded_side_data, stream.codecpar->nb_coded_side_data, type);
  size = data ? data->size : 0;
  return data ? data->data : nullptr;
#else
  return av_stream_get_side_data(&stream, type, &size);
#endif
}

/// New side data of `size` bytes on a stream being written, or null (out of memory).
inline std::uint8_t* newStreamSideData(AVStream& stream, AVPacketSideDataType type, std::size_t size) {
#if LIBAVCODEC_VERSION_INT >= AV_VERSION_INT(60, 31, 102)
  AVPacketSideData* data =
      av_packet_side_data_new(&stream.codecpar->coded_side_data, &stream.codecpar->nb_coded_side_data, type, size, 0);
  return data ? data->data : nullptr;
#else
  return av_stream_new_side_data(&stream, type, size);
#endif
}

inline Rational toRational(AVRational r) { return {r.num, r.den}; }
inline AVRational toAv(Rational r) { return {r.num, r.den}; }

struct FrameDeleter {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
using FramePtr = std::unique_ptr<AVFrame, FrameDeleter>;
struct PacketDeleter {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
using PacketPtr = std::unique_ptr<AVPacket, PacketDeleter>;
struct CodecContextDeleter {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
using CodecContextPtr = std::unique_ptr<AVCodecContext, CodecContextDeleter>;

/// Converts between an AVFrame's pixel format and tightly packed RGBA8, with libswscale's
/// slice threads. The YUV matrix and range are the frame's (decoding) or the encoder's
/// (encoding); unspecified matrices are guessed from the height like players do.
class RgbaConverter {
public:
  RgbaConverter() = default;
  ~RgbaConverter();
  RgbaConverter(const RgbaConverter&) = delete;
  RgbaConverter& operator=(const RgbaConverter&) = delete;

  /// `frame` (any format) → `image` (U8 RGBA of the frame's size; reallocated if needed).
  void toRgba(const AVFrame& frame, Image& image);
  /// `image` (U8 RGBA) → `frame`, whose format, size, colorspace and range are set and
  /// whose buffers are allocated.
  void fromRgba(const Image& image, AVFrame& frame);
  /// A Yuv420 frame's planes (video/frame.h) in `matrix` → `frame`, as fromRgba.
  void fromYuv420(const Image& planes, YuvMatrix matrix, AVFrame& frame);

private:
  void prepare(int width, int height, AVPixelFormat from, AVPixelFormat to, int yuvColorspace, bool yuvFullRange,
               bool toYuv);
  SwsContext* m_context = nullptr;
  int m_width = 0, m_height = 0, m_colorspace = -1;
  AVPixelFormat m_from = AV_PIX_FMT_NONE, m_to = AV_PIX_FMT_NONE;
  bool m_fullRange = false;
};

/// The audio stream a Source keeps and a Sink copies: its codec parameters and time base.
class AudioTrack {
public:
  /// `leadSeconds`: how long before the video's first frame the audio stream starts in the
  /// source (an AAC encoder's priming), 0 when it does not.
  AudioTrack(const AVCodecParameters& parameters, AVRational timeBase, double leadSeconds = 0.0);
  ~AudioTrack();
  AudioTrack(const AudioTrack&) = delete;
  AudioTrack& operator=(const AudioTrack&) = delete;
  const AVCodecParameters& parameters() const { return *m_parameters; }
  AVRational timeBase() const { return m_timeBase; }
  double leadSeconds() const { return m_leadSeconds; }

private:
  AVCodecParameters* m_parameters = nullptr;
  AVRational m_timeBase;
  double m_leadSeconds = 0.0;
};

/// Runs `body` and returns its result; a thrown Error (or anything else) is caught into
/// `status` instead, with `failed` returned: no exception leaves the module.
template <typename Body, typename Result>
Result guarded(backend::Status& status, Body&& body, Result failed) {
  status = {};
  try {
    return body();
  } catch (const Error& e) {
    status = {false, e.kind(), e.what()};
  } catch (const std::exception& e) {
    status = {false, ErrorKind::Internal, e.what()};
  } catch (...) {
    status = {false, ErrorKind::Internal, "unknown exception in the video module"};
  }
  return failed;
}

std::int64_t concatenateFiles(std::span<const std::filesystem::path> parts, const std::filesystem::path& destination);

/// Copies `frame`'s planes into `out` (FrameFormat::Yuv420) when it is 8-bit limited-range
/// 4:2:0 in BT.601 or BT.709 with an even size; false (nothing done) otherwise.
bool takeYuv420(const AVFrame& frame, Frame& out);

/// The colorspace libswscale should use for a YUV frame: its own tag, else BT.709 for
/// 720 lines and up, BT.601 below.
int swsColorspace(AVColorSpace tagged, int height);

}  // namespace glint::video
