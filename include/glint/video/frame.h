#pragma once
// glint/video/frame.h — what flows through glint's video layer: RGBA or YUV frames with
// their timestamps, and rationals. Plain data, header-only (a module that works on frames,
// post's CPU backend, uses it without linking the video layer); compressed packets are
// video/packet.h's.
//
// The video layer (glint::video) is GL-free: FFmpeg's libraries read files, cameras (V4L2
// through libavdevice) and lavfi sources, and write H.264 or FFV1 files; no FFmpeg type
// appears in its headers, so a program using glint::video needs FFmpeg's libraries only
// to link. render/post processes the frames on the GPU; app/cmd_post.cpp joins the two.

#include "glint/image/image.h"

#include <cstdint>

namespace glint::video {

/// A rational number: frame rates (30000/1001) and time bases (1/90000).
struct Rational {
  int num = 0;
  int den = 1;
  double value() const { return den != 0 ? double(num) / double(den) : 0.0; }
  bool valid() const { return num > 0 && den > 0; }
  bool operator==(const Rational&) const = default;
};

/// No timestamp (FFmpeg's AV_NOPTS_VALUE).
constexpr std::int64_t kNoTimestamp = INT64_MIN;

/// How a Frame's `image` holds the picture.
enum class FrameFormat {
  Rgba,   ///< U8 RGBA, 4 channels, tightly packed (rowBytes() = 4·width): the default
  /// 8-bit limited-range YUV 4:2:0 as a decoder gives it, planar (I420) in one U8 1-channel
  /// image of width × (height·3/2): the Y plane (width × height), then U and V (width/2 ×
  /// height/2 each, rows of width/2 bytes, packed). Even sizes only. Sources deliver it when
  /// asked (SourceOptions::yuv420) so that an effect defined on luma skips the RGB round trip.
  Yuv420
};

/// The YUV matrix of a Yuv420 frame (the stream's tag; untagged: BT.709 from 720 lines up).
enum class YuvMatrix {
  Bt601,  ///< Kr = 0.299, Kb = 0.114 (SD video; the luma glint's effects use)
  Bt709   ///< Kr = 0.2126, Kb = 0.0722 (HD video; what glint's H.264 sink writes)
};

/// One decoded picture, row 0 at the top: `image` as `format` says (U8 RGBA by default).
struct Frame {
  Image image;
  FrameFormat format = FrameFormat::Rgba;
  YuvMatrix matrix = YuvMatrix::Bt709;  ///< Yuv420 only
  std::int64_t index = 0;   ///< frame number from the start of the source (its first frame is 0)
  std::int64_t pts = kNoTimestamp;  ///< presentation timestamp in the source's time base
  double seconds = 0.0;     ///< pts in seconds from the source's start (0 for its first frame)
};


}  // namespace glint::video
