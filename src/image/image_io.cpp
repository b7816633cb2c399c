// Image file I/O through OpenImageIO: every format it knows, 8/16-bit and float; PNG is
// written through libspng.
//
// OpenImageIO lives in a module (glint_oiio, see oiio_module.h) that is dlopen()ed on
// first use or by preloadImageIo() on a background thread: linking it would make the
// dynamic loader map ~260 libraries before main() of every glint command.
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/locations.h"
#include "glint/image/image.h"

#include "builtin_codecs.h"
#include "oiio_locate.h"
#include "oiio_module.h"

#include <spng.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <cerrno>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace glint {
namespace fs = std::filesystem;

namespace {
// ---------------------------------------------------------------------------------
// Loading the module

using OiioApi = GlintOiioApi;

// Loads the module (core/locations.h's loadModule); Error(Internal) when none loads.
const OiioApi& loadModule() {
  return glint::loadModule<OiioApi>(oiio::module(), "image I/O", "glint_oiio_api", GLINT_OIIO_ABI_VERSION);
}

// The module, loaded once: in the background by preload(), or by the first get().
// A failed background load is retried by get(), which reports the error. main() joins
// the background thread before it returns (finishImageIoPreload): the libraries being
// loaded register exit handlers as they load, and those run before this static's
// destructor, which joins too for processes whose main does not.
class ModuleLoader {
public:
  ~ModuleLoader() {
    if (m_thread.joinable()) m_thread.join();
  }

  void preload() {
    std::lock_guard lock(m_mutex);
    if (m_api || m_started) return;
    m_started = true;
    m_loading = true;
    try {
      m_thread = std::thread([this] {
        const OiioApi* api = nullptr;
        try {
          api = &loadModule();
        } catch (...) {  // get() retries a failed load and reports it
        }
        std::lock_guard lock(m_mutex);
        if (api) m_api = api;
        m_loading = false;
        m_done.notify_all();
      });
    } catch (const std::system_error&) {
      m_loading = false;  // no thread to spare: the first get() loads in the foreground
    }
  }

  // Joins the background load, if one was started (outside the lock, which the loader
  // takes as it ends).
  void finish() {
    std::thread loader;
    {
      std::lock_guard lock(m_mutex);
      loader = std::move(m_thread);
    }
    if (loader.joinable()) loader.join();
  }

  const OiioApi& get() {
    std::unique_lock lock(m_mutex);
    m_done.wait(lock, [&] { return !m_loading; });
    if (!m_api) m_api = &loadModule();
    return *m_api;
  }

private:
  std::mutex m_mutex;
  std::condition_variable m_done;
  std::thread m_thread;
  bool m_started = false;  // preload() ran (at most one background thread)
  bool m_loading = false;  // the background thread is still loading
  const OiioApi* m_api = nullptr;
};

ModuleLoader& theModule() {
  static ModuleLoader loader;
  return loader;
}

// ---------------------------------------------------------------------------------
// Reading and writing


// The widest pixel type a file format stores; wider images are converted down.
PixelType widestTypeFor(const std::string& ext) {
  if (ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff") return PixelType::F32;
  if (ext == ".png" || ext == ".ppm" || ext == ".pgm") return PixelType::U16;
  return PixelType::U8;  // tga, jpg, bmp, ...
}

// The module's pixel type codes follow PixelType's order.
static_assert(int(PixelType::U8) == GLINT_OIIO_U8 && int(PixelType::U16) == GLINT_OIIO_U16 &&
              int(PixelType::F32) == GLINT_OIIO_F32);

// glint_oiio_read's allocation callback: creates the Image (which may throw — kept
// here and rethrown by loadImage, since no exception may cross the C boundary).
struct ReadTarget {
  Image image;
  std::exception_ptr exception;
  std::string name;
};

// The largest image glint reads: 16384² pixels (1 GiB as RGBA8, 4 GiB as RGBA float), at
// most 65536 on a side (four times the largest GL texture). A header that claims more is
// far more often corrupt than real (found by fuzz/image.cpp: a 12 GB allocation for a few
// hundred bytes of TIFF; a 434-byte EXR that decoded to 15,335,428 × 3 pixels, 552 MB),
// and would end in an out-of-memory kill.
constexpr std::size_t kMaxReadPixels = std::size_t(16384) * 16384;
constexpr int kMaxReadSide = 65536;

void* allocateImage(void* user, int width, int height, int channels, int pixelType) {
  auto* target = static_cast<ReadTarget*>(user);
  try {
    if (std::size_t(width) * std::size_t(height) > kMaxReadPixels) {
      fail(ErrorKind::Input, "cannot read image '{}': it says it is {}×{}, more than the {} megapixels glint reads",
           target->name, width, height, kMaxReadPixels >> 20);
    }
    if (width > kMaxReadSide || height > kMaxReadSide) {
      fail(ErrorKind::Input, "cannot read image '{}': it says it is {}×{}, more than the {} pixels a side glint reads",
           target->name, width, height, kMaxReadSide);
    }
    target->image = Image(width, height, channels, static_cast<PixelType>(pixelType));
    return target->image.bytes().data();
  } catch (...) {
    target->exception = std::current_exception();
    return nullptr;
  }
}

constexpr std::size_t kErrorSize = 1024;

// PNG through libspng: zlib level 4 with the "up" row filter (see docs/bake.md, speed).
// Best of 5 writes on the 2-core machine, against OpenImageIO's writer at glint's former
// settings (level 5, "up"; module already loaded):
//                                     OpenImageIO L5     spng L5         spng L4         spng L1
//   glint bake map, 1024² RGB         32 ms   90 KB     37 ms  90 KB    30 ms  98 KB    20 ms 154 KB
//   shadows/bunny render, 1024² RGBA  36 ms  155 KB     35 ms 157 KB    31 ms 168 KB    21 ms 224 KB
//   env/sphere render, 1024² RGBA    165 ms 1078 KB    150 ms 1077 KB  103 ms 1110 KB   58 ms 1295 KB
// zlib does the work either way; what libspng saves is the OpenImageIO module, which a
// bake writing PNG no longer loads (its 0.3 s of dynamic linking ran on the core the mesh
// parser wants). Level 4 is the last level before the sizes jump (level 3: +34 % on maps).
constexpr int kPngLevel = 4;
constexpr int kPngFilter = SPNG_FILTER_CHOICE_UP;

/// An spng encoder set up for `image` (8 or 16 bits, 1 to 4 channels) at glint's settings.
std::unique_ptr<spng_ctx, decltype(&spng_ctx_free)> pngEncoder(const Image& image, const std::function<void(int)>& check) {
  std::unique_ptr<spng_ctx, decltype(&spng_ctx_free)> ctx(spng_ctx_new(SPNG_CTX_ENCODER), &spng_ctx_free);
  if (!ctx) throw std::bad_alloc();
  const bool wide = image.type() == PixelType::U16;
  static constexpr std::uint8_t kColorTypes[] = {SPNG_COLOR_TYPE_GRAYSCALE, SPNG_COLOR_TYPE_GRAYSCALE_ALPHA,
                                                 SPNG_COLOR_TYPE_TRUECOLOR, SPNG_COLOR_TYPE_TRUECOLOR_ALPHA};
  spng_ihdr ihdr{};
  ihdr.width = std::uint32_t(image.width());
  ihdr.height = std::uint32_t(image.height());
  ihdr.bit_depth = wide ? 16 : 8;
  ihdr.color_type = kColorTypes[image.channels() - 1];
  check(spng_set_ihdr(ctx.get(), &ihdr));
  check(spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_LEVEL, kPngLevel));
  check(spng_set_option(ctx.get(), SPNG_FILTER_CHOICE, kPngFilter));
  return ctx;
}

void writePng(const Image& image, const fs::path& path, const fs::path& tmp) {
  const auto check = [&](int status) {
    if (status != 0) fail(ErrorKind::Output, "cannot write '{}': {}", path.string(), spng_strerror(status));
  };
  auto ctx = pngEncoder(image, check);
  std::unique_ptr<std::FILE, decltype(&std::fclose)> file(std::fopen(tmp.c_str(), "wb"), &std::fclose);
  if (!file) fail(ErrorKind::Output, "cannot write '{}': {}", path.string(), std::strerror(errno));
  check(spng_set_png_file(ctx.get(), file.get()));
  // SPNG_FMT_PNG takes 16-bit samples in host byte order and swaps them itself.
  const std::span<const std::byte> bytes = image.bytes();
  check(spng_encode_image(ctx.get(), bytes.data(), bytes.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE));
  std::FILE* f = file.release();
  if (std::fclose(f) != 0) fail(ErrorKind::Output, "cannot write '{}': {}", path.string(), std::strerror(errno));
}
}  // namespace

std::vector<unsigned char> encodePng(const Image& image) {
  if (image.empty()) fail(ErrorKind::Internal, "encodePng: an empty image");
  const Image* toEncode = &image;
  Image wide;
  if (image.type() == PixelType::F32) {
    wide = image.converted(PixelType::U16);
    toEncode = &wide;
  }
  const auto check = [](int status) {
    if (status != 0) fail(ErrorKind::Internal, "cannot encode a PNG: {}", spng_strerror(status));
  };
  auto ctx = pngEncoder(*toEncode, check);
  check(spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1));
  const std::span<const std::byte> bytes = toEncode->bytes();
  check(spng_encode_image(ctx.get(), bytes.data(), bytes.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE));
  std::size_t size = 0;
  int status = 0;
  void* buffer = spng_get_png_buffer(ctx.get(), &size, &status);
  check(status);
  if (!buffer) throw std::bad_alloc();
  std::vector<unsigned char> png(static_cast<unsigned char*>(buffer), static_cast<unsigned char*>(buffer) + size);
  std::free(buffer);
  return png;
}

void preloadImageIo() { theModule().preload(); }

void finishImageIoPreload() { theModule().finish(); }

void requireImageIo() {
  std::error_code ec;
  for (const fs::path& path : moduleCandidates(oiio::module())) {
    if (fs::exists(path, ec)) return;
  }
  fail(ErrorKind::Internal, "cannot load the image I/O module '{}': not found ({})",
       oiio::module().built.filename().string(), moduleSearchDescription(oiio::module()));
}


// ---------------------------------------------------------------------------
namespace {
// "-": standard input and output. Image codecs read and write files, so stdin is read
// into a temporary file (named with the extension its first bytes say) and an image for
// stdout is written to one, then copied out.

/// A temporary file in $TMPDIR (or /tmp) ending in `extension`, removed with the object.
class TemporaryFile {
public:
  explicit TemporaryFile(std::string_view extension) {
    const char* dir = std::getenv("TMPDIR");
    std::string name = fmt::format("{}/glint-XXXXXX{}", dir && *dir ? dir : "/tmp", extension);
    const int fd = ::mkstemps(name.data(), int(extension.size()));
    if (fd < 0) fail(ErrorKind::Output, "cannot make a temporary file in '{}': {}", dir && *dir ? dir : "/tmp", std::strerror(errno));
    ::close(fd);
    m_path = name;
  }
  ~TemporaryFile() {
    std::error_code ignored;
    fs::remove(m_path, ignored);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  const fs::path& path() const { return m_path; }

private:
  fs::path m_path;
};

/// The extension an image file's first bytes say ("" when none matches; TGA has no magic).
std::string sniffExtension(std::string_view head) {
  using namespace std::string_view_literals;
  const auto starts = [&](std::string_view magic) { return head.substr(0, magic.size()) == magic; };
  if (starts("\x89PNG"sv)) return ".png";
  if (starts("\xFF\xD8\xFF"sv)) return ".jpg";
  if (starts("II*\0"sv) || starts("MM\0*"sv)) return ".tif";
  if (starts("\x76\x2F\x31\x01"sv)) return ".exr";
  if (starts("#?RADIANCE") || starts("#?RGBE")) return ".hdr";
  if (starts("BM")) return ".bmp";
  if (starts("RIFF") && head.size() >= 12 && head.substr(8, 4) == "WEBP") return ".webp";
  if (starts("P5") || starts("P6")) return ".ppm";
  return "";
}

/// The first `count` bytes of a file (fewer when it is shorter; none when it cannot be read).
std::string readFileHead(const fs::path& path, std::size_t count) {
  std::string head(count, '\0');
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return {};
  head.resize(std::fread(head.data(), 1, count, f));
  std::fclose(f);
  return head;
}

Image loadStdin() {
  std::string bytes;
  char buffer[1 << 16];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, stdin)) > 0;) bytes.append(buffer, n);
  if (std::ferror(stdin)) fail(ErrorKind::Input, "cannot read stdin: {}", std::strerror(errno));
  if (bytes.empty()) fail(ErrorKind::Input, "stdin is empty: pipe an image into it (glint ... - < photo.png)");
  std::string ext = sniffExtension(bytes);
  if (ext.empty()) ext = ".tga";  // the one common format without a magic number
  TemporaryFile file(ext);
  {
    std::FILE* f = std::fopen(file.path().c_str(), "wb");
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fclose(f) != 0) {
      fail(ErrorKind::Output, "cannot copy stdin to '{}': {}", file.path().string(), std::strerror(errno));
    }
  }
  try {
    return loadImage(file.path());
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Input) throw;
    fail(ErrorKind::Input, "cannot read an image from stdin: not PNG, JPEG, TIFF, EXR, HDR, BMP, WebP, PNM or TGA");
  }
}
}  // namespace

Image decodeImage(std::span<const unsigned char> bytes, const std::string& name) {
  // The built-in readers: a model's images are PNG or JPEG (glTF allows no other without
  // an extension), and they give OpenImageIO's pixels (tests/image/builtin_codecs_test.cpp).
  return builtin::decode(bytes, name);
}

Image loadImage(const fs::path& path) {
  if (path == "-") return loadStdin();
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", path.string());
  if (fs::is_directory(path, ec)) fail(ErrorKind::Input, "cannot read '{}': it is a directory", path.string());
  const OiioApi* module = nullptr;
  try {
    module = &theModule().get();
  } catch (const Error& e) {
    // No module (a bare machine): PNG, JPEG and OpenEXR are read without it, by what the
    // file's first bytes say it is (or its extension).
    if (e.kind() != ErrorKind::Internal) throw;
    std::string ext = sniffExtension(readFileHead(path, 16));
    if (ext.empty()) ext = lowerExtension(path);
    if (!builtin::reads(ext)) throw;
    return builtin::read(path, ext);
  }
  const OiioApi& oiio = *module;
  ReadTarget target;
  target.name = path.string();
  std::array<char, kErrorSize> error{};
  switch (oiio.read(path.c_str(), &allocateImage, &target, error.data(), error.size())) {
    case GLINT_OIIO_OK: return std::move(target.image);
    case GLINT_OIIO_EMPTY: fail(ErrorKind::Input, "image '{}' is empty", path.string());
    case GLINT_OIIO_ALLOC_FAILED:
      if (target.exception) std::rethrow_exception(target.exception);
      fail(ErrorKind::Internal, "cannot read image '{}': out of memory", path.string());
    case GLINT_OIIO_EXCEPTION: throw std::runtime_error(error.data());
    default: fail(ErrorKind::Input, "cannot read image '{}': {}", path.string(), error.data());
  }
}

namespace {
/// The extension an image written to `path` gets: its own, or for "-" (stdout) `format`'s
/// ("png" or ".png"; PNG when empty). Lower case.
std::string outputExtension(const fs::path& path, std::string_view format) {
  if (path != "-") return lowerExtension(path);
  if (format.empty()) return ".png";
  return lowerExtension(fs::path("stdout" + std::string(format.starts_with('.') ? "" : ".") + std::string(format)));
}
}  // namespace

void checkImageOutput(const fs::path& path, std::string_view format) {
  static constexpr std::array<std::string_view, 12> kWritten = {".png", ".jpg", ".jpeg", ".tga", ".tif", ".tiff",
                                                                ".exr", ".hdr", ".bmp", ".webp", ".ppm", ".pgm"};
  const std::string ext = outputExtension(path, format);
  if (std::find(kWritten.begin(), kWritten.end(), ext) == kWritten.end()) {
    fail(ErrorKind::Usage, "cannot write '{}': {} is not an image format (use .png, .jpg, .tga, .tif, .exr, .hdr, "
         ".bmp or .webp)", path.string(), ext.empty() ? "no extension" : "'" + ext + "'");
  }
  if (path != "-") checkWritable(path);
}

namespace {
/// Encodes `image` into the file `target` (written directly), in the format of `ext`;
/// messages name `path`.
void encodeImage(const Image& image, const fs::path& path, const std::string& ext, const fs::path& target) {
  const PixelType widest = widestTypeFor(ext);
  const Image* toWrite = &image;
  Image convertedImage;
  if (static_cast<int>(image.type()) > static_cast<int>(widest)) {
    convertedImage = image.converted(widest);
    toWrite = &convertedImage;
  }
  if (ext == ".png") {
    writePng(*toWrite, path, target);
    return;
  }
  const OiioApi& oiio = theModule().get();
  std::array<char, kErrorSize> error{};
  const int status = oiio.write(target.c_str(), toWrite->width(), toWrite->height(), toWrite->channels(),
                                static_cast<int>(toWrite->type()), toWrite->bytes().data(), toWrite->channels() == 4,
                                error.data(), error.size());
  switch (status) {
    case GLINT_OIIO_OK: return;
    case GLINT_OIIO_UNKNOWN_FORMAT:
      fail(ErrorKind::Output, "cannot write '{}': unknown image format '{}'", path.string(), ext);
    case GLINT_OIIO_EXCEPTION: throw std::runtime_error(error.data());
    default: fail(ErrorKind::Output, "cannot write '{}': {}", path.string(), error.data());
  }
}
}  // namespace

void saveImage(const Image& image, const fs::path& path, std::string_view format) {
  if (image.empty()) fail(ErrorKind::Internal, "cannot save an empty image to '{}'", path.string());
  if (path == "-") {  // encoded into a temporary file (codecs write files), then copied to stdout
    const std::string ext = outputExtension(path, format);
    TemporaryFile file(ext);
    encodeImage(image, "stdout", ext, file.path());
    const std::string bytes = readTextFile(file.path());
    if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0) {
      fail(ErrorKind::Output, "cannot write the image to stdout: {}", std::strerror(errno));
    }
    return;
  }
  const std::string ext = lowerExtension(path);
  writeAtomically(path, [&](const fs::path& tmp) { encodeImage(image, path, ext, tmp); });
}

}  // namespace glint
