// PNG, JPEG and OpenEXR read without the image I/O module (builtin_codecs.h): libspng,
// libjpeg-turbo and OpenEXR's own library, each as OpenImageIO reads the same file — the
// file's channels (palette expanded, tRNS as alpha), its depth (8 or 16 bits; EXR as 32-bit
// float), no colour or gamma conversion.
#include "builtin_codecs.h"

#include "glint/core/error.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImathBox.h>
#include <jpeglib.h>
#include <spng.h>

#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace glint::builtin {
namespace fs = std::filesystem;

namespace {
// The largest image read (as in image_io.cpp: 16384², a 1 GiB RGBA8 buffer).
constexpr std::uint64_t kMaxPixels = std::uint64_t(16384) * 16384;

void checkSize(const fs::path& path, std::uint64_t width, std::uint64_t height) {
  if (width == 0 || height == 0) fail(ErrorKind::Input, "image '{}' is empty", path.string());
  if (width * height > kMaxPixels)
    fail(ErrorKind::Input, "cannot read image '{}': {}x{} is larger than glint reads (16384²)", path.string(), width, height);
}

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

File openForReading(const fs::path& path) {
  File file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) fail(ErrorKind::Input, "cannot read '{}': {}", path.string(), std::strerror(errno));
  return file;
}

// ---------------------------------------------------------------------------------- PNG
/// Where an image's bytes come from: a file, or memory (an image inside a model file).
struct Source {
  fs::path path;                               ///< the name messages give
  std::span<const unsigned char> memory;       ///< read from here when `inMemory`
  bool inMemory = false;
};

Image readPng(const Source& source) {
  const fs::path& path = source.path;
  File file(nullptr, &std::fclose);
  if (!source.inMemory) file = openForReading(path);
  std::unique_ptr<spng_ctx, decltype(&spng_ctx_free)> ctx(spng_ctx_new(0), &spng_ctx_free);
  if (!ctx) fail(ErrorKind::Internal, "cannot read image '{}': out of memory", path.string());
  const auto check = [&](int status) {
    if (status != 0) fail(ErrorKind::Input, "cannot read image '{}': {}", path.string(), spng_strerror(status));
  };
  if (source.inMemory) check(spng_set_png_buffer(ctx.get(), source.memory.data(), source.memory.size()));
  else check(spng_set_png_file(ctx.get(), file.get()));
  spng_ihdr ihdr{};
  check(spng_get_ihdr(ctx.get(), &ihdr));
  checkSize(path, ihdr.width, ihdr.height);
  spng_trns trns{};
  const bool hasTrns = spng_get_trns(ctx.get(), &trns) == 0;
  // The file's channels: grey 1, grey + alpha 2, RGB or palette 3, RGBA 4; tRNS adds alpha.
  int channels = 3;
  switch (ihdr.color_type) {
    case SPNG_COLOR_TYPE_GRAYSCALE: channels = 1; break;
    case SPNG_COLOR_TYPE_GRAYSCALE_ALPHA: channels = 2; break;
    case SPNG_COLOR_TYPE_TRUECOLOR_ALPHA: channels = 4; break;
    default: channels = 3; break;
  }
  if (hasTrns && (channels == 1 || channels == 3)) ++channels;
  const bool wide = ihdr.bit_depth == 16;
  const int format = wide ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8;
  std::size_t size = 0;
  check(spng_decoded_image_size(ctx.get(), format, &size));
  std::vector<unsigned char> rgba(size);
  check(spng_decode_image(ctx.get(), rgba.data(), rgba.size(), format, SPNG_DECODE_TRNS));
  Image image(int(ihdr.width), int(ihdr.height), channels, wide ? PixelType::U16 : PixelType::U8);
  // RGBA (host order for 16 bits) to the file's channels: grey keeps R (= G = B).
  const int pick[4][4] = {{0}, {0, 3}, {0, 1, 2}, {0, 1, 2, 3}};
  const std::size_t pixels = std::size_t(ihdr.width) * ihdr.height;
  const auto narrow = [&](auto* out, const auto* in) {
    for (std::size_t i = 0; i < pixels; ++i)
      for (int c = 0; c < channels; ++c) out[i * std::size_t(channels) + std::size_t(c)] = in[i * 4 + std::size_t(pick[channels - 1][c])];
  };
  if (wide) {
    narrow(reinterpret_cast<std::uint16_t*>(image.bytes().data()), reinterpret_cast<const std::uint16_t*>(rgba.data()));
  } else {
    narrow(reinterpret_cast<unsigned char*>(image.bytes().data()), rgba.data());
  }
  return image;
}

// --------------------------------------------------------------------------------- JPEG
struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

Image readJpeg(const Source& source) {
  const fs::path& path = source.path;
  File file(nullptr, &std::fclose);
  if (!source.inMemory) file = openForReading(path);
  // Declared before setjmp: a longjmp back here leaves them as they were (libjpeg's C
  // frames are all it skips).
  jpeg_decompress_struct info{};
  JpegErrors errors{};
  std::optional<Image> image;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = [](j_common_ptr common) {
    auto* e = reinterpret_cast<JpegErrors*>(common->err);
    (*common->err->format_message)(common, e->message);
    std::longjmp(e->jump, 1);
  };
  errors.manager.output_message = [](j_common_ptr) {};  // warnings (a truncated file) are not printed
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&info);
    fail(ErrorKind::Input, "cannot read image '{}': {}", path.string(), errors.message);
  }
  jpeg_create_decompress(&info);
  if (source.inMemory) {
    if (source.memory.empty()) fail(ErrorKind::Input, "cannot read image '{}': no data", path.string());
    jpeg_mem_src(&info, source.memory.data(), static_cast<unsigned long>(source.memory.size()));
  } else {
    jpeg_stdio_src(&info, file.get());
  }
  jpeg_read_header(&info, TRUE);
  if (info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK) {
    jpeg_destroy_decompress(&info);
    fail(ErrorKind::Input, "cannot read image '{}': a CMYK JPEG needs the image I/O module", path.string());
  }
  info.out_color_space = info.num_components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&info);
  if (std::uint64_t(info.output_width) * info.output_height > kMaxPixels || info.output_width == 0) {
    jpeg_destroy_decompress(&info);
    checkSize(path, info.output_width, info.output_height);
  }
  image.emplace(int(info.output_width), int(info.output_height), int(info.output_components), PixelType::U8);
  const std::size_t stride = std::size_t(info.output_width) * std::size_t(info.output_components);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = reinterpret_cast<JSAMPROW>(image->bytes().data()) + std::size_t(info.output_scanline) * stride;
    jpeg_read_scanlines(&info, &row, 1);
  }
  // libjpeg only warns of a truncated or damaged stream (and fills the rest with grey):
  // here that is an error, not a picture.
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  if (errors.manager.num_warnings > 0)
    fail(ErrorKind::Input, "cannot read image '{}': the JPEG data is truncated or corrupt", path.string());
  return std::move(*image);
}

// ---------------------------------------------------------------------------------- EXR
Image readExr(const fs::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::ChannelList& list = file.header().channels();
    const auto has = [&](const char* name) { return list.findChannel(name) != nullptr; };
    // R, G, B (+ A); else Y (+ A); else the file's first channels, up to four.
    std::vector<std::string> names;
    if (has("R") && has("G") && has("B")) {
      names = {"R", "G", "B"};
    } else if (has("Y")) {
      names = {"Y"};
    }
    if (!names.empty() && has("A")) names.emplace_back("A");
    if (names.empty())
      for (auto it = list.begin(); it != list.end() && names.size() < 4; ++it) names.emplace_back(it.name());
    if (names.empty()) fail(ErrorKind::Input, "image '{}' has no channels", path.string());
    const Imath::Box2i window = file.header().dataWindow();
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0) fail(ErrorKind::Input, "image '{}' is empty", path.string());
    checkSize(path, std::uint64_t(width), std::uint64_t(height));
    const int channels = int(names.size());
    Image image(int(width), int(height), channels, PixelType::F32);
    float* base = reinterpret_cast<float*>(image.bytes().data());
    const std::size_t xStride = sizeof(float) * std::size_t(channels), yStride = xStride * std::size_t(width);
    // The frame buffer's origin is pixel (0, 0) of the display, so the data window's
    // first pixel lands at the image's first.
    char* origin = reinterpret_cast<char*>(base) - std::ptrdiff_t(window.min.x) * std::ptrdiff_t(xStride) -
                   std::ptrdiff_t(window.min.y) * std::ptrdiff_t(yStride);
    Imf::FrameBuffer frame;
    for (int c = 0; c < channels; ++c)
      frame.insert(names[std::size_t(c)], Imf::Slice(Imf::FLOAT, origin + std::size_t(c) * sizeof(float), xStride, yStride,
                                                      1, 1, names[std::size_t(c)] == "A" ? 1.0 : 0.0));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail(ErrorKind::Input, "cannot read image '{}': {}", path.string(), e.what());
  }
}
}  // namespace

bool reads(std::string_view extension) {
  return extension == ".png" || extension == ".jpg" || extension == ".jpeg" || extension == ".exr";
}

Image read(const fs::path& path, std::string_view extension) {
  if (extension == ".png") return readPng({path});
  if (extension == ".jpg" || extension == ".jpeg") return readJpeg({path});
  if (extension == ".exr") return readExr(path);
  fail(ErrorKind::Internal, "no built-in reader for '{}'", std::string(extension));
}

Image decode(std::span<const unsigned char> bytes, const std::string& name) {
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPng, 8) == 0) return readPng({name, bytes, true});
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return readJpeg({name, bytes, true});
  fail(ErrorKind::Input, "cannot read image '{}': neither PNG nor JPEG data", name);
}

}  // namespace glint::builtin
