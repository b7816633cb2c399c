// Fuzz harness: image reading (image/image.h loadImage: OpenImageIO, through glint's
// module). The first byte chooses the file name's extension, which OpenImageIO uses as a
// hint before it looks at the bytes. A decoded image must be what glint's Image promises.
#include "support.h"

#include "glint/core/log.h"
#include "glint/image/image.h"

namespace {
constexpr const char* kExtensions[] = {"png", "exr", "hdr", "jpg", "tif", "tga", "bmp", "ppm", "dds", "psd"};
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);
  glint::preloadImageIo();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  const auto path = fuzz::inputFile(data, size, kExtensions);
  if (!path) return 0;
  fuzz::parse([&] {
    const Image image = loadImage(*path);
    fuzz::check(image.width() > 0 && image.height() > 0, "a decoded image has pixels");
    fuzz::check(image.channels() >= 1 && image.channels() <= 4, "1 to 4 channels");
    fuzz::check(image.bytes().size() == image.pixelCount() * std::size_t(image.channels()) * pixelTypeSize(image.type()),
                "the pixel buffer matches the size");
  });
  return 0;
}
