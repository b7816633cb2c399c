// `glint render FILE` and `glint view FILE` (issue 35, deliverable 3): a bake's asset with
// every toggle doing what it says, glint cut's GLB tinted by light mask, OBJ and PLY files,
// the viewer under Xvfb, --export-web, bad files; and the viewer panel's font drawing every
// character of the scenes' texts.
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"
#include "glint/scenes/model.h"
#ifdef GLINT_HAS_VIEWER
#include "glint/viewer/viewer.h"
#endif

#include "support/cli.h"
#include "support/gltf.h"
#include "support/obj.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

namespace fs = std::filesystem;
using namespace glint;
using namespace glint::testing;

namespace {
constexpr auto q = shellQuote;

/// `glint render FILE` at 320×240 with `settings`; the picture.
Image renderFile(const fs::path& file, const fs::path& out, const std::string& settings = "") {
  const auto r = runGlint("-q render " + q(file) + " -o " + q(out) + " --size 320x240 " + settings);
  EXPECT_EQ(r.status, 0) << r.output;
  return r.status == 0 ? loadImage(out) : Image(320, 240, 3);
}

bool isBackground(const Image& im, int x, int y) {
  return std::fabs(im.at(x, y, 0) - 0x2b / 255.0f) < 0.01f && std::fabs(im.at(x, y, 1) - 0x2d / 255.0f) < 0.01f &&
         std::fabs(im.at(x, y, 2) - 0x31 / 255.0f) < 0.01f;
}

/// Share of the frame that is not background.
double coverage(const Image& im) {
  int n = 0;
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) n += !isBackground(im, x, y);
  return double(n) / (double(im.width()) * im.height());
}

/// Share of pixels whose colour differs by more than `codes`/255 in some channel.
double changed(const Image& a, const Image& b, float codes = 3.0f) {
  int n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      bool d = false;
      for (int c = 0; c < 3; ++c) d = d || std::fabs(a.at(x, y, c) - b.at(x, y, c)) > codes / 255.0f;
      n += d;
    }
  return double(n) / (double(a.width()) * a.height());
}

/// The unit sphere's share of a 320×240 frame as the model scene frames it (35° field of
/// view, bounding sphere at 1/1.05 of it): see asset_test.cpp's page test.
double sphereShare() {
  const double half = 17.5 * 3.14159265358979 / 180.0;
  const double radius = 120.0 * std::tan(std::asin(std::sin(half) / 1.05)) / std::tan(half);
  return 3.14159265358979 * radius * radius / (320.0 * 240.0);
}
}  // namespace

TEST(ModelRender, ABakesAssetShowsItsMapsAndEveryToggleChangesThePicture) {
  const fs::path d = freshDir("model", "asset");
  writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  // The high poly covers the upper half only: the lower half's rays miss.
  Mesh high = bumpySphere(0.1f);
  Mesh upper;
  upper.positions = high.positions;
  upper.normals = high.normals;
  for (std::size_t t = 0; t < high.triangleCount(); ++t) {
    const vec3 c = (high.positions[high.indices[3 * t]] + high.positions[high.indices[3 * t + 1]] +
                    high.positions[high.indices[3 * t + 2]]) / 3.0f;
    if (c.y > -0.2f)
      for (int k = 0; k < 3; ++k) upper.indices.push_back(high.indices[3 * t + std::size_t(k)]);
  }
  writeObj(upper, d / "high.obj");
  const auto bake = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n.png") + " --ao " +
                             q(d / "ao.png") + " --curvature " + q(d / "curv.png") +
                             " --size 128x64 --samples 4 --max-front 0.15 --max-rear 0.15 --ao-distance 0.5 -q --asset " +
                             q(d / "ball.glb"));
  ASSERT_EQ(bake.status, 0) << bake.output;

  const Image shaded = renderFile(d / "ball.glb", d / "shaded.png", "--camera 0,0");
  EXPECT_NEAR(coverage(shaded) / sphereShare(), 1.0, 0.05) << "the model where the camera frames it";
  // Each toggle changes the picture; `show` k shows a map, each another picture. (AO dims
  // only the environment's light, as glTF's occlusion does, and the pits are shallow: it
  // changes a tenth of the frame by a code or two.)
  const Image noAo = renderFile(d / "ball.glb", d / "no-ao.png", "--camera 0,0 --set ao=false");
  EXPECT_GT(changed(shaded, noAo, 0.5f), 0.05) << "--set ao=false";
  const std::map<std::string, double> least = {{"--set normal-map=false", 0.2},
                                               {"--set wireframe=true", 0.02}, {"--set uv-seams=true", 0.002}};
  for (const auto& [settings, share] : least) {
    const Image other = renderFile(d / "ball.glb", d / "other.png", "--camera 0,0 " + settings);
    EXPECT_GT(changed(shaded, other), share) << settings;
  }
  const auto count = [](const Image& im, auto&& pixel) {
    int n = 0;
    for (int y = 0; y < im.height(); ++y)
      for (int x = 0; x < im.width(); ++x) n += pixel(im, x, y);
    return n;
  };
  // Misses in red: below the equator's band (where the high poly stops), not above it.
  const Image misses = renderFile(d / "ball.glb", d / "misses.png", "--camera 0,0 --set misses=true");
  const auto red = [](const Image& im, int x, int y) { return im.at(x, y, 0) > 0.7f && im.at(x, y, 1) < 0.35f && im.at(x, y, 2) < 0.35f; };
  int upperRed = 0, lowerRed = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) (y < 100 ? upperRed : lowerRed) += y < 100 || y > 150 ? red(misses, x, y) : 0;
  EXPECT_EQ(upperRed, 0) << "red where the rays hit";
  EXPECT_GT(lowerRed, 3000) << "no red where the rays missed";
  EXPECT_EQ(count(shaded, red), 0);
  EXPECT_GT(changed(shaded, misses), 0.1) << "--set misses=true";
  std::set<std::string> seen;
  for (int k = 1; k <= 4; k += 3) {  // the first and the last map: normal, miss mask
    const Image map = renderFile(d / "ball.glb", d / ("show" + std::to_string(k) + ".png"), "--camera 0,0 --set show=" + std::to_string(k));
    EXPECT_GT(changed(shaded, map), 0.2) << "show=" << k;
    seen.insert(readBytes(d / ("show" + std::to_string(k) + ".png")));
  }
  EXPECT_EQ(seen.size(), 2u) << "each map its own picture";

  // Bad uses: a built-in scene has its own camera; a file that is not there, or not glTF.
  const auto camera = runGlint("render basics/triangle -o " + q(d / "x.png") + " --camera 10,10");
  EXPECT_EQ(camera.status, 2) << camera.output;
  EXPECT_TRUE(oneLine(camera.output)) << camera.output;
  const auto missing = runGlint("render " + q(d / "nothing.glb") + " -o " + q(d / "x.png"));
  EXPECT_EQ(missing.status, 3) << missing.output;
  EXPECT_TRUE(oneLine(missing.output)) << missing.output;
  std::ofstream(d / "junk.glb") << "not a glb";
  const auto junk = runGlint("render " + q(d / "junk.glb") + " -o " + q(d / "x.png"));
  EXPECT_EQ(junk.status, 3) << junk.output;
  EXPECT_TRUE(oneLine(junk.output)) << junk.output;
  EXPECT_FALSE(fs::exists(d / "x.png"));
}

TEST(ModelRender, CutsGlbShowsItsPiecesInTheirLightMasksTintsAndObjAndPlyOpen) {
  const fs::path d = freshDir("model", "cut");
  // A ball over a floor: the ball shadows part of the floor from the light.
  Mesh scene = makeIcosphere(0.5f, 2);
  for (vec3& p : scene.positions) p.y += 0.8f;
  Mesh floor = makePlane(4.0f);
  scene.append(floor);
  writeObj(scene, d / "scene.obj");
  const auto cut = runGlint("-q cut " + q(d / "scene.obj") + " -o " + q(d / "cut.glb") + " --light 0,4,0,sun");
  ASSERT_EQ(cut.status, 0) << cut.output;
  const Image picture = renderFile(d / "cut.glb", d / "cut.png", "--camera 0,60");
  std::set<std::tuple<int, int, int>> tints;  // hue buckets of the saturated pixels
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      if (isBackground(picture, x, y)) continue;
      const float r = picture.at(x, y, 0), g = picture.at(x, y, 1), b = picture.at(x, y, 2);
      if (std::max({r, g, b}) - std::min({r, g, b}) > 0.1f) tints.insert({int(r * 4), int(g * 4), int(b * 4)});
    }
  EXPECT_GE(tints.size(), 2u) << "lit and shadowed pieces in their light masks' tints";

  writeObj(makeUvSphere(1.0f, 64, 32), d / "ball.obj");
  const Image ball = renderFile(d / "ball.obj", d / "obj.png", "--camera 0,0");
  EXPECT_NEAR(coverage(ball) / sphereShare(), 1.0, 0.05) << "OBJ";
  // Hard edges: none on the smooth ball; every edge of a cube's faces (its corners have three normals).
  EXPECT_EQ(changed(ball, renderFile(d / "ball.obj", d / "obj-hard.png", "--camera 0,0 --set hard-edges=true"), 0.5f), 0.0);
  writeObj(makeCube(1.0f), d / "cube.obj");
  const Image cube = renderFile(d / "cube.obj", d / "cube.png", "--camera 30,20");
  EXPECT_GT(changed(cube, renderFile(d / "cube.obj", d / "cube-hard.png", "--camera 30,20 --set hard-edges=true")), 0.003);
  const fs::path bunny = fs::path(GLINT_SOURCE_DIR) / "data/bunny/bunny.ply";
  if (fs::exists(bunny)) {
    EXPECT_GT(coverage(renderFile(bunny, d / "ply.png")), 0.15) << "PLY";
  }
}

TEST(ModelView, TheViewerOpensAModelFileAndExportsItsPage) {
  const fs::path d = freshDir("model", "view");
  writeObj(makeUvSphere(1.0f, 16, 8), d / "low.obj");
  writeObj(bumpySphere(), d / "high.obj");
  const auto bake = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n.png") +
                             " --size 64x32 -q --asset " + q(d / "ball.glb"));
  ASSERT_EQ(bake.status, 0) << bake.output;
  // The page: the model as glint read it, written again (never the file's own bytes: what
  // glint does not read, it does not pass on), with the bake's maps; a .glb made from an
  // OBJ. The validator passes both.
  const auto web = runGlint("-q view " + q(d / "ball.glb") + " --export-web " + q(d / "web"));
  ASSERT_EQ(web.status, 0) << web.output;
  const scenes::ModelFile asset = scenes::loadModelFile(d / "ball.glb"), page = scenes::loadModelFile(d / "web/model.glb");
  ASSERT_EQ(page.parts.size(), asset.parts.size());
  EXPECT_EQ(page.parts[0].mesh.indices, asset.parts[0].mesh.indices);
  EXPECT_EQ(page.mapNames(), asset.mapNames());
  ASSERT_FALSE(page.materials.empty());
  const auto pageMap = page.materials[0].normalMap.bytes(), assetMap = asset.materials[0].normalMap.bytes();
  EXPECT_TRUE(std::equal(pageMap.begin(), pageMap.end(), assetMap.begin(), assetMap.end())) << "the normal map, texel for texel";
  const nlohmann::json pageVerdict = validateGltf(d / "web/model.glb");
  EXPECT_EQ(pageVerdict.value("errors", -1), 0) << pageVerdict.dump(1);
  for (const char* f : {"index.html", "model.js", "three/three.min.js"}) EXPECT_TRUE(fs::exists(d / "web" / f)) << f;
  const auto obj = runGlint("-q view " + q(d / "high.obj") + " --export-web " + q(d / "web-obj"));
  ASSERT_EQ(obj.status, 0) << obj.output;
  const nlohmann::json verdict = validateGltf(d / "web-obj/model.glb");
  EXPECT_EQ(verdict.value("errors", -1), 0) << verdict.dump(1);
  EXPECT_EQ(verdict.value("warnings", -1), 0) << verdict.dump(1);
  const auto notModel = runGlint("view basics/triangle --export-web " + q(d / "web-x"));
  EXPECT_EQ(notModel.status, 2) << notModel.output;

  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run not installed (scripts/setup --test)";
  const auto view = runGlint("view " + q(d / "ball.glb") + " --size 800x600 --screenshot " + q(d / "view.png") +
                             " --set misses=true --set uv-seams=true", "xvfb-run -a -s '-screen 0 1024x768x24'");
  ASSERT_EQ(view.status, 0) << view.output;
  const Image shot = loadImage(d / "view.png");
  ASSERT_EQ(shot.width(), 800);
  // The model right of the panel, the panel at the top left.
  int model = 0;
  for (int y = 100; y < 500; ++y)
    for (int x = 450; x < 750; ++x) model += !isBackground(shot, x, y);
  EXPECT_GT(model, 30000) << "the model is not where the window shows it";
}

#ifdef GLINT_HAS_VIEWER
TEST(ModelView, ThePanelFontHasAGlyphForEveryCharacterOfTheScenesTexts) {
  const std::u32string missing = viewer::glyphsMissingFromPanelFont();
  std::string shown;
  for (char32_t c : missing) shown += std::to_string(unsigned(c)) + " ";
  EXPECT_TRUE(missing.empty()) << "code points without a glyph: " << shown;
}
#endif
