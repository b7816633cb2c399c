// The asset reads the same in Blender (issue 35, deliverable 2): a low/high pair made in
// Blender 3.4 (Suzanne, smart-UV-unwrapped; the high poly subdivided and displaced), baked by
// glint with --asset, imported back with Blender's own glTF importer. The material has the
// normal map wired in tangent space on the mesh's UV map (a Non-Color image) and the AO as
// the glTF occlusion; and Blender's MikkTSpace tangents of the imported mesh
// (mesh.calc_tangents) agree with the tangents glint wrote, corner by corner: mean angle
// ≤ 0.1° and every bitangent sign the same. Blender's side is tests/bake/blender_asset.py;
// skipped when `blender` is not on PATH (scripts/setup --test installs it).
#include "support/cli.h"
#include "support/gltf.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using namespace glint::testing;

namespace {
constexpr auto q = shellQuote;

/// blender -b with the check script, `args` after "--"; its output on failure.
CliRun blender(const std::string& args) {
  return runShell("blender -b --factory-startup --python-exit-code 1 --python " +
                  q(fs::path(GLINT_SOURCE_DIR) / "tests/bake/blender_asset.py") + " -- " + args);
}

/// A corner as both sides can name it: Blender's position (glTF's Y up turned to Z up:
/// (x, -z, y)) and the v-up UV, rounded to 1e-4.
using CornerKey = std::tuple<long, long, long, long, long>;
CornerKey key(double x, double y, double z, double u, double v) {
  const auto r = [](double a) { return std::lround(a * 1e4); };
  return {r(x), r(y), r(z), r(u), r(v)};
}
}  // namespace

TEST(BakeAssetBlender, BlenderImportsTheAssetWithTheNormalMapInTangentSpaceAndGlintsTangents) {
  if (runShell("command -v blender").status != 0) GTEST_SKIP() << "blender is not installed (scripts/setup --test)";
  const fs::path d = freshDir("bake-asset", "blender");
  const auto made = blender("make " + q(d));
  ASSERT_EQ(made.status, 0) << made.output;
  const auto bake = runGlint("bake " + q(d / "low.obj") + " " + q(d / "high.obj") + " -o " + q(d / "n.png") + " --ao " +
                             q(d / "ao.png") + " --size 256x256 --samples 4 -q --asset " + q(d / "suzanne.glb"));
  ASSERT_EQ(bake.status, 0) << bake.output;
  const nlohmann::json verdict = validateGltf(d / "suzanne.glb");
  EXPECT_EQ(verdict.value("errors", -1), 0) << verdict.dump(1);
  EXPECT_EQ(verdict.value("warnings", -1), 0) << verdict.dump(1);
  const auto checked = blender("check " + q(d / "suzanne.glb") + " " + q(d / "blender.json"));
  ASSERT_EQ(checked.status, 0) << checked.output;
  const auto seen = nlohmann::json::parse(readBytes(d / "blender.json"));

  // The material graph.
  ASSERT_EQ(seen["objects"].size(), 1u) << seen["objects"].dump();
  ASSERT_EQ(seen["materials"].size(), 1u) << seen["materials"].dump();
  const auto& material = seen["materials"][0];
  ASSERT_TRUE(material.contains("normal_map")) << "no Normal Map node feeds the BSDF's normal: " << material.dump(1);
  EXPECT_EQ(material["normal_map"]["space"], "TANGENT");
  EXPECT_TRUE(material["normal_map"]["uv_map_is_the_mesh_s"].get<bool>()) << material.dump(1);
  EXPECT_EQ(material["normal_map"]["colorspace"], "Non-Color");
  EXPECT_TRUE(material.contains("occlusion_image") && !material["occlusion_image"].is_null()) << material.dump(1);

  // Blender's tangents against glint's, corner by corner.
  const Glb glb(d / "suzanne.glb");
  std::map<CornerKey, std::vector<std::array<double, 4>>> glint;
  for (const auto& prim : glb.json["meshes"][0]["primitives"]) {
    const auto p = glb.read<float>(prim["attributes"]["POSITION"]), uv = glb.read<float>(prim["attributes"]["TEXCOORD_0"]);
    const auto t = glb.read<float>(prim["attributes"]["TANGENT"]);
    for (std::size_t v = 0; v < p.size() / 3; ++v) {
      glint[key(p[3 * v], -p[3 * v + 2], p[3 * v + 1], uv[2 * v], 1.0 - uv[2 * v + 1])].push_back(
          {t[4 * v], -t[4 * v + 2], t[4 * v + 1], t[4 * v + 3]});
    }
  }
  double sum = 0.0, worst = 0.0;
  int corners = 0, unmatched = 0, signs = 0;
  for (const auto& c : seen["corners"]) {
    const auto found = glint.find(key(c[0], c[1], c[2], c[3], c[4]));
    if (found == glint.end()) {
      ++unmatched;
      continue;
    }
    double best = -2.0, sign = 0.0;  // where a point holds several of glint's vertices, the closest frame
    for (const auto& t : found->second) {
      const double dot = t[0] * c[5].get<double>() + t[1] * c[6].get<double>() + t[2] * c[7].get<double>();
      if (dot > best) best = dot, sign = t[3];
    }
    const double angle = std::acos(std::clamp(best, -1.0, 1.0)) * 180.0 / 3.14159265358979;
    sum += angle;
    worst = std::max(worst, angle);
    signs += sign * c[8].get<double>() > 0.0;
    ++corners;
  }
  ASSERT_GT(corners, 2000);
  EXPECT_EQ(unmatched, 0) << "Blender corners with no glint vertex at their position and UV";
  const double mean = sum / corners;
  EXPECT_LE(mean, 0.1) << "mean angle between Blender's and glint's tangents, degrees (worst " << worst << ")";
  EXPECT_EQ(signs, corners) << "bitangent signs that agree";
  std::printf("Blender vs glint tangents over %d corners: mean %.4f°, worst %.4f°, signs agree %d/%d\n", corners, mean,
              worst, signs, corners);
}
