#include "ffmpeg.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/video/packet.h"

#include <algorithm>
#include <cctype>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <utility>
#include <thread>
#include <vector>

namespace glint::video {

namespace {
// The live watches: the log callback only trusts an AVCodecContext's opaque once it is found
// here (other code in the process, OpenImageIO's FFmpeg reader, may decode too).
std::mutex g_watchMutex;
std::vector<DecoderErrorWatch*> g_watches;

bool isCodecContext(void* avcl) {
  if (!avcl) return false;
  const AVClass* c = *static_cast<const AVClass* const*>(avcl);
  return c && c->class_name && std::strcmp(c->class_name, "AVCodecContext") == 0;
}

extern "C" void routeFfmpegLog(void* avcl, int level, const char* format, va_list args) {
  const bool debug = level <= AV_LOG_WARNING && log::level() <= log::Level::Debug;
  const bool watched = level <= AV_LOG_ERROR && isCodecContext(avcl);
  if (!debug && !watched) return;
  if (watched) {
    va_list copy;
    va_copy(copy, args);
    char plain[1024];
    std::vsnprintf(plain, sizeof plain, format, copy);
    va_end(copy);
    DecoderErrorWatch::record(static_cast<AVCodecContext*>(avcl)->opaque, plain);
  }
  if (!debug) return;
  char line[1024];
  static int printPrefix = 1;
  av_log_format_line(avcl, level, format, args, line, sizeof line, &printPrefix);
  std::string text(line);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  if (!text.empty()) log::debug("ffmpeg: {}", text);
}
}  // namespace

DecoderErrorWatch::DecoderErrorWatch() {
  std::lock_guard lock(g_watchMutex);
  g_watches.push_back(this);
}

DecoderErrorWatch::~DecoderErrorWatch() {
  std::lock_guard lock(g_watchMutex);
  std::erase(g_watches, this);
}

std::int64_t DecoderErrorWatch::count() const {
  std::lock_guard lock(m_mutex);
  return m_count;
}

std::string DecoderErrorWatch::first() const {
  std::lock_guard lock(m_mutex);
  return m_first;
}

void DecoderErrorWatch::record(void* opaque, const char* text) {
  std::lock_guard registry(g_watchMutex);  // held: the watch cannot go away meanwhile
  const auto found = std::find(g_watches.begin(), g_watches.end(), static_cast<DecoderErrorWatch*>(opaque));
  if (!opaque || found == g_watches.end()) return;
  DecoderErrorWatch& w = **found;
  std::lock_guard lock(w.m_mutex);
  // FFmpeg logs a line in pieces ("slice CRC mismatch 1A2B!", then "at 1.0 seconds\n"): a
  // line counts once, when its newline arrives.
  if (!w.m_pending.empty() && !std::isspace(static_cast<unsigned char>(w.m_pending.back())) && *text != '\n') {
    w.m_pending += ' ';
  }
  w.m_pending += text;
  for (std::size_t end; (end = w.m_pending.find('\n')) != std::string::npos;) {
    std::string line = w.m_pending.substr(0, end);
    w.m_pending.erase(0, end + 1);
    if (line.empty()) continue;
    ++w.m_count;
    if (w.m_first.empty()) w.m_first = std::move(line);
  }
}

void initFfmpeg() {
  static std::once_flag once;
  std::call_once(once, [] {
    avdevice_register_all();
    av_log_set_callback(routeFfmpegLog);
  });
}

std::string ffmpegError(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

// ---------------------------------------------------------------------------
Packet::Packet(AVPacket* packet) : m_packet(packet) {}
Packet::~Packet() { av_packet_free(&m_packet); }
Packet::Packet(Packet&& other) noexcept : m_packet(std::exchange(other.m_packet, nullptr)) {}
Packet& Packet::operator=(Packet&& other) noexcept {
  if (this != &other) {
    av_packet_free(&m_packet);
    m_packet = std::exchange(other.m_packet, nullptr);
  }
  return *this;
}

AudioTrack::AudioTrack(const AVCodecParameters& parameters, AVRational timeBase, double leadSeconds)
    : m_parameters(avcodec_parameters_alloc()), m_timeBase(timeBase), m_leadSeconds(leadSeconds) {
  avcodec_parameters_copy(m_parameters, &parameters);
}
AudioTrack::~AudioTrack() { avcodec_parameters_free(&m_parameters); }

// ---------------------------------------------------------------------------
int swsColorspace(AVColorSpace tagged, int height) {
  switch (tagged) {
    case AVCOL_SPC_BT709: return SWS_CS_ITU709;
    case AVCOL_SPC_BT470BG:
    case AVCOL_SPC_SMPTE170M: return SWS_CS_ITU601;
    case AVCOL_SPC_FCC: return SWS_CS_FCC;
    case AVCOL_SPC_SMPTE240M: return SWS_CS_SMPTE240M;
    case AVCOL_SPC_BT2020_NCL:
    case AVCOL_SPC_BT2020_CL: return SWS_CS_BT2020;
    default: return height >= 720 ? SWS_CS_ITU709 : SWS_CS_ITU601;
  }
}

namespace {
bool isYuv(AVPixelFormat format) {
  const AVPixFmtDescriptor* d = av_pix_fmt_desc_get(format);
  return d && !(d->flags & AV_PIX_FMT_FLAG_RGB) && d->nb_components >= 3;
}

// The deprecated "J" formats are full-range YUV under another name; libswscale wants the
// plain format and the range given separately.
AVPixelFormat plainFormat(AVPixelFormat format, bool& fullRange) {
  switch (format) {
    case AV_PIX_FMT_YUVJ420P: fullRange = true; return AV_PIX_FMT_YUV420P;
    case AV_PIX_FMT_YUVJ422P: fullRange = true; return AV_PIX_FMT_YUV422P;
    case AV_PIX_FMT_YUVJ444P: fullRange = true; return AV_PIX_FMT_YUV444P;
    case AV_PIX_FMT_YUVJ440P: fullRange = true; return AV_PIX_FMT_YUV440P;
    case AV_PIX_FMT_YUVJ411P: fullRange = true; return AV_PIX_FMT_YUV411P;
    default: return format;
  }
}

// An AVBufferRef over memory glint owns: libswscale's frame API then writes into it
// instead of allocating its own.
void noFree(void*, std::uint8_t*) {}
}  // namespace

RgbaConverter::~RgbaConverter() { sws_freeContext(m_context); }

void RgbaConverter::prepare(int width, int height, AVPixelFormat from, AVPixelFormat to, int colorspace,
                            bool fullRange, bool toYuv) {
  if (m_context && width == m_width && height == m_height && from == m_from && to == m_to &&
      colorspace == m_colorspace && fullRange == m_fullRange) {
    return;
  }
  sws_freeContext(m_context);
  m_context = sws_alloc_context();
  if (!m_context) fail(ErrorKind::Internal, "libswscale: out of memory");
  // Bicubic chroma, accurate rounding and full chroma interpolation: packed RGB ↔ RGB is then
  // an exact copy, and YUV ↔ RGB round trips within a step or two.
  const int flags = SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT | SWS_FULL_CHR_H_INP;
  av_opt_set_int(m_context, "srcw", width, 0);
  av_opt_set_int(m_context, "srch", height, 0);
  av_opt_set_int(m_context, "src_format", from, 0);
  av_opt_set_int(m_context, "dstw", width, 0);
  av_opt_set_int(m_context, "dsth", height, 0);
  av_opt_set_int(m_context, "dst_format", to, 0);
  av_opt_set_int(m_context, "sws_flags", flags, 0);
  // Slice threads: at 1080p and up, one core converting is the pipeline's bottleneck.
  av_opt_set_int(m_context, "threads", std::max(1u, std::min(8u, std::thread::hardware_concurrency())), 0);
  if (const int e = sws_init_context(m_context, nullptr, nullptr); e < 0) {
    sws_freeContext(m_context);
    m_context = nullptr;
    fail(ErrorKind::Input, "cannot convert {} to {}: {}", av_get_pix_fmt_name(from), av_get_pix_fmt_name(to),
         ffmpegError(e));
  }
  const int* coefficients = sws_getCoefficients(colorspace);
  // RGB is always full range; the YUV side has the stream's range.
  const int srcRange = toYuv ? 1 : (fullRange ? 1 : 0);
  const int dstRange = toYuv ? (fullRange ? 1 : 0) : 1;
  sws_setColorspaceDetails(m_context, coefficients, srcRange, coefficients, dstRange, 0, 1 << 16, 1 << 16);
  m_width = width;
  m_height = height;
  m_from = from;
  m_to = to;
  m_colorspace = colorspace;
  m_fullRange = fullRange;
}

void RgbaConverter::toRgba(const AVFrame& frame, Image& image) {
  if (image.width() != frame.width || image.height() != frame.height || image.channels() != 4 ||
      image.type() != PixelType::U8) {
    image = Image(frame.width, frame.height, 4, PixelType::U8);
  }
  bool fullRange = frame.color_range == AVCOL_RANGE_JPEG;
  const auto format = plainFormat(AVPixelFormat(frame.format), fullRange);
  const int colorspace = isYuv(format) ? swsColorspace(frame.colorspace, frame.height) : SWS_CS_DEFAULT;
  prepare(frame.width, frame.height, format, AV_PIX_FMT_RGBA, colorspace, fullRange, false);

  FramePtr src(av_frame_alloc());
  av_frame_ref(src.get(), &frame);
  src->format = format;
  FramePtr dst(av_frame_alloc());
  dst->format = AV_PIX_FMT_RGBA;
  dst->width = frame.width;
  dst->height = frame.height;
  auto bytes = image.bytes();
  dst->buf[0] = av_buffer_create(reinterpret_cast<std::uint8_t*>(bytes.data()), bytes.size(), noFree, nullptr, 0);
  dst->data[0] = reinterpret_cast<std::uint8_t*>(bytes.data());
  dst->linesize[0] = int(image.rowBytes());
  if (const int e = sws_scale_frame(m_context, dst.get(), src.get()); e < 0) {
    fail(ErrorKind::Input, "cannot convert a {} frame to RGBA: {}", av_get_pix_fmt_name(format), ffmpegError(e));
  }
}

void RgbaConverter::fromRgba(const Image& image, AVFrame& frame) {
  const auto to = AVPixelFormat(frame.format);
  const bool fullRange = frame.color_range == AVCOL_RANGE_JPEG;
  const int colorspace = isYuv(to) ? swsColorspace(frame.colorspace, frame.height) : SWS_CS_DEFAULT;
  prepare(image.width(), image.height(), AV_PIX_FMT_RGBA, to, colorspace, fullRange, true);
  FramePtr src(av_frame_alloc());
  src->format = AV_PIX_FMT_RGBA;
  src->width = image.width();
  src->height = image.height();
  auto bytes = image.bytes();
  auto* data = const_cast<std::uint8_t*>(reinterpret_cast<const std::uint8_t*>(bytes.data()));
  src->buf[0] = av_buffer_create(data, bytes.size(), noFree, nullptr, AV_BUFFER_FLAG_READONLY);
  src->data[0] = data;
  src->linesize[0] = int(image.rowBytes());
  if (const int e = sws_scale_frame(m_context, &frame, src.get()); e < 0) {
    fail(ErrorKind::Internal, "cannot convert RGBA to {}: {}", av_get_pix_fmt_name(to), ffmpegError(e));
  }
}

}  // namespace glint::video

namespace glint::video {

void RgbaConverter::fromYuv420(const Image& planes, YuvMatrix matrix, AVFrame& frame) {
  const auto to = AVPixelFormat(frame.format);
  const int width = frame.width, height = frame.height;
  if (planes.width() != width || planes.height() != height + height / 2 || planes.channels() != 1) {
    fail(ErrorKind::Internal, "a Yuv420 frame of {}x{} bytes does not match the video's {}x{}", planes.width(),
         planes.height(), width, height);
  }
  auto* y = const_cast<std::uint8_t*>(reinterpret_cast<const std::uint8_t*>(planes.bytes().data()));
  std::uint8_t* u = y + std::size_t(width) * height;
  std::uint8_t* v = u + std::size_t(width / 2) * (height / 2);
  const bool bt709 = matrix == YuvMatrix::Bt709;
  if (to == AV_PIX_FMT_YUV420P && frame.color_range != AVCOL_RANGE_JPEG &&
      (frame.colorspace == AVCOL_SPC_BT709) == bt709) {
    // The encoder's own format and matrix: the planes as they are.
    av_image_copy_plane(frame.data[0], frame.linesize[0], y, width, width, height);
    av_image_copy_plane(frame.data[1], frame.linesize[1], u, width / 2, width / 2, height / 2);
    av_image_copy_plane(frame.data[2], frame.linesize[2], v, width / 2, width / 2, height / 2);
    return;
  }
  // Anything else (FFV1's bgr0, another matrix): libswscale, from limited-range 4:2:0.
  const int colorspace = bt709 ? SWS_CS_ITU709 : SWS_CS_ITU601;
  const int target = isYuv(to) ? swsColorspace(frame.colorspace, height) : colorspace;
  if (isYuv(to) && target != colorspace) {
    fail(ErrorKind::Internal, "converting a Yuv420 frame between YUV matrices is not supported");
  }
  prepare(width, height, AV_PIX_FMT_YUV420P, to, colorspace, false, false);
  FramePtr src(av_frame_alloc());
  src->format = AV_PIX_FMT_YUV420P;
  src->width = width;
  src->height = height;
  src->buf[0] = av_buffer_create(y, planes.bytes().size(), noFree, nullptr, AV_BUFFER_FLAG_READONLY);
  src->data[0] = y;
  src->data[1] = u;
  src->data[2] = v;
  src->linesize[0] = width;
  src->linesize[1] = src->linesize[2] = width / 2;
  if (const int e = sws_scale_frame(m_context, &frame, src.get()); e < 0) {
    fail(ErrorKind::Internal, "cannot convert yuv420p to {}: {}", av_get_pix_fmt_name(to), ffmpegError(e));
  }
}

bool takeYuv420(const AVFrame& frame, Frame& out) {
  if (frame.format != AV_PIX_FMT_YUV420P || frame.color_range == AVCOL_RANGE_JPEG || frame.width % 2 != 0 ||
      frame.height % 2 != 0) {
    return false;
  }
  const int colorspace = swsColorspace(frame.colorspace, frame.height);
  if (colorspace != SWS_CS_ITU709 && colorspace != SWS_CS_ITU601) return false;
  const int width = frame.width, height = frame.height;
  if (out.image.width() != width || out.image.height() != height + height / 2 || out.image.channels() != 1 ||
      out.image.type() != PixelType::U8) {
    out.image = Image(width, height + height / 2, 1, PixelType::U8);
  }
  auto* y = reinterpret_cast<std::uint8_t*>(out.image.bytes().data());
  std::uint8_t* u = y + std::size_t(width) * height;
  std::uint8_t* v = u + std::size_t(width / 2) * (height / 2);
  av_image_copy_plane(y, width, frame.data[0], frame.linesize[0], width, height);
  av_image_copy_plane(u, width / 2, frame.data[1], frame.linesize[1], width / 2, height / 2);
  av_image_copy_plane(v, width / 2, frame.data[2], frame.linesize[2], width / 2, height / 2);
  out.format = FrameFormat::Yuv420;
  out.matrix = colorspace == SWS_CS_ITU709 ? YuvMatrix::Bt709 : YuvMatrix::Bt601;
  return true;
}

}  // namespace glint::video
