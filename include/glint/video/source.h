#pragma once
// glint/video/source.h — frames from a video file, a camera or an FFmpeg lavfi graph.
//
/// ```cpp
/// glint::video::Source source = glint::video::Source::open("clip.mp4");  // a file
/// glint::video::SourceOptions camera;
/// camera.camera = true;
/// camera.size = {640, 480};
/// glint::video::Source live = glint::video::Source::open("/dev/video0", camera);
/// glint::video::Source bars = glint::video::Source::open("lavfi:testsrc2=size=1280x720:rate=30:duration=2");
/// glint::video::Frame frame;
/// std::vector<glint::Image> pictures;
/// while (source.read(frame)) pictures.push_back(frame.image);  // RGBA8, top row first
/// ```
//
// What it does
//   - Demuxes and decodes with libavformat/libavcodec (frame-threaded decoders), converts
//     every frame to RGBA8 with libswscale, honouring the stream's colour matrix (BT.601 or
//     BT.709; unspecified: 709 from 720 lines up, as players guess) and range (limited or
//     full). Packed RGB sources (FFV1 in bgr0, PNG, lavfi's rgb formats) convert exactly.
//   - Sources are one of three kinds. A *file* is read to its end, every frame in order:
//     none is skipped (a packet the decoder rejects is counted in corruptPackets(), and
//     read() says so through a warning; damage the decoder conceals is counted in
//     decoderErrors(); a file that ends early just ends, info().frameCount tells by how
//     much). A *camera* (V4L2, libavdevice) and any source
//     opened with `realtime` are *live*: frames come at their own pace, and the layer
//     above drops what it cannot keep up with; gaps in the source's own timestamps (frames
//     the device dropped before we saw them) are counted in droppedFrames(). A *lavfi*
//     source ("lavfi:GRAPH", FFmpeg's filter-graph syntax: testsrc2, smptehdbars, mandelbrot,
//     ...) is a generator; it is live only when opened with `realtime`, which paces it at
//     its frame rate like a camera — the live path tested without a camera.
//   - firstFrame/lastFrame select frames [first, last) (`glint post --frames a:b`): a file
//     seeks to the keyframe before `first` and decodes from there; frame indices come from
//     the timestamps, so the parts of a split video keep their numbers and times.
//   - Audio: the first audio stream's packets are kept (not decoded) for a Sink to copy.
//
// Errors are glint::Error with one line: Input for a missing or unreadable file (an MP4
// cut before its index), a stream without video, a codec FFmpeg cannot decode, no such camera or a camera
// that stops answering.

#include "glint/core/math.h"
#include "glint/video/frame.h"
#include "glint/video/packet.h"

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace glint::video {

enum class SourceKind {
  File,    ///< a video file (anything libavformat demuxes)
  Camera,  ///< a V4L2 device, /dev/videoN
  Lavfi    ///< an FFmpeg filter graph generating frames ("lavfi:testsrc2=...")
};

struct SourceOptions {
  bool camera = false;        ///< the name is a V4L2 device (`glint post --camera /dev/video0`)
  bool realtime = false;      ///< pace a file or lavfi source at its frame rate and treat it as live
  ivec2 size{0};              ///< camera: the size to ask for (0: the device's default; WWDC 2003 session 212's was 640×480)
  double frameRate = 0.0;     ///< camera: the rate to ask for (0: the device's default)
  std::int64_t firstFrame = 0;   ///< first frame to deliver
  std::int64_t lastFrame = -1;   ///< one past the last frame to deliver; -1: to the end
  bool keepAudio = true;      ///< keep the first audio stream's packets for passthrough
  int threads = 0;            ///< decoder threads; 0: FFmpeg's choice (one per core)
  /// Deliver 8-bit limited-range 4:2:0 frames (BT.601 or BT.709, even size) as decoded,
  /// FrameFormat::Yuv420, without converting to RGBA; any other frame is converted as usual.
  /// For processors that work on luma (glint post's CPU backend).
  bool yuv420 = false;
  /// Turn the frames as the stream's display matrix says they are shown (a phone's portrait
  /// clip, stored sideways): RGBA frames rotated by SourceInfo::rotation, the size as shown,
  /// no display matrix left to copy. Quarter turns only (other matrices are left as they are).
  bool applyRotation = false;
};

/// What a source is, as far as the container says.
struct SourceInfo {
  SourceKind kind = SourceKind::File;
  std::string name;            ///< the path, device or graph
  ivec2 size{0};               ///< frame size in pixels
  Rational frameRate;          ///< average frame rate (may be invalid for variable-rate streams)
  Rational timeBase;           ///< the video stream's time base (Frame::pts units)
  double durationSeconds = 0;  ///< 0 when unknown (cameras, endless generators)
  std::int64_t frameCount = -1;  ///< frames in the file (container's count or duration × rate); -1 unknown
  /// Whether frameCount is the container's own count (MP4's nb_frames) rather than an
  /// estimate from the duration and the average rate, which a variable-rate stream misses.
  bool frameCountExact = false;
  /// The stream's display matrix (9 values, FFmpeg's AV_PKT_DATA_DISPLAYMATRIX), empty when
  /// it has none; kept on a video written from these frames (SinkOptions::displayMatrix).
  std::vector<std::int32_t> displayMatrix;
  /// The rotation that matrix shows the frames with, counterclockwise in degrees, 0..359 (as
  /// ffprobe prints it); 0 without one. After applyRotation, the rotation that was applied.
  int rotation = 0;
  bool rotationApplied = false;  ///< the frames were turned (SourceOptions::applyRotation)
  std::string container;       ///< "matroska,webm", "video4linux2,v4l2", "lavfi"
  std::string codec;           ///< "h264", "ffv1", "rawvideo"
  std::string pixelFormat;     ///< the decoded format before conversion, "yuv420p"
  bool live = false;           ///< camera, or opened with realtime
  bool hasAudio = false;       ///< an audio stream exists (and is kept when keepAudio)
  std::string audioCodec;      ///< e.g. "aac", "pcm_s16le"
};

/// Source::decoderErrors(): how many error lines the decoder logged, and the first.
struct DecoderErrors {
  std::int64_t count = 0;
  std::string first;  ///< e.g. "slice CRC mismatch 22998C7A! at 1.000000 seconds"
};

class AudioTrack;  // opaque: the audio stream's parameters, for Sink

class Source {
public:
  /// Opens a file, "lavfi:GRAPH", or with options.camera a V4L2 device. See the header.
  static Source open(const std::string& name, const SourceOptions& options = {});

  Source(Source&&) noexcept;
  Source& operator=(Source&&) noexcept;
  ~Source();

  const SourceInfo& info() const;
  /// The next frame (reusing frame.image's storage when its size fits). False at the end of
  /// the stream (or past lastFrame). Error(Input) when the stream breaks: a camera that
  /// disappears, a read error other than the end of a file.
  bool read(Frame& frame);

  /// Audio packets demuxed so far (the first audio stream), in file order; empty when
  /// there is no audio or keepAudio is off. Packets before firstFrame's time or from
  /// lastFrame's time on are not kept.
  std::deque<Packet> takeAudio();
  /// The audio stream's parameters (null without audio).
  const AudioTrack* audio() const;

  /// Live sources: frames missing from the source's own timestamp sequence (gaps longer
  /// than 1.5 frame intervals), i.e. dropped before glint saw them.
  std::int64_t droppedFrames() const;
  /// Packets the decoder rejected (corrupt data); those frames are missing from the output.
  std::int64_t corruptPackets() const;
  /// Frames delivered so far.
  std::int64_t framesRead() const;
  /// The time of the last frame delivered, seconds from the stream's start; -1 before one.
  double lastFrameSeconds() const;
  /// Errors the decoder reported while still delivering frames: damage it concealed (an
  /// FFV1 slice whose CRC does not match, broken H.264 macroblocks). Those frames are in
  /// the output, possibly wrong; nothing on the frame itself says which.
  DecoderErrors decoderErrors() const;

private:
  struct Impl;
  explicit Source(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> m_impl;
};

/// A video file's frames, from its packets alone (nothing is decoded): how many there are
/// and which are keyframes, numbered as Source numbers them (from the timestamps: frame 0 is
/// the stream's start). `glint farm post` splits a video at keyframes with it, so every
/// part (`glint post --frames a:b`) starts decoding at its own first frame.
struct FrameIndex {
  std::int64_t frameCount = 0;          ///< frames in the file
  std::vector<std::int64_t> keyframes;  ///< ascending frame indices of the keyframes
  Rational frameRate;                   ///< the average rate (as SourceInfo::frameRate)
};

/// The frame index of the video file `path`. Error(Input) as Source::open for a file that
/// cannot be read or has no video stream. Reads the whole file once (packets only).
FrameIndex indexFrames(const std::string& path);

/// Why video cannot be read or written here, in one line ("cannot load the video module
/// …", or a build without video), or empty when it can: loads the module (FFmpeg) once.
std::string unavailableReason();

/// Whether `name` looks like a still image glint reads through OpenImageIO (by extension:
/// .png .jpg .jpeg .tga .tif .tiff .exr .hdr .bmp .webp), not a video.
bool isImagePath(const std::string& name);

/// Whether `name` names a video file glint writes (by extension: .mp4 .mkv .mov .avi .nut,
/// the containers a Sink holds H.264 or FFV1 in) — how `glint render` tells a clip from a
/// picture.
bool isVideoPath(const std::string& name);

}  // namespace glint::video
