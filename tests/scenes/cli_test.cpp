// The glint command as a user runs it: exit codes, one-line errors, atomic outputs,
// and the viewer in a real X window (Xvfb).
#include "glint/image/image.h"

#include "support/cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace glint;

namespace {
using Run = glint::testing::CliRun;
using glint::testing::fileCount;
using glint::testing::oneLine;
using glint::testing::runGlint;

fs::path dir(const char* name) { return glint::testing::freshDir("cli", name); }

bool haveXvfbAndXdotool() {
  return std::system("command -v xvfb-run >/dev/null 2>&1 && command -v xdotool >/dev/null 2>&1") == 0;
}

/// How two screenshots differ over the columns x ≥ x0 (right of where the viewer's panel
/// can be, whose frame-time text changes every frame).
struct SceneDifference {
  double differing = 0;  ///< fraction of pixels with a channel differing by more than 1/255
  double mean = 0;       ///< mean absolute channel difference, 0..1
};
SceneDifference sceneDifference(const Image& a, const Image& b, int x0) {
  EXPECT_EQ(a.width(), b.width());
  EXPECT_EQ(a.height(), b.height());
  std::size_t differing = 0, n = 0;
  double sum = 0;
  for (int y = 0; y < std::min(a.height(), b.height()); ++y)
    for (int x = x0; x < std::min(a.width(), b.width()); ++x, ++n) {
      float worst = 0;
      for (int c = 0; c < 3; ++c) {
        const float d = std::abs(a.at(x, y, c) - b.at(x, y, c));
        worst = std::max(worst, d);
        sum += d;
      }
      differing += worst > 1.5f / 255.0f;
    }
  return {double(differing) / double(std::max<std::size_t>(n, 1)), sum / double(std::max<std::size_t>(3 * n, 1))};
}

}  // namespace

// `glint info --json` is what scripts/gpu-check reads; on a software renderer (this
// machine's llvmpipe) the check says so in one line, exits 3 and measures nothing.
TEST(Cli, InfoJsonAndGpuCheckSayWhetherThereIsAGpu) {
  const auto info = runGlint("info --json");
  ASSERT_EQ(info.status, 0) << info.output;
  const auto j = nlohmann::json::parse(info.output, nullptr, false);
  ASSERT_TRUE(j.is_object()) << info.output;
  EXPECT_FALSE(j.at("renderer").get<std::string>().empty());
  EXPECT_TRUE(j.at("version").get<std::string>().starts_with("4.5")) << j.at("version");
  EXPECT_GE(j.at("stencil_bits").get<int>(), 8);
  const bool software = j.at("software").get<bool>();
  EXPECT_EQ(software, j.at("renderer").get<std::string>().find("llvmpipe") != std::string::npos) << j.at("renderer");
  if (!software) return;  // a real GPU: gpu-check would measure for 8 minutes
  const fs::path out = dir("gpu-check");
  const auto check = glint::testing::runShell(std::string(GLINT_SOURCE_DIR) + "/scripts/gpu-check -o " + out.string() +
                                              " --glint " + GLINT_EXE);
  EXPECT_EQ(check.status, 3) << check.output;
  EXPECT_TRUE(oneLine(check.output)) << check.output;
  EXPECT_NE(check.output.find("no GPU"), std::string::npos) << check.output;
  std::ifstream in(out / "gpu-check.json");
  const auto report = nlohmann::json::parse(in, nullptr, false);
  ASSERT_TRUE(report.is_object());
  EXPECT_TRUE(report.at("status").get<std::string>().starts_with("no GPU")) << report.dump();
  EXPECT_TRUE(report.at("info").at("software").get<bool>());
  EXPECT_TRUE(report.at("bench").empty());
}

TEST(Cli, ListNamesEveryVariant) {
  const auto r = runGlint("list --names");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("basics/triangle/color\n"), std::string::npos);
  EXPECT_NE(r.output.find("basics/depth/mask-off\n"), std::string::npos);
}

TEST(Cli, VersionPrintsTheProjectVersion) {
  const auto r = runGlint("--version");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.rfind("glint ", 0), 0u) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
}

// OpenImageIO (~260 libraries with Debian's build) is a module loaded only by commands
// that touch images; the dynamic loader's own log shows which objects a run opened.
TEST(Cli, OnlyCommandsThatTouchImagesLoadOpenImageIO) {
  auto r = runGlint("list --names", "LD_DEBUG=files");
  ASSERT_EQ(r.status, 0);
  EXPECT_EQ(r.output.find("libOpenImageIO"), std::string::npos);
  const auto d = dir("oiio");
  r = runGlint("render basics/triangle/color --size 32x32 -o " + (d / "t.png").string(), "LD_DEBUG=files");
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("libOpenImageIO"), std::string::npos);
}

TEST(Cli, RenderWritesTheImageAndNothingElse) {
  const auto d = dir("render");
  const auto r = runGlint("render basics/triangle/depth --size 64x48 -o " + (d / "t.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Image img = loadImage(d / "t.png");
  EXPECT_EQ(img.width(), 64);
  EXPECT_EQ(img.height(), 48);
  EXPECT_EQ(fileCount(d), 1u);  // no temporaries left behind
}

// glint gallery --references: every variant against its reference image at the golden
// tests' tolerance (scenes::checkAgainstReference), as gpu-check runs it on a bare GPU
// machine. The source tree's references pass; a reference with a changed patch fails,
// exit 1, with its figures in gallery.json and a difference image; a missing one too.
TEST(Cli, GalleryComparesEveryVariantWithItsReference) {
  const auto d = dir("gallery-references");
  const fs::path golden = fs::path(GLINT_SOURCE_DIR) / "tests" / "golden";
  auto r = runGlint("gallery --filter basics/triangle --repeats 0 --references " + golden.string() + " -o " +
                    (d / "same").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("2 of 2 variants within the tolerance"), std::string::npos) << r.output;
  const auto same = nlohmann::json::parse(std::ifstream(d / "same" / "gallery.json"));
  for (const auto& v : same["variants"]) {
    EXPECT_TRUE(v["reference"]["pass"].get<bool>()) << v.dump();
    EXPECT_LE(v["reference"]["mean_steps"].get<double>(), 0.5) << v.dump();
  }

  const fs::path changed = d / "references" / "basics" / "triangle";
  fs::create_directories(changed);
  Image color = loadImage(golden / "basics" / "triangle" / "color.png");
  for (int y = 200; y < 240; ++y)
    for (int x = 200; x < 240; ++x) color.set(x, y, 0, 1.0f - color.at(x, y, 0));
  saveImage(color, changed / "color.png");  // and no depth.png
  r = runGlint("gallery --filter basics/triangle --repeats 0 --references " + (d / "references").string() + " -o " +
               (d / "changed").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("basics/triangle/color: beyond the reference's tolerance"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("basics/triangle/depth: no reference image"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(d / "changed" / "basics" / "triangle" / "color.diff.png"));
  const auto json = nlohmann::json::parse(std::ifstream(d / "changed" / "gallery.json"));
  EXPECT_FALSE(json["variants"][0]["reference"]["pass"].get<bool>());
  EXPECT_GT(json["variants"][0]["reference"]["differing_percent"].get<double>(), 0.5);
  EXPECT_TRUE(json["variants"][1]["reference"].contains("missing"));

  // Where the video module cannot load (a bare GPU machine's pack), post/camera, whose frames
  // come through it, is skipped and marked; the comparison of the rest still passes.
  r = runGlint("gallery --filter post/camera/sepia --repeats 0 --references " + golden.string() + " -o " +
                   (d / "no-video").string(),
               "GLINT_FFMPEG_MODULE=" + (d / "nowhere" / "glint_ffmpeg.so").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("post/camera/sepia: skipped (its frames come through the video module: cannot load"),
            std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0 of 0 variants within the tolerance"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 skipped"), std::string::npos) << r.output;
  const auto noVideo = nlohmann::json::parse(std::ifstream(d / "no-video" / "gallery.json"));
  EXPECT_NE(noVideo["variants"][0]["skipped"].get<std::string>().find("video module"), std::string::npos);
}

TEST(Cli, UnknownSceneOrVariantIsAUsageError) {
  auto r = runGlint("render basics/nope -o /tmp/x.png");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("unknown scene 'basics/nope'"), std::string::npos) << r.output;
  r = runGlint("render basics/triangle/nope -o /tmp/x.png");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("variants: color, depth"), std::string::npos) << r.output;
}

TEST(Cli, BadSizeAndBadNumbersAreUsageErrors) {
  for (const char* size : {"12x", "0x10", "axb", "100000x10", "10x10x"}) {
    const auto r = runGlint(std::string("render basics/triangle/color --size ") + size + " -o /tmp/x.png");
    EXPECT_EQ(r.status, 2) << size << ": " << r.output;
    EXPECT_TRUE(oneLine(r.output)) << r.output;
  }
  const auto r = runGlint("render basics/triangle/color --time soon -o /tmp/x.png");
  EXPECT_EQ(r.status, 2) << r.output;
}

TEST(Cli, UnwritableOutputFailsBeforeRenderingAndLeavesNothing) {
  const auto r = runGlint("render basics/triangle/color -o /nonexistent-dir/x.png");
  EXPECT_EQ(r.status, 4);
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  const auto d = dir("unknown-format");
  const auto r2 = runGlint("render basics/triangle/color -o " + (d / "x.notaformat").string());
  EXPECT_EQ(r2.status, 2) << r2.output;  // an extension that names no image format: a usage error, as in every tool
  EXPECT_EQ(fileCount(d), 0u);
}

TEST(Cli, NoOpenGLSaysWhatToInstall) {
  // Point glvnd at no EGL vendor: exactly what a machine without Mesa's EGL looks like.
  const auto r = runGlint("render basics/triangle/color -o /tmp/x.png", "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json");
  EXPECT_EQ(r.status, 5) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("apt-get install"), std::string::npos) << r.output;
}

TEST(Cli, ViewerOpensAWindowWithTheSceneAndThePanel) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run not installed (scripts/setup --test)";
  const auto d = dir("viewer");
  const auto shot = d / "viewer.png";
  const auto r = runGlint("view basics/triangle/color --size 800x600 --frames 3 --screenshot " + shot.string(),
                       "xvfb-run -a -s '-screen 0 1024x768x24'");
  ASSERT_EQ(r.status, 0) << r.output;
  const Image img = loadImage(shot);
  ASSERT_EQ(img.width(), 800);
  ASSERT_EQ(img.height(), 600);
  // The scene: a point inside the triangle right of the panel, at NDC (0.3, 0.2), is a
  // blend of all three vertex colours (not the clear colour, not black).
  const int x = int((0.3f + 1) * 400), y = 600 - 1 - int((0.2f + 1) * 300);
  EXPECT_GT(img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2), 0.6f);
  EXPECT_GT(img.at(x, y, 1), 0.2f);  // green weight is large there
  // The panel: ImGui's near-black window background with light text in the top left.
  int text = 0, dark = 0;
  for (int py = 12; py < 120; ++py)
    for (int px = 12; px < 300; ++px) {
      const float sum = img.at(px, py, 0) + img.at(px, py, 1) + img.at(px, py, 2);
      text += sum > 2.4f;
      dark += sum < 0.35f;
    }
  EXPECT_GT(text, 50) << "no panel text found";
  EXPECT_GT(dark, 5000) << "no panel background found";
}

TEST(Cli, ViewerShotDirMustBeADirectory) {
  // Checked before any window opens: no display needed.
  const auto r = runGlint("view basics/triangle --shot-dir /nonexistent-dir");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(oneLine(r.output)) << r.output;
  EXPECT_NE(r.output.find("--shot-dir"), std::string::npos) << r.output;
}

// The mouse on a real X server: tests/scenes/viewer_input.sh drives `glint view` with
// xdotool (XTEST: the events a user's mouse makes) and saves F12 screenshots; see the
// script for the steps. Compared right of x = 520, where the panel never is (it starts at
// x 10..390 and is dragged left).
TEST(Cli, ViewerMouseOrbitsPansAndZoomsThe3DCameraAndLeaves2DViewsAlone) {
  if (!haveXvfbAndXdotool()) GTEST_SKIP() << "xvfb-run or xdotool not installed (scripts/setup --test)";
  const auto d = dir("viewer-input");
  const std::string script = std::string(GLINT_SOURCE_DIR) + "/tests/scenes/viewer_input.sh";
  const auto r = glint::testing::runShell("xvfb-run -a -s '-screen 0 1024x768x24' " + script + " " GLINT_EXE " " + d.string());
  ASSERT_EQ(r.status, 0) << r.output;
  constexpr int kX0 = 520;
  const auto shot = [&](const char* scene, int n) { return loadImage(d / scene / ("glint-view-" + std::to_string(n) + ".png")); };
  // Same view, same renderer, a static scene: the pictures are identical; the slack (0.1%
  // of pixels, mean 0.2/255) only keeps a stray edge pixel from failing the test.
  const auto same = [&](const Image& a, const Image& b) {
    const SceneDifference diff = sceneDifference(a, b, kX0);
    return diff.differing <= 0.001 && diff.mean <= 0.2 / 255.0;
  };
  // A moved camera moves most of the picture (measured: 60–100% of these pixels).
  const auto moved = [&](const Image& a, const Image& b) { return sceneDifference(a, b, kX0).differing > 0.3; };

  const Image defined = shot("3d", 2);
  ASSERT_EQ(defined.width(), 800);
  ASSERT_EQ(defined.height(), 600);
  EXPECT_TRUE(same(shot("3d", 1), defined)) << "the scene is not static: the comparisons below mean nothing";
  EXPECT_TRUE(same(shot("3d", 3), defined)) << "a drag on the panel moved the camera";
  EXPECT_TRUE(moved(shot("3d", 4), defined)) << "a left drag did not orbit";
  EXPECT_TRUE(same(shot("3d", 5), defined)) << "C did not return to the defined camera";
  EXPECT_TRUE(moved(shot("3d", 6), defined)) << "the wheel did not zoom";
  EXPECT_TRUE(moved(shot("3d", 7), defined)) << "a right drag did not pan";
  EXPECT_TRUE(same(shot("3d", 8), defined)) << "Home did not return to the defined camera";

  // basics/triangle draws NDC vertices: the same picture whatever the mouse did. (Part of
  // the triangle is in the compared columns, so "the same" is not a blank compared to itself.)
  const Image flat = shot("2d", 2);
  int triangle = 0;
  for (int y = 0; y < flat.height(); ++y)
    for (int x = kX0; x < flat.width(); ++x) triangle += flat.at(x, y, 1) > 0.3f;
  EXPECT_GT(triangle, 5000);
  EXPECT_TRUE(same(shot("2d", 3), flat)) << "the mouse changed a 2D view";
}
