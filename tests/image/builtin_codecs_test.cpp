// The built-in readers (src/image/builtin_codecs.h: PNG, JPEG, OpenEXR without the image
// I/O module) against OpenImageIO's reads of the same files, byte for byte: every PNG
// colour type and depth, JPEG in colour and grey, EXR float and half in RGB, RGBA and grey,
// the environment maps glint ships; corrupt files as one-line input errors. Then the
// fallback as a user meets it: `glint render` with the module made unreachable
// (GLINT_OIIO_MODULE naming a missing file) draws the same picture from an EXR.
#include "builtin_codecs.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/locations.h"
#include "glint/image/image.h"

#include "support/cli.h"

#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <spng.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;

namespace {
/// This test's own directory, emptied when the test first asks for it.
fs::path outDir() {
  static std::string emptied;
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  if (emptied == test) return fs::path(GLINT_TEST_OUTPUT_DIR) / "builtin-codecs" / test;
  emptied = test;
  return glint::testing::freshDir("builtin-codecs", test);
}

Image pattern(PixelType type, int channels, int width = 37, int height = 19) {
  Image image(width, height, channels, type);  // odd sizes catch row-stride bugs
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) image.set(x, y, c, float((x * 7 + y * 13 + c * 29) % 97) / 96.0f);
  return image;
}

void expectSameAsModule(const fs::path& path) {
  SCOPED_TRACE(path.filename().string());
  const Image viaModule = loadImage(path);
  std::string ext = path.extension().string();
  const Image builtin = builtin::read(path, ext);
  ASSERT_EQ(builtin.width(), viaModule.width());
  ASSERT_EQ(builtin.height(), viaModule.height());
  ASSERT_EQ(builtin.channels(), viaModule.channels());
  ASSERT_EQ(builtin.type(), viaModule.type());
  EXPECT_TRUE(std::equal(builtin.bytes().begin(), builtin.bytes().end(), viaModule.bytes().begin()))
      << "pixels differ from OpenImageIO's read";
}

/// A PNG of `color` type (SPNG_COLOR_TYPE_*) and `depth` bits, through libspng, with an
/// optional tRNS chunk: the kinds saveImage does not write (palette, tRNS, 1-bit grey).
fs::path writeSpng(const std::string& name, int color, int depth, bool trns) {
  const int w = 13, h = 7;
  spng_ctx* ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
  spng_ihdr ihdr{};
  ihdr.width = w;
  ihdr.height = h;
  ihdr.bit_depth = std::uint8_t(depth);
  ihdr.color_type = std::uint8_t(color);
  spng_set_ihdr(ctx, &ihdr);
  int samples = color == SPNG_COLOR_TYPE_TRUECOLOR ? 3 : 1;
  if (color == SPNG_COLOR_TYPE_INDEXED) {
    spng_plte plte{};
    plte.n_entries = 4;
    for (unsigned i = 0; i < 4; ++i) plte.entries[i] = {std::uint8_t(60 * i), std::uint8_t(255 - 50 * i), std::uint8_t(30 + 40 * i), 0};
    spng_set_plte(ctx, &plte);
  }
  if (trns) {
    spng_trns t{};
    if (color == SPNG_COLOR_TYPE_INDEXED) {
      t.n_type3_entries = 2;
      t.type3_alpha[0] = 0;
      t.type3_alpha[1] = 128;
    } else if (color == SPNG_COLOR_TYPE_GRAYSCALE) {
      t.gray = 1;
    } else {
      t.red = 1, t.green = 2, t.blue = 3;
    }
    spng_set_trns(ctx, &t);
  }
  const std::size_t rowBytes = (std::size_t(w) * std::size_t(samples) * std::size_t(depth) + 7) / 8;
  std::vector<unsigned char> pixels(rowBytes * h);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = std::uint8_t((i * 37) % 256);
  if (color == SPNG_COLOR_TYPE_INDEXED)
    for (auto& p : pixels) p = std::uint8_t(p % 4);
  EXPECT_EQ(spng_encode_image(ctx, pixels.data(), pixels.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE), 0);
  std::size_t size = 0;
  int status = 0;
  void* bytes = spng_get_png_buffer(ctx, &size, &status);
  const fs::path path = outDir() / name;
  std::ofstream(path, std::ios::binary).write(static_cast<const char*>(bytes), std::streamsize(size));
  std::free(bytes);
  spng_ctx_free(ctx);
  return path;
}
}  // namespace

TEST(BuiltinCodecs, PngReadsAsTheModuleReadsIt) {
  const fs::path dir = outDir();
  for (const PixelType type : {PixelType::U8, PixelType::U16})
    for (int channels = 1; channels <= 4; ++channels) {
      const fs::path path = dir / fmt::format("saved-{}-{}.png", pixelTypeName(type), channels);
      saveImage(pattern(type, channels), path);
      expectSameAsModule(path);
    }
  expectSameAsModule(writeSpng("palette.png", SPNG_COLOR_TYPE_INDEXED, 8, false));
  expectSameAsModule(writeSpng("palette-trns.png", SPNG_COLOR_TYPE_INDEXED, 2, true));
  expectSameAsModule(writeSpng("grey-1bit.png", SPNG_COLOR_TYPE_GRAYSCALE, 1, false));
  expectSameAsModule(writeSpng("rgb-trns.png", SPNG_COLOR_TYPE_TRUECOLOR, 8, true));
}

TEST(BuiltinCodecs, JpegReadsAsTheModuleReadsIt) {
  for (const int channels : {1, 3}) {
    const fs::path path = outDir() / fmt::format("photo-{}.jpg", channels);
    saveImage(pattern(PixelType::U8, channels, 161, 83), path);
    expectSameAsModule(path);
  }
}

TEST(BuiltinCodecs, ExrReadsAsTheModuleReadsIt) {
  for (int channels : {1, 3, 4}) {
    const fs::path path = outDir() / fmt::format("float-{}.exr", channels);
    saveImage(pattern(PixelType::F32, channels), path);
    expectSameAsModule(path);
  }
  // Half-float RGB with a data window that does not start at 0 (OpenEXR's own writer).
  const fs::path half = outDir() / "half-window.exr";
  {
    Imf::Header header(Imath::Box2i({0, 0}, {19, 9}), Imath::Box2i({3, 2}, {14, 8}));
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::HALF));
    Imf::OutputFile file(half.c_str(), header);
    std::vector<Imath::half> values(12 * 7 * 3);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = float(i) / 17.0f;
    Imf::FrameBuffer frame;
    const std::size_t x = sizeof(Imath::half) * 3, y = x * 12;
    char* origin = reinterpret_cast<char*>(values.data()) - 3 * x - 2 * y;
    for (int c = 0; c < 3; ++c) frame.insert(std::string(1, "RGB"[c]), Imf::Slice(Imf::HALF, origin + c * sizeof(Imath::half), x, y));
    file.setFrameBuffer(frame);
    file.writePixels(7);
  }
  expectSameAsModule(half);
  expectSameAsModule(findDataFile("env/courtyard.exr", "environment 'courtyard'"));
}

TEST(BuiltinCodecs, CorruptFilesAreOneLineInputErrors) {
  const fs::path dir = outDir();
  for (const char* name : {"bad.png", "bad.jpg", "bad.exr"}) {
    const fs::path good = dir / (std::string("good") + fs::path(name).extension().string());
    saveImage(pattern(PixelType::U8, 3, 64, 64), good);
    std::string bytes = readTextFile(good);
    bytes.resize(bytes.size() / 3);  // truncated
    writeTextAtomically(dir / name, bytes);
    try {
      builtin::read(dir / name, fs::path(name).extension().string());
      ADD_FAILURE() << name << ": no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << name << ": " << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

TEST(BuiltinCodecs, WithoutTheModuleTheCommandStillReadsPngJpegAndExr) {
  // The post photograph is made from an EXR environment map: the same picture either way.
  const fs::path dir = outDir();
  const std::string missing = "GLINT_OIIO_MODULE=" + (dir / "nowhere" / "glint_oiio.so").string();
  for (const char* variant : {"post/photo/sepia", "env/cube/front"}) {
    const fs::path with = dir / (std::string(fs::path(variant).filename()) + "-module.png");
    const fs::path without = dir / (std::string(fs::path(variant).filename()) + "-builtin.png");
    auto r = glint::testing::runGlint(fmt::format("render {} --size 96x64 -o {}", variant, with.string()));
    ASSERT_EQ(r.status, 0) << r.output;
    r = glint::testing::runGlint(fmt::format("render {} --size 96x64 -o {}", variant, without.string()), missing);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(readTextFile(with) == readTextFile(without)) << variant << ": the pictures differ";
  }
  // A format only the module reads is still its one-line error.
  const fs::path tga = dir / "module-only.tga";
  saveImage(pattern(PixelType::U8, 3), tga);
  const auto r = glint::testing::runGlint("normalmap " + tga.string() + " -o " + (dir / "n.png").string(), missing);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("GLINT_OIIO_MODULE"), std::string::npos) << r.output;
}
