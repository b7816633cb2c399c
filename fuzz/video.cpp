// Fuzz harness: video demuxing and decoding (video/source.h: libavformat and libavcodec
// through glint's FFmpeg module, then libswscale to RGBA8), the input of `glint post`. The
// first byte chooses the file name's extension (FFmpeg probes the bytes, the name is a
// hint). At most 8 frames are read; each must be a whole RGBA8 image of the stream's size.
#include "support.h"

#include "glint/core/log.h"
#include "glint/video/source.h"

#include <cstdint>

namespace {
constexpr const char* kExtensions[] = {"mkv", "mp4", "avi", "nut", "webm", "mov", "ts", "y4m"};
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Off);  // decoders warn about damage all the time here
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  const auto path = fuzz::inputFile(data, size, kExtensions);
  if (!path) return 0;
  fuzz::parse([&] {
    auto source = video::Source::open(path->string(), {.keepAudio = (data[0] & 0x80) != 0, .threads = 1});
    video::Frame frame;
    for (int i = 0; i < 8 && source.read(frame); ++i) {
      fuzz::check(frame.image.width() > 0 && frame.image.height() > 0, "a frame has pixels");
      fuzz::check(frame.image.channels() == 4 && frame.image.bytes().size() == frame.image.pixelCount() * 4,
                  "frames are whole RGBA8 images");
    }
  });
  return 0;
}
