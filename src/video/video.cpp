// The public video classes: thin forwarders to the glint_ffmpeg module (backend.h), which
// is dlopen()ed on first use so that commands without video never map FFmpeg's ~200
// libraries.
#include "backend.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/locations.h"
#include "glint/core/log.h"
#include "glint/video/sink.h"
#include "glint/video/source.h"
#include "glint/video/packet.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#if defined(GLINT_NO_VIDEO_MODULE)
// Built with GLINT_BUILD_VIDEO=OFF: no module to load (api() says so).
#elif !defined(GLINT_FFMPEG_MODULE) || !defined(GLINT_FFMPEG_MODULE_INSTALLED)
#error "GLINT_FFMPEG_MODULE and GLINT_FFMPEG_MODULE_INSTALLED (the module's build and install paths) must be defined"
#endif

namespace glint::video {
namespace fs = std::filesystem;

namespace {
#if defined(GLINT_NO_VIDEO_MODULE)
const backend::Api& api() {
  fail(ErrorKind::Usage, "this glint was built without video (GLINT_BUILD_VIDEO=OFF): it reads and writes images only");
}
#else
const ModuleLocation kModule{GLINT_FFMPEG_MODULE, GLINT_FFMPEG_MODULE_INSTALLED, "GLINT_FFMPEG_MODULE"};

// Loads the module once (core/locations.h's loadModule); never unloaded (objects it made
// may live until exit). A failed load throws, and the next call tries again (a static
// whose initialisation throws is not initialised).
const backend::Api& api() {
  static const backend::Api& loaded =
      loadModule<backend::Api>(kModule, "video", "glint_video_api", backend::kVideoAbiVersion);
  loaded.setLogLevel(int(log::level()));  // the module's logger follows -q / -v
  return loaded;
}
#endif

void check(const backend::Status& status) {
  if (!status.ok) throw Error(status.kind, status.message);
}
}  // namespace

std::string unavailableReason() {
  try {
    api();
    return {};
  } catch (const Error& e) {
    return e.what();
  }
}

bool isImagePath(const std::string& name) {
  const std::string ext = lowerExtension(name);
  static constexpr std::array<std::string_view, 10> kImages = {".png", ".jpg", ".jpeg", ".tga", ".tif",
                                                               ".tiff", ".exr", ".hdr", ".bmp", ".webp"};
  return std::find(kImages.begin(), kImages.end(), ext) != kImages.end();
}

bool isVideoPath(const std::string& name) {
  const std::string ext = lowerExtension(name);
  static constexpr std::array<std::string_view, 5> kVideos = {".mp4", ".mkv", ".mov", ".avi", ".nut"};
  return std::find(kVideos.begin(), kVideos.end(), ext) != kVideos.end();
}

Codec parseCodec(const std::string& name) {
  if (name == "h264" || name == "H264" || name == "x264") return Codec::H264;
  if (name == "ffv1" || name == "FFV1") return Codec::Ffv1;
  fail(ErrorKind::Usage, "unknown codec '{}': h264 or ffv1 (lossless)", name);
}

void checkPreset(const std::string& preset) {
  static constexpr std::array<std::string_view, 10> presets{"ultrafast", "superfast", "veryfast", "faster", "fast",
                                                            "medium", "slow", "slower", "veryslow", "placebo"};
  if (std::find(presets.begin(), presets.end(), preset) != presets.end()) return;
  fail(ErrorKind::Usage, "unknown --preset '{}': ultrafast, superfast, veryfast, faster, fast, medium, slow, slower, "
       "veryslow or placebo (faster = bigger files)", preset);
}

// ---------------------------------------------------------------------------
Packet::Packet(AVPacket* packet) : m_packet(packet) {}
Packet::~Packet() {
  if (m_packet) api().freePacket(m_packet);
}
Packet::Packet(Packet&& other) noexcept : m_packet(std::exchange(other.m_packet, nullptr)) {}
Packet& Packet::operator=(Packet&& other) noexcept {
  if (this != &other) {
    if (m_packet) api().freePacket(m_packet);
    m_packet = std::exchange(other.m_packet, nullptr);
  }
  return *this;
}

// ---------------------------------------------------------------------------
struct Source::Impl {
  backend::SourceHandle* handle = nullptr;
  ~Impl() {
    if (handle) api().closeSource(handle);
  }
};

Source::Source(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Source::Source(Source&&) noexcept = default;
Source& Source::operator=(Source&&) noexcept = default;
Source::~Source() = default;

Source Source::open(const std::string& name, const SourceOptions& options) {
  backend::Status status;
  auto impl = std::make_unique<Impl>();
  impl->handle = api().openSource(name, options, status);
  check(status);
  return Source(std::move(impl));
}

const SourceInfo& Source::info() const { return *api().sourceInfo(m_impl->handle); }

bool Source::read(Frame& frame) {
  backend::Status status;
  const bool ok = api().read(m_impl->handle, frame, status);
  check(status);
  return ok;
}

std::deque<Packet> Source::takeAudio() {
  std::deque<Packet> packets;
  api().takeAudio(m_impl->handle, packets);
  return packets;
}

const AudioTrack* Source::audio() const { return api().audio(m_impl->handle); }

namespace {
std::int64_t counter(const backend::SourceHandle* handle, int which) {
  std::int64_t values[5] = {};
  api().counters(handle, values);
  return values[which];
}
}  // namespace

std::int64_t Source::droppedFrames() const { return counter(m_impl->handle, 0); }
std::int64_t Source::corruptPackets() const { return counter(m_impl->handle, 1); }
std::int64_t Source::framesRead() const { return counter(m_impl->handle, 2); }
double Source::lastFrameSeconds() const {
  const std::int64_t us = counter(m_impl->handle, 4);
  return us < 0 ? -1.0 : double(us) * 1e-6;
}
DecoderErrors Source::decoderErrors() const {
  return {.count = counter(m_impl->handle, 3), .first = api().firstDecoderError(m_impl->handle)};
}

// ---------------------------------------------------------------------------
struct Sink::Impl {
  /// The file being written (its temporary), renamed into place by finish(): here, in the
  /// program, so that a run's OutputSet stages it with the run's other outputs. Declared
  /// before the handle: the module closes its file before the temporary is removed.
  std::optional<AtomicFile> file;
  backend::SinkHandle* handle = nullptr;
  fs::path destination;
  ~Impl() {
    if (handle) api().closeSink(handle);
  }
};

bool holdsDisplayMatrix(const fs::path& destination, const std::string& format) {
  const std::string ext = lowerExtension(destination == "-" ? fs::path("stdout." + format) : destination);
  return ext == ".mp4" || ext == ".mov" || ext == ".m4v";
}

Sink::Sink(const fs::path& destination, const SinkOptions& options) : m_impl(std::make_unique<Impl>()) {
  if (options.codec == Codec::H264) checkPreset(options.preset);  // x264 would print its own error line
  if (options.displayMatrix.size() == 9 && !holdsDisplayMatrix(destination, options.format)) {
    fail(ErrorKind::Usage, "'{}': a {} file cannot hold the video's rotation (its display matrix): write .mp4 or .mov, "
         "or turn the frames upright", destination.string(), destination.extension().string());
  }
  backend::Status status;
  m_impl->destination = destination;
  if (destination != "-") m_impl->file.emplace(destination);  // checks the folder first
  m_impl->handle = api().openSink(destination, m_impl->file ? m_impl->file->temporary() : fs::path("-"), options, status);
  check(status);
}

Sink::Sink(Sink&&) noexcept = default;
Sink& Sink::operator=(Sink&&) noexcept = default;
Sink::~Sink() = default;

void Sink::write(const Frame& frame) {
  backend::Status status;
  api().write(m_impl->handle, frame, status);
  check(status);
}

void Sink::writeAudio(Packet packet) {
  backend::Status status;
  api().writeAudio(m_impl->handle, packet, status);
  check(status);
}

void Sink::finish() {
  backend::Status status;
  api().finish(m_impl->handle, status);
  check(status);
  if (m_impl->file) m_impl->file->commit();  // with the run's other outputs, when a run stages them
}

std::int64_t Sink::framesWritten() const { return api().framesWritten(m_impl->handle); }
const std::string& Sink::audioNote() const { return *api().audioNote(m_impl->handle); }
const fs::path& Sink::destination() const { return m_impl->destination; }

std::int64_t concatenate(std::span<const fs::path> parts, const fs::path& destination) {
  backend::Status status;
  AtomicFile file(destination);
  const std::int64_t frames = api().concatenate(parts, destination, file.temporary(), status);
  check(status);
  file.commit();
  return frames;
}

FrameIndex indexFrames(const std::string& path) {
  backend::Status status;
  FrameIndex index = api().indexFrames(path, status);
  check(status);
  return index;
}

}  // namespace glint::video
