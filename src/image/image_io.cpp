// Image file I/O through OpenImageIO: every format it knows, 8/16-bit and float.
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/image/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>

namespace glint {
namespace fs = std::filesystem;

namespace {
OIIO::TypeDesc oiioType(PixelType type) {
  switch (type) {
    case PixelType::U8: return OIIO::TypeDesc::UINT8;
    case PixelType::U16: return OIIO::TypeDesc::UINT16;
    case PixelType::F32: return OIIO::TypeDesc::FLOAT;
  }
  return OIIO::TypeDesc::UINT8;
}

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The widest pixel type a file format stores; wider images are converted down.
PixelType widestTypeFor(const std::string& ext) {
  if (ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff") return PixelType::F32;
  if (ext == ".png" || ext == ".ppm" || ext == ".pgm") return PixelType::U16;
  return PixelType::U8;  // tga, jpg, bmp, ...
}

std::string firstLine(std::string s) {
  if (auto nl = s.find('\n'); nl != std::string::npos) s.resize(nl);
  return s;
}
}  // namespace

Image loadImage(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", path.string());
  if (fs::is_directory(path, ec)) fail(ErrorKind::Input, "cannot read '{}': it is a directory", path.string());
  // Straight (unassociated) alpha in, straight alpha out: glint never premultiplies
  // behind the caller's back, so RGB survives a round trip whatever the alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(path.string(), &config);
  if (!input) {
    fail(ErrorKind::Input, "cannot read image '{}': {}", path.string(), firstLine(OIIO::geterror()));
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0) fail(ErrorKind::Input, "image '{}' is empty", path.string());
  PixelType type = PixelType::F32;
  if (spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::INT8) type = PixelType::U8;
  if (spec.format == OIIO::TypeDesc::UINT16 || spec.format == OIIO::TypeDesc::INT16) type = PixelType::U16;
  const int channels = std::min(spec.nchannels, 4);
  Image image(spec.width, spec.height, channels, type);
  if (!input->read_image(0, 0, 0, channels, oiioType(type), image.bytes().data())) {
    fail(ErrorKind::Input, "cannot read image '{}': {}", path.string(), firstLine(input->geterror()));
  }
  return image;
}

void saveImage(const Image& image, const fs::path& path) {
  if (image.empty()) fail(ErrorKind::Internal, "cannot save an empty image to '{}'", path.string());
  const std::string ext = lowerExtension(path);
  const PixelType widest = widestTypeFor(ext);
  const Image* toWrite = &image;
  Image convertedImage;
  if (static_cast<int>(image.type()) > static_cast<int>(widest)) {
    convertedImage = image.converted(widest);
    toWrite = &convertedImage;
  }
  writeAtomically(path, [&](const fs::path& tmp) {
    auto output = OIIO::ImageOutput::create(tmp.string());
    if (!output) {
      fail(ErrorKind::Output, "cannot write '{}': unknown image format '{}'", path.string(), ext);
    }
    OIIO::ImageSpec spec(toWrite->width(), toWrite->height(), toWrite->channels(), oiioType(toWrite->type()));
    if (toWrite->channels() == 4) {
      spec.alpha_channel = 3;
      spec.attribute("oiio:UnassociatedAlpha", 1);
    }
    if (!output->open(tmp.string(), spec) ||
        !output->write_image(oiioType(toWrite->type()), toWrite->bytes().data()) || !output->close()) {
      fail(ErrorKind::Output, "cannot write '{}': {}", path.string(), firstLine(output->geterror()));
    }
  });
}

}  // namespace glint
