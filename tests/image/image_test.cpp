#include "glint/core/error.h"
#include "glint/image/image.h"
#include "glint/image/srgb.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;

namespace {
fs::path outDir() {
  fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "image";
  fs::create_directories(dir);
  return dir;
}

Image gradient(PixelType type, int channels) {
  Image img(37, 19, channels, type);  // odd sizes catch row-stride bugs
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      for (int c = 0; c < channels; ++c) img.set(x, y, c, float(x + 3 * y + 11 * c) / 200.0f);
  return img;
}
}  // namespace

TEST(Image, NormalizedAccessRoundsToTheNearestCode) {
  Image img(2, 1, 1, PixelType::U8);
  img.set(0, 0, 0, 0.5f);
  EXPECT_EQ(img.pixels<std::uint8_t>()[0], 128);  // 127.5 rounds up
  img.set(1, 0, 0, 2.0f);
  EXPECT_EQ(img.pixels<std::uint8_t>()[1], 255);  // clamped
  img.set(1, 0, 0, NAN);
  EXPECT_EQ(img.pixels<std::uint8_t>()[1], 0);  // NaN is not garbage
}

// converted() quantizes floats in one loop; set() is the reference rounding (lround of the
// clamped value). Every half-way point between codes and its float neighbours, specials and
// random values must land on the same code in both.
TEST(Image, ConvertedQuantizesLikeSet) {
  std::vector<float> values = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, NAN, INFINITY, -INFINITY, 1e-30f, 0.49999997f};
  for (float scale : {255.0f, 65535.0f}) {
    for (int k = 0; k <= int(scale); k += scale > 300.0f ? 97 : 1) {
      for (float v : {(float(k) + 0.5f) / scale, float(k) / scale}) {
        values.insert(values.end(), {v, std::nextafter(v, 0.0f), std::nextafter(v, 2.0f)});
      }
    }
  }
  std::uint32_t state = 12345;
  for (int i = 0; i < 10000; ++i) {
    state = state * 1664525u + 1013904223u;
    values.push_back(float(state >> 8) / float(1 << 24) * 1.2f - 0.1f);
  }
  Image source(int(values.size()), 1, 1, PixelType::F32);
  std::copy(values.begin(), values.end(), source.pixels<float>().begin());
  for (PixelType type : {PixelType::U8, PixelType::U16}) {
    Image reference(source.width(), 1, 1, type);
    for (int x = 0; x < source.width(); ++x) reference.set(x, 0, 0, source.at(x, 0, 0));
    const Image fast = source.converted(type);
    for (int x = 0; x < source.width(); ++x) {
      ASSERT_EQ(fast.at(x, 0, 0), reference.at(x, 0, 0)) << "value " << values[std::size_t(x)] << ", "
                                                         << pixelTypeName(type);
    }
  }
}

TEST(Image, RejectsBadShapesAndWrongTypedViews) {
  EXPECT_THROW(Image(0, 4, 3), Error);
  EXPECT_THROW(Image(4, 4, 5), Error);
  Image img(2, 2, 1, PixelType::F32);
  EXPECT_THROW(img.pixels<std::uint8_t>(), Error);
}

TEST(Image, FlipVerticalSwapsRows) {
  Image img(1, 3, 1, PixelType::U8);
  img.set(0, 0, 0, 0.0f);
  img.set(0, 2, 0, 1.0f);
  img.flipVertical();
  EXPECT_FLOAT_EQ(img.at(0, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(img.at(0, 2, 0), 0.0f);
}

TEST(Image, LuminanceUsesRec709Weights) {
  Image rgb(1, 1, 3, PixelType::F32);
  rgb.set(0, 0, 1, 1.0f);  // pure green
  EXPECT_NEAR(rgb.withChannels(1).at(0, 0, 0), 0.7152f, 1e-6);
  EXPECT_FLOAT_EQ(rgb.withChannels(4).at(0, 0, 3), 1.0f);
}

// Round trips through real files: PNG 8/16-bit, TGA 8-bit, EXR float must return
// exactly what was written (lossless formats).
struct RoundTrip {
  const char* ext;
  PixelType type;
  int channels;
};
void PrintTo(const RoundTrip& p, std::ostream* os) { *os << pixelTypeName(p.type) << p.channels << p.ext; }
class ImageRoundTrip : public ::testing::TestWithParam<RoundTrip> {};

TEST_P(ImageRoundTrip, IsLossless) {
  const auto p = GetParam();
  const Image img = gradient(p.type, p.channels);
  const auto path = outDir() / (std::string("roundtrip_") + pixelTypeName(p.type) + std::to_string(p.channels) + p.ext);
  saveImage(img, path);
  const Image back = loadImage(path);
  EXPECT_EQ(back.type(), p.type);
  EXPECT_EQ(back.channels(), p.channels);
  const auto diff = compareImages(img, back);
  EXPECT_EQ(diff.maxAbs, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Formats, ImageRoundTrip,
                         // PNG is written by libspng and read by OpenImageIO: every colour type at both depths
                         // (16-bit samples are byte-swapped on the way out).
                         ::testing::Values(RoundTrip{".png", PixelType::U8, 1}, RoundTrip{".png", PixelType::U8, 2},
                                           RoundTrip{".png", PixelType::U8, 3}, RoundTrip{".png", PixelType::U8, 4},
                                           RoundTrip{".png", PixelType::U16, 1}, RoundTrip{".png", PixelType::U16, 2},
                                           RoundTrip{".png", PixelType::U16, 3}, RoundTrip{".png", PixelType::U16, 4},
                                           RoundTrip{".tga", PixelType::U8, 4},
                                           RoundTrip{".exr", PixelType::F32, 3}),
                         [](const auto& info) {
                           return std::string(info.param.ext + 1) + "_" +
                                  (info.param.type == PixelType::U8 ? "u8" : info.param.type == PixelType::U16 ? "u16" : "f32") +
                                  "_" + std::to_string(info.param.channels);
                         });

TEST(ImageIo, FloatIntoPngIsStoredAs16Bit) {
  const Image img = gradient(PixelType::F32, 3);
  const auto path = outDir() / "float_as.png";
  saveImage(img, path);
  const Image back = loadImage(path);
  EXPECT_EQ(back.type(), PixelType::U16);
  EXPECT_LT(compareImages(img, back).maxAbs, 1.0 / 65535.0);
}

TEST(ImageIo, MissingAndCorruptFilesAreInputErrors) {
  try {
    loadImage(outDir() / "does-not-exist.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos);
  }
  const auto corrupt = outDir() / "corrupt.png";
  std::ofstream(corrupt) << "\x89PNG\r\n\x1a\n this is not a png";
  try {
    loadImage(corrupt);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "message must be one line";
  }
}

// A header that claims more than glint reads (16384² pixels, 65536 a side) is an input
// error before any pixel memory is allocated, however few bytes the file has.
TEST(ImageIo, HeadersClaimingMoreThanGlintReadsAreRefusedBeforeAllocation) {
  const auto refused = [](const fs::path& file, const char* limit) {
    try {
      loadImage(file);
      ADD_FAILURE() << file << " was read";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
      EXPECT_NE(std::string(e.what()).find(limit), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "message must be one line";
    }
  };
  // An uncompressed 32-bit TGA header claiming 65529 × 65535 pixels (4.3 gigapixels), no pixels.
  const unsigned char tga[18] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xF9, 0xFF, 0xFF, 0xFF, 32, 8};
  const auto big = outDir() / "claims-4-gigapixels.tga";
  std::ofstream(big, std::ios::binary).write(reinterpret_cast<const char*>(tga), sizeof tga);
  refused(big, "megapixels");
  // 434 bytes of EXR (found by fuzz/image.cpp) that decoded to 15,335,428 × 3 pixels: 552 MB
  // of float pixels. The fuzz input's first byte picks the extension; the file is the rest.
  std::ifstream in(fs::path(GLINT_SOURCE_DIR) / "fuzz/regressions/image/exr-15-million-pixels-wide", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 100u);
  const auto wide = outDir() / "15-million-pixels-wide.exr";
  std::ofstream(wide, std::ios::binary) << bytes.substr(1);
  refused(wide, "a side");
}

TEST(ImageIo, UnwritableOutputIsAnOutputErrorAndLeavesNothing) {
  const Image img = gradient(PixelType::U8, 3);
  try {
    saveImage(img, "/nonexistent-glint-dir/x.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
  }
  try {
    saveImage(img, outDir() / "x.unknownformat");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
  }
  EXPECT_FALSE(fs::exists(outDir() / "x.unknownformat"));
}

TEST(CompareImages, ReportsMaxMeanAndCount) {
  Image a(4, 1, 1, PixelType::U8), b(4, 1, 1, PixelType::U8);
  b.set(1, 0, 0, 1.0f);
  const auto d = compareImages(a, b);
  EXPECT_DOUBLE_EQ(d.maxAbs, 1.0);
  EXPECT_DOUBLE_EQ(d.meanAbs, 0.25);
  EXPECT_EQ(d.differingPixels, 1u);
  EXPECT_THROW(compareImages(a, Image(3, 1, 1)), Error);
}

TEST(Srgb, EncodeAndDecodeAreTheStandardsCurveAndInverses) {
  // IEC 61966-2-1: the linear segment meets the power curve at 0.0031308 ↔ 0.04045.
  EXPECT_FLOAT_EQ(srgbEncode(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgbEncode(1.0f), 1.0f);
  EXPECT_NEAR(srgbEncode(0.0031308f), 0.04045f, 1e-5f);
  EXPECT_NEAR(srgbEncode(0.18f), 0.4613561f, 1e-6f);  // middle gray
  for (int i = 0; i <= 255; ++i) {
    const float v = float(i) / 255.0f;
    EXPECT_NEAR(srgbEncode(srgbDecode(v)), v, 2e-6f) << i;
  }
  // An image: colour clamped and encoded, alpha untouched.
  Image light(2, 1, 4, PixelType::F32);
  light.set(0, 0, 0, 2.0f);
  light.set(0, 0, 1, -1.0f);
  light.set(0, 0, 2, 0.18f);
  light.set(0, 0, 3, 0.25f);
  const Image encoded = srgbEncoded(light);
  EXPECT_FLOAT_EQ(encoded.at(0, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(encoded.at(0, 0, 1), 0.0f);
  EXPECT_FLOAT_EQ(encoded.at(0, 0, 2), srgbEncode(0.18f));
  EXPECT_FLOAT_EQ(encoded.at(0, 0, 3), 0.25f);
}
