#pragma once
// glint/image/image.h — a CPU image: 8-bit, 16-bit or float, 1 to 4 channels.
//
// Contents
//   Image            pixel storage, typed access, conversions
//   loadImage        read any format OpenImageIO reads (PNG, TGA, JPEG, EXR, HDR, TIFF);
//                    PNG, JPEG and EXR also without its module
//   saveImage        write atomically; format from the extension
//   preloadImageIo   start loading the image I/O module in the background
//   compareImages    max / mean difference and a visual diff image
//
// Row 0 is the TOP row, as in image files. OpenGL's window origin is the lower
// left, so GL readback (readTexture in gl/render_target.h) flips rows; do not flip twice.
// Channels are interleaved (RGBARGBA...). Integer pixels are normalized: at()
// returns 0..1 for U8 and U16, the stored value for F32.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <span>
#include <string>
#include <vector>

namespace glint {

enum class PixelType {
  U8,   ///< 8-bit unsigned normalized
  U16,  ///< 16-bit unsigned normalized
  F32   ///< 32-bit float, linear, unclamped
};

/// Bytes of one channel value of this type.
std::size_t pixelTypeSize(PixelType type);
const char* pixelTypeName(PixelType type);

/// Normalized floats → integer codes, exactly as Image::set stores them: NaN → 0, clamped
/// to 0..1, rounded to the nearest code (halves up). For whole buffers at once (one tight
/// loop). Error(Internal) when the spans differ in size.
void quantize(std::span<const float> in, std::span<std::uint8_t> out);
void quantize(std::span<const float> in, std::span<std::uint16_t> out);

class Image {
public:
  Image() = default;
  /// A zero-filled image. Throws Error(Usage) for a non-positive size or channels outside 1..4.
  Image(int width, int height, int channels, PixelType type = PixelType::U8);

  int width() const { return m_width; }
  int height() const { return m_height; }
  int channels() const { return m_channels; }
  PixelType type() const { return m_type; }
  bool empty() const { return m_data.empty(); }
  std::size_t pixelCount() const { return std::size_t(m_width) * std::size_t(m_height); }
  std::size_t bytesPerPixel() const { return pixelTypeSize(m_type) * std::size_t(m_channels); }
  std::size_t rowBytes() const { return bytesPerPixel() * std::size_t(m_width); }

  std::span<std::byte> bytes() { return m_data; }
  std::span<const std::byte> bytes() const { return m_data; }

  /// Typed views; T must match type() (uint8_t, uint16_t, float), else Error(Internal).
  template <typename T> std::span<T> pixels();
  template <typename T> std::span<const T> pixels() const;

  /// Normalized channel value (0..1 for integer types). No bounds check in release builds.
  float at(int x, int y, int c) const;
  /// Stores a normalized value, rounding and clamping to the integer range when needed.
  void set(int x, int y, int c, float value);

  /// Same pixels in another type (values clamped to 0..1 when converting to integers).
  Image converted(PixelType type) const;
  /// Same pixels with another channel count: 1 → n replicates gray (alpha = 1),
  /// 3/4 → 1 takes Rec.709 luminance, 4 → 3 drops alpha, 3 → 4 adds opaque alpha.
  Image withChannels(int channels) const;
  /// Swaps rows top ↔ bottom in place.
  void flipVertical();

  bool operator==(const Image& other) const = default;

private:
  int m_width = 0;
  int m_height = 0;
  int m_channels = 0;
  PixelType m_type = PixelType::U8;
  std::vector<std::byte> m_data;
};

/// Reads an image file ("-": standard input, any format with a magic number, or TGA).
/// Error(Input) with the reason when it is missing, unreadable or corrupt,
/// or when its header claims more than 16384² pixels or more than 65536 on a side (refused
/// before any pixel memory is allocated). 8-bit files load as U8, 16-bit as U16, everything
/// else (half, float) as F32. When the image I/O module cannot load (a bare machine),
/// PNG, JPEG and OpenEXR are still read, through libspng, libjpeg-turbo and OpenEXR's own
/// library, to the same pixels; other formats fail as requireImageIo() does.
Image loadImage(const std::filesystem::path& path);

/// A PNG or JPEG file's bytes held in memory (an image inside a model file) as loadImage
/// reads the file: the same pixels, the same 16384² limit. `name` is what a message calls
/// it ("'crate.glb' image 2"). Error(Input) for other formats or corrupt data.
Image decodeImage(std::span<const unsigned char> bytes, const std::string& name);

/// Writes an image atomically; the format follows the extension. Wider pixels than the
/// format holds are converted (float into PNG becomes 16-bit). "-" writes to standard output
/// in `format` ("png", "jpg", ...; PNG when empty). Error(Output) when the file cannot be
/// written.
void saveImage(const Image& image, const std::filesystem::path& path, std::string_view format = {});

/// The image as the bytes of a PNG file, encoded as saveImage writes one (8-bit stays 8-bit,
/// 16-bit 16; float becomes 16-bit), for files that hold images inside them (a glTF asset).
std::vector<unsigned char> encodePng(const Image& image);

/// The checks a command makes before working on an image it will write: Error(Usage) when
/// the extension names no image format glint writes (.png .jpg .jpeg .tga .tif .tiff .exr
/// .hdr .bmp .webp .ppm .pgm), Error(Output) when the file cannot be created
/// (checkWritable). For "-" (stdout) the format is `format`'s, as saveImage.
void checkImageOutput(const std::filesystem::path& path, std::string_view format = {});

/// Starts loading OpenImageIO (a dlopen()ed module: ~260 libraries, ~0.3 s) on a
/// background thread and returns at once; loadImage/saveImage wait for it, and load it
/// themselves when this was not called. Call it early in commands that touch images.
void preloadImageIo();

/// Waits for a background preloadImageIo() to finish (at once when none runs). main()
/// calls it before returning: the libraries the module loads register exit handlers as
/// they load, and exit() must not run those (OpenImageIO's GDCM, for one, tears down a
/// global another of its libraries is still constructing) while the load goes on.
void finishImageIoPreload();

/// Fails at once (Error(Internal), one line) when the image I/O module is not where glint
/// looks for it, without waiting for it to load: long commands call this before their
/// work, so a broken install is not discovered only when the result is written.
void requireImageIo();

struct ImageDifference {
  double maxAbs = 0;   ///< largest absolute channel difference, normalized 0..1
  double meanAbs = 0;  ///< mean absolute channel difference over all channels
  std::size_t differingPixels = 0;  ///< pixels with any channel differing by more than 1/255
  Image visual;        ///< RGB U8: |a - b| per pixel scaled ×8 and clamped, for eyes
};

/// Compares two images of equal size (any types/channels; compared on min(channels)).
/// Error(Usage) when the sizes differ.
ImageDifference compareImages(const Image& a, const Image& b);

}  // namespace glint
