// `glint normalmap` as a user runs it: CPU and GPU give the same map, colour inputs are
// converted with a warning, odd sizes work, bad input gets one line and the right exit code.
#include "glint/image/heightfield.h"
#include "glint/image/image.h"
#include "glint/image/normalmap.h"

#include "support/cli.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using namespace glint;

namespace {
using Run = glint::testing::CliRun;
using glint::testing::fileCount;
using glint::testing::oneLine;
using glint::testing::runGlint;

fs::path dir() {
  return glint::testing::freshDir("normalmap-cli", ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

Image oddHeight() {  // 8-bit gray, 45×29: neither side a power of two
  Image h = makeBrickHeight(64).converted(PixelType::U8);
  Image out(45, 29, 1);
  for (int y = 0; y < 29; ++y)
    for (int x = 0; x < 45; ++x) out.set(x, y, 0, h.at(x, y, 0));
  return out;
}
}  // namespace

TEST(NormalMapCli, CpuAndGpuAgreeAndMatchTheLibrary) {
  const fs::path d = dir();
  const Image height = oddHeight();
  saveImage(height, d / "h.png");
  const std::string in = (d / "h.png").string();
  auto cpu = runGlint("normalmap " + in + " -o " + (d / "cpu.png").string() + " --scale 12 --wrap");
  ASSERT_EQ(cpu.status, 0) << cpu.output;
  auto gpu = runGlint("normalmap " + in + " -o " + (d / "gpu.png").string() + " --scale 12 --wrap --gpu");
  ASSERT_EQ(gpu.status, 0) << gpu.output;
  const Image a = loadImage(d / "cpu.png"), b = loadImage(d / "gpu.png");
  EXPECT_EQ(a.width(), 45);
  EXPECT_EQ(a.height(), 29);
  EXPECT_EQ(a, heightToNormalMap(height, {.scale = 12.0f, .wrap = true}).withChannels(3));  // a normal map is RGB
  EXPECT_LE(compareImages(a, b).maxAbs, 1.0 / 255 + 1e-6);
  EXPECT_EQ(cpu.output.find("warning"), std::string::npos) << "a gray input needs no warning";
}

TEST(NormalMapCli, ColourInputUsesLuminanceAndSaysSo) {
  const fs::path d = dir();
  saveImage(makeBrickAlbedo(32), d / "colour.png");
  const auto r = runGlint("normalmap " + (d / "colour.png").string() + " -o " + (d / "n.png").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("luminance"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(d / "n.png"));
}

TEST(NormalMapCli, BadInputGetsOneLineAndNoOutputFile) {
  const fs::path d = dir();
  const auto missing = runGlint("normalmap " + (d / "missing.png").string() + " -o " + (d / "n.png").string());
  EXPECT_EQ(missing.status, 3);
  EXPECT_EQ(std::count(missing.output.begin(), missing.output.end(), '\n'), 1) << missing.output;
  std::FILE* f = std::fopen((d / "corrupt.png").c_str(), "wb");
  std::fputs("not a png", f);
  std::fclose(f);
  const auto corrupt = runGlint("normalmap " + (d / "corrupt.png").string() + " -o " + (d / "n.png").string());
  EXPECT_EQ(corrupt.status, 3) << corrupt.output;
  const auto usage = runGlint("normalmap " + (d / "corrupt.png").string() + " -o " + (d / "n.png").string() +
                              " --formula sideways");
  EXPECT_EQ(usage.status, 2) << usage.output;
  const auto unwritable = runGlint("normalmap " + (d / "corrupt.png").string() + " -o /nonexistent-dir/n.png");
  EXPECT_EQ(unwritable.status, 4) << unwritable.output;
  EXPECT_FALSE(fs::exists(d / "n.png"));
}

TEST(NormalMapCli, CheckReportsGoodMapsAndExplainsBadOnes) {
  const fs::path d = dir();
  saveImage(heightToNormalMap(makeBumpsHeight(64), {.wrap = true}), d / "good.png");
  saveImage(makeBumpsHeight(64).converted(PixelType::U8), d / "height.png");
  saveImage(makeBrickAlbedo(64), d / "colour.png");
  const auto good = runGlint("normalmap --check " + (d / "good.png").string());
  EXPECT_EQ(good.status, 0) << good.output;
  EXPECT_NE(good.output.find("tangent-space normal map"), std::string::npos) << good.output;
  const auto height = runGlint("normalmap --check " + (d / "height.png").string());
  EXPECT_EQ(height.status, 3);
  EXPECT_NE(height.output.find("height map"), std::string::npos) << height.output;
  const auto colour = runGlint("normalmap --check " + (d / "colour.png").string());
  EXPECT_EQ(colour.status, 3);
  EXPECT_NE(colour.output.find("mean length"), std::string::npos) << colour.output;
  EXPECT_EQ(std::count(colour.output.begin(), colour.output.end(), '\n'), 1) << colour.output;
  const auto noOutput = runGlint("normalmap " + (d / "height.png").string());
  EXPECT_EQ(noOutput.status, 2) << noOutput.output;
}

// A normal map is RGB: it used to come out RGBA with an opaque alpha whatever the input. A
// height map with alpha keeps it; stdin and stdout work ('-', --format for stdout).
TEST(NormalMapCli, WritesRgbKeepsAlphaAndPipes) {
  const fs::path d = dir();
  const Image grey = oddHeight();
  saveImage(grey, d / "h.png");
  Image withAlpha(grey.width(), grey.height(), 2);
  for (int y = 0; y < grey.height(); ++y)
    for (int x = 0; x < grey.width(); ++x) {
      withAlpha.set(x, y, 0, grey.at(x, y, 0));
      withAlpha.set(x, y, 1, float((x * 7 + y) % 256) / 255.0f);
    }
  saveImage(withAlpha, d / "ha.png");
  ASSERT_EQ(runGlint("-q normalmap " + (d / "h.png").string() + " -o " + (d / "n.png").string()).status, 0);
  const Image n = loadImage(d / "n.png");
  EXPECT_EQ(n.channels(), 3);
  const Image library = heightToNormalMap(grey, {});
  for (int y = 0; y < n.height(); ++y)
    for (int x = 0; x < n.width(); ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(n.at(x, y, c), library.at(x, y, c)) << x << "," << y;
  ASSERT_EQ(runGlint("-q normalmap " + (d / "ha.png").string() + " -o " + (d / "na.png").string()).status, 0);
  const Image na = loadImage(d / "na.png");
  ASSERT_EQ(na.channels(), 4);
  for (int y = 0; y < na.height(); ++y)
    for (int x = 0; x < na.width(); ++x) ASSERT_EQ(na.at(x, y, 3), withAlpha.at(x, y, 1)) << x << "," << y;

  const auto piped = glint::testing::runShell(std::string(GLINT_EXE) + " -q normalmap - -o - --format tga < " +
                                              (d / "h.png").string() + " > " + (d / "piped.tga").string());
  ASSERT_EQ(piped.status, 0) << piped.output;
  EXPECT_EQ(loadImage(d / "piped.tga"), n);
}
