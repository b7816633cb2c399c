// Bake groups matched by name, the material ID map and the vertex colour map (issue 23),
// each against an answer computed here: a group baked with others equals it baked alone,
// every material texel is exactly its material's colour, a linear colour ramp comes back.
#include "bake_test_util.h"

#include "glint/bake/groups.h"
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/mesh/parts.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

using namespace glint;
using namespace bake_test;

namespace {

/// A mesh as one named part.
MeshParts part(const Mesh& mesh, const std::string& name) {
  MeshParts p;
  p.mesh = mesh;
  p.partNames = {name};
  p.trianglePart.assign(mesh.triangleCount(), 0);
  return p;
}

/// Parts side by side in one MeshParts (as a file with several objects reads).
MeshParts combined(const std::vector<MeshParts>& parts) {
  MeshParts all;
  for (const MeshParts& p : parts) {
    const auto base = std::uint32_t(all.partNames.size());
    all.mesh.append(p.mesh);
    all.partNames.insert(all.partNames.end(), p.partNames.begin(), p.partNames.end());
    for (std::uint32_t t : p.trianglePart) all.trianglePart.push_back(base + t);
  }
  return all;
}

Mesh moved(Mesh m, vec3 offset) {
  for (vec3& p : m.positions) p += offset;
  return m;
}

/// UVs squeezed into u in [u0, u0 + 0.5) (with a margin), so two parts share one map.
Mesh inHalf(Mesh m, float u0) {
  for (vec2& uv : m.uvs) uv = vec2(u0 + 0.02f + 0.46f * uv.x, 0.02f + 0.96f * uv.y);
  return m;
}

}  // namespace

TEST(BakeGroups, NamesFollowTheSuffixConvention) {
  EXPECT_EQ(bake::groupName("body_low", "_low", false), "body");
  EXPECT_EQ(bake::groupName("body_high", "_high", true), "body");
  EXPECT_EQ(bake::groupName("body_high_bolts", "_high", true), "body");
  EXPECT_EQ(bake::groupName("body_high_bolts", "_low", false), "");
  EXPECT_EQ(bake::groupName("body", "_high", true), "");
  EXPECT_EQ(bake::groupName("_high", "_high", true), "");
  EXPECT_EQ(bake::groupName("body_high_", "_high", true), "");
}

// Two spheres that interpenetrate (centres 0.8 apart, radius 1): baked without groups,
// the rays of each low sphere inside the other hit the other's high surface. With groups
// each half of the map must equal, byte for byte, the bake of that group alone.
TEST(BakeGroups, InterpenetratingGroupsBakeAsIfAlone) {
  log::setLevel(log::Level::Error);
  const vec3 ca(-0.4f, 0.0f, 0.0f), cb(0.4f, 0.0f, 0.0f);
  const MeshParts lowA = part(inHalf(moved(makeUvSphere(0.97f, 24, 12), ca), 0.0f), "a_low");
  const MeshParts lowB = part(inHalf(moved(makeUvSphere(0.97f, 24, 12), cb), 0.5f), "b_low");
  const MeshParts highA = part(moved(makeUvSphere(1.0f, 96, 48), ca), "a_high");
  const MeshParts highB1 = part(moved(makeUvSphere(1.0f, 96, 48), cb), "b_high_1");
  const MeshParts highB2 = part(moved(makeIcosphere(0.3f, 2), cb + vec3(0, 0, 1.0f)), "b_high_bolt");
  const MeshParts low = combined({lowA, lowB});
  const MeshParts high = combined({highB1, highA, highB2});  // order does not matter

  const bake::GroupMatch match = bake::matchGroups(low, high);
  ASSERT_EQ(match.groups.size(), 2u);
  EXPECT_EQ(match.groups[0].name, "a");
  EXPECT_EQ(match.groups[1].highParts, (std::vector<std::string>{"b_high_1", "b_high_bolt"}));
  EXPECT_TRUE(match.unmatchedLow.empty());
  EXPECT_TRUE(match.unmatchedHigh.empty());
  const nlohmann::ordered_json report = bake::toJson(match);
  EXPECT_EQ(report["groups"][1]["name"], "b");

  bake::BakeOptions options;
  options.width = options.height = 128;
  options.samples = 4;
  options.normalType = PixelType::U8;
  options.maxFront = {0.3f, false};  // absolute: the low poly's diagonal differs alone
  options.maxRear = {0.3f, false};
  options.maps.add(bake::Map::Height);
  options.maps.add(bake::Map::Ao);  // AO rays too see only their group
  options.aoSamples = 8;
  options.aoDistance = {0.5f, false};
  options.padding = 4;
  options.progress = false;
  const bake::BakeResult together = bake::bake(low, high, match, options);
  const bake::BakeResult aloneA = bake::bake(lowA, highA, bake::matchGroups(lowA, highA), options);
  const MeshParts highB = combined({highB1, highB2});
  const bake::BakeResult aloneB = bake::bake(lowB, highB, bake::matchGroups(lowB, highB), options);
  const bake::BakeResult naive = bake::bake(low.mesh, high.mesh, options);

  int compared = 0, differentNormal = 0, differentHeight = 0, differentAo = 0, naiveDifferent = 0;
  for (int row = 0; row < 128; ++row) {
    for (int x = 0; x < 128; ++x) {
      const bake::BakeResult* alone = nullptr;
      if (aloneA.coverage.at(x, row, 0) > 0.99f) alone = &aloneA;
      if (aloneB.coverage.at(x, row, 0) > 0.99f) alone = &aloneB;
      if (!alone) continue;
      ASSERT_GT(together.coverage.at(x, row, 0), 0.99f);
      ++compared;
      const auto* a = together.normal.pixels<std::uint8_t>().data() + (std::size_t(row) * 128 + std::size_t(x)) * 3;
      const auto* b = alone->normal.pixels<std::uint8_t>().data() + (std::size_t(row) * 128 + std::size_t(x)) * 3;
      const auto* c = naive.normal.pixels<std::uint8_t>().data() + (std::size_t(row) * 128 + std::size_t(x)) * 3;
      differentNormal += std::memcmp(a, b, 3) != 0;
      differentHeight += together.map(bake::Map::Height).at(x, row, 0) != alone->map(bake::Map::Height).at(x, row, 0);
      differentAo += together.map(bake::Map::Ao).at(x, row, 0) != alone->map(bake::Map::Ao).at(x, row, 0);
      naiveDifferent += std::memcmp(a, c, 3) != 0;
    }
  }
  std::printf("groups: %d island texels compared, %d normal, %d height and %d AO texels differ from the groups baked "
              "alone; the naive bake's normal map differs at %d\n", compared, differentNormal, differentHeight, differentAo,
              naiveDifferent);
  EXPECT_GT(compared, 8000);
  EXPECT_EQ(differentNormal, 0);
  EXPECT_EQ(differentHeight, 0);
  EXPECT_EQ(differentAo, 0);
  EXPECT_GT(naiveDifferent, compared / 20);  // where the spheres interpenetrate rays hit the other part
}

TEST(BakeGroups, UnmatchedPartsAreReportedAndLowOnesLeftEmpty) {
  log::setLevel(log::Level::Error);
  const MeshParts lowA = part(inHalf(makeUvSphere(0.97f, 16, 8), 0.0f), "a_low");
  const MeshParts lowC = part(inHalf(moved(makeUvSphere(0.97f, 16, 8), vec3(3, 0, 0)), 0.5f), "c_low");
  const MeshParts low = combined({lowA, lowC});
  const MeshParts high = combined({part(makeUvSphere(1.0f, 32, 16), "a_high"), part(makeCube(0.5f), "d_high")});
  const bake::GroupMatch match = bake::matchGroups(low, high);
  ASSERT_EQ(match.groups.size(), 1u);
  EXPECT_EQ(match.unmatchedLow, std::vector<std::string>{"c_low"});
  EXPECT_EQ(match.unmatchedHigh, std::vector<std::string>{"d_high"});
  bake::BakeOptions options;
  options.width = options.height = 64;
  options.padding = 0;
  options.progress = false;
  const bake::BakeResult r = bake::bake(low, high, match, options);
  int right = 0;
  for (int row = 0; row < 64; ++row)
    for (int x = 34; x < 64; ++x) right += r.coverage.at(x, row, 0) > 0.0f;
  EXPECT_EQ(right, 0);  // c_low's half is not baked
  EXPECT_EQ(r.warnings.size() >= 2, true);
  // Names without the low suffix: one group, whatever the high parts are called.
  EXPECT_FALSE(bake::matchGroups(part(lowA.mesh, "a"), high).grouped());
  // Suffixes used but nothing pairs: an error naming the parts.
  EXPECT_THROW(bake::matchGroups(part(lowA.mesh, "x_low"), high), Error);
}

// Two materials on known triangles: every baked texel holds exactly one of the two
// colours, and texels whose centre is more than a texel from the border hold their side's.
TEST(BakeMaterialId, EveryTexelIsExactlyItsMaterialsColour) {
  log::setLevel(log::Level::Error);
  const Mesh low = makePlane(2.0f);
  MeshParts high = part(makeGrid(16, 16, 2.0f), "plane");
  high.materialNames = {"red_paint", "steel"};
  for (std::size_t t = 0; t < high.mesh.triangleCount(); ++t) {
    const float x = (high.mesh.positions[high.mesh.indices[3 * t]].x + high.mesh.positions[high.mesh.indices[3 * t + 1]].x +
                     high.mesh.positions[high.mesh.indices[3 * t + 2]].x) / 3.0f;
    high.triangleMaterial.push_back(x < 0.0f ? 0 : 1);
  }
  bake::BakeOptions options;
  options.width = options.height = 64;
  options.samples = 9;
  options.maps.add(bake::Map::MaterialId);
  options.progress = false;
  const bake::BakeResult r = bake::bake(part(low, "plane"), high, bake::GroupMatch{}, options);
  ASSERT_FALSE(r.map(bake::Map::MaterialId).empty());
  const Image map = r.map(bake::Map::MaterialId).converted(PixelType::U8);
  const vec3 red = bake::materialColor("red_paint"), steel = bake::materialColor("steel");
  EXPECT_NE(red, steel);
  EXPECT_EQ(bake::materialColor("steel"), steel);  // a function of the name
  // Hues from a hash are not spread by construction: only check that common names differ.
  const std::vector<std::string> names{"red", "blue", "", "steel", "red_paint", "rubber", "glass", "wood", "metal"};
  double closest = 1e9;
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t j = i + 1; j < names.size(); ++j)
      closest = std::min(closest, double(glm::length(255.0f * (bake::materialColor(names[i]) - bake::materialColor(names[j])))));
  std::printf("material ID: the closest two of %zu common names' colours are %.1f apart (8-bit RGB)\n", names.size(), closest);
  EXPECT_GT(closest, 0.0);
  const auto bytes = [](const vec3& c) { return glm::ivec3(glm::round(c * 255.0f)); };
  int exact = 0, sided = 0;
  for (int row = 0; row < 64; ++row) {
    for (int x = 0; x < 64; ++x) {
      const std::uint8_t* px = map.pixels<std::uint8_t>().data() + (std::size_t(row) * 64 + std::size_t(x)) * 3;
      const glm::ivec3 got(px[0], px[1], px[2]);
      ASSERT_TRUE(got == bytes(red) || got == bytes(steel)) << x << "," << row;
      ++exact;
      const auto s = surfaceAt(low, texelCentre(x, row, 64, 64));
      if (!s || std::fabs(s->position.x) < 2.0f * 2.0f / 64.0f) continue;
      EXPECT_EQ(got, bytes(s->position.x < 0.0f ? red : steel)) << x << "," << row;
      ++sided;
    }
  }
  std::printf("material ID: %d texels exactly one material's colour, %d of them away from the border on their side's\n",
              exact, sided);
  EXPECT_GT(sided, 3500);
  // Without materials: one colour, and a warning.
  const bake::BakeResult plain = bake::bake(low, high.mesh, options);
  EXPECT_EQ(plain.map(bake::Map::MaterialId).at(10, 10, 0), bake::materialColor("").r);
  EXPECT_FALSE(plain.warnings.empty());
}

// A high poly smaller than the low poly's island (an impostor card, a hole): texels on the
// island whose rays all missed are black, as the docs and the vertex colour map have it;
// dilation fills only the texels outside the island (it used to fill these too, up to
// --padding texels out from every hit: a halo of material colour around the silhouette).
TEST(BakeMaterialId, MissedTexelsOnTheIslandStayBlack) {
  log::setLevel(log::Level::Error);
  const Mesh low = makePlane(2.0f);  // x, z in [-1, 1], the whole map one island
  MeshParts high = part(makeGrid(8, 8, 1.0f), "plane");  // x, z in [-0.5, 0.5]
  high.materialNames = {"steel"};
  high.triangleMaterial.assign(high.mesh.triangleCount(), 0);
  high.colors.assign(high.mesh.positions.size(), vec4(1.0f, 0.5f, 0.25f, 1.0f));
  bake::BakeOptions options;
  options.width = options.height = 64;
  options.samples = 4;
  options.maps.add(bake::Map::MaterialId);
  options.maps.add(bake::Map::VertexColor);
  options.progress = false;  // padding: the default 16
  const bake::BakeResult r = bake::bake(part(low, "plane"), high, bake::GroupMatch{}, options);
  const Image map = r.map(bake::Map::MaterialId).converted(PixelType::U8);
  const vec3 steel = glm::round(bake::materialColor("steel") * 255.0f);
  int black = 0, coloured = 0;
  for (int row = 0; row < 64; ++row) {
    for (int x = 0; x < 64; ++x) {
      const auto s = surfaceAt(low, texelCentre(x, row, 64, 64));
      ASSERT_TRUE(s.has_value());
      const std::uint8_t* px = map.pixels<std::uint8_t>().data() + (std::size_t(row) * 64 + std::size_t(x)) * 3;
      const vec3 got(px[0], px[1], px[2]);
      const float margin = 2.0f * 2.0f / 64.0f;  // two texels either side of the high poly's edge
      const float out = std::max(std::fabs(s->position.x), std::fabs(s->position.z));
      if (out > 0.5f + margin) {
        EXPECT_EQ(got, vec3(0.0f)) << x << "," << row;
        EXPECT_EQ(r.map(bake::Map::VertexColor).at(x, row, 0), 0.0f) << x << "," << row;  // the two maps agree
        ++black;
      } else if (out < 0.5f - margin) {
        EXPECT_EQ(got, steel) << x << "," << row;
        ++coloured;
      }
    }
  }
  EXPECT_GT(black, 2500);
  EXPECT_GT(coloured, 700);
}

// A linear colour gradient over a plane: the map reproduces it within 8-bit quantization
// (interpolation is exact for a linear function, and so is the average of the samples).
TEST(BakeVertexColor, LinearGradientIsReproduced) {
  log::setLevel(log::Level::Error);
  const Mesh low = makePlane(2.0f);
  MeshParts high = part(makeGrid(12, 12, 2.0f), "plane");
  const auto colour = [](const vec3& p) { return vec4((p.x + 1.0f) * 0.5f, (p.z + 1.0f) * 0.5f, 0.25f, 1.0f); };
  for (const vec3& p : high.mesh.positions) high.colors.push_back(colour(p));
  bake::BakeOptions options;
  options.width = options.height = 48;
  options.samples = 4;
  options.maps.add(bake::Map::VertexColor);
  options.progress = false;
  const bake::BakeResult r = bake::bake(part(low, "plane"), high, bake::GroupMatch{}, options);
  ASSERT_FALSE(r.map(bake::Map::VertexColor).empty());
  const Image map = r.map(bake::Map::VertexColor).converted(PixelType::U8);
  double worst = 0.0;
  int n = 0;
  for (int row = 0; row < 48; ++row) {
    for (int x = 0; x < 48; ++x) {
      if (r.coverage.at(x, row, 0) < 0.99f) continue;
      const auto s = surfaceAt(low, texelCentre(x, row, 48, 48));
      if (!s) continue;
      const vec4 want = colour(s->position);
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(map.at(x, row, k) - double(want[k])));
      ++n;
    }
  }
  std::printf("vertex colour: %d texels, worst error %.5f (8-bit step %.5f)\n", n, worst, 1.0 / 255.0);
  EXPECT_GT(n, 2000);
  EXPECT_LE(worst, 0.5 / 255.0 + 1e-4);  // rounding to 8 bits, and float arithmetic
  // A high poly without colours: a one-line input error.
  EXPECT_THROW(bake::bake(low, high.mesh, options), Error);
}

TEST(MeshParts, ObjObjectsMaterialsAndColours) {
  const std::string path = ::testing::TempDir() + "parts_test.obj";
  {
    std::ofstream out(path);
    out << "o a_low\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nusemtl red\nf 1 2 3\n"
           "o b_low\nv 2 0 0 1 1 1\nv 3 0 0 1 1 1\nv 2 1 0 1 1 1\nusemtl blue\nf 4 5 6\n";
  }
  const MeshParts parts = loadMeshParts(path, {.joinVertices = false});
  EXPECT_EQ(parts.mesh.triangleCount(), 2u);
  EXPECT_EQ(parts.partNames, (std::vector<std::string>{"a_low", "b_low"}));
  ASSERT_EQ(parts.trianglePart.size(), 2u);
  EXPECT_NE(parts.trianglePart[0], parts.trianglePart[1]);
  ASSERT_TRUE(parts.hasMaterials());
  EXPECT_EQ(parts.materialNames[parts.triangleMaterial[0]], "red");
  EXPECT_EQ(parts.materialNames[parts.triangleMaterial[1]], "blue");
  ASSERT_TRUE(parts.hasColors());
  // The first triangle's corners carry red, green and blue (in some corner order).
  vec3 sum(0.0f);
  for (int k = 0; k < 3; ++k) sum += vec3(parts.colors[parts.mesh.indices[std::size_t(k)]]);
  EXPECT_EQ(sum, vec3(1.0f));
  std::remove(path.c_str());
}

TEST(MeshParts, ObjMaterialsFromAnMtlLibrary) {
  const std::string dir = ::testing::TempDir();
  {
    std::ofstream(dir + "parts_lib.mtl") << "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n";
    std::ofstream out(dir + "parts_lib.obj");
    out << "mtllib parts_lib.mtl\no a_high\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n"
           "o b_high\nusemtl blue\nv 2 0 0\nv 3 0 0\nv 2 1 0\nvn 0 0 1\nf 4//2 5//2 6//2\n";
  }
  const MeshParts parts = loadMeshParts(dir + "parts_lib.obj", {.joinVertices = false});
  for (std::size_t t = 0; t < parts.trianglePart.size(); ++t)
    std::printf("triangle %zu: part %s, material %s\n", t, parts.partNames[parts.trianglePart[t]].c_str(),
                parts.hasMaterials() && parts.triangleMaterial[t] != MeshParts::kNoMaterial
                    ? parts.materialNames[parts.triangleMaterial[t]].c_str() : "-");
  ASSERT_TRUE(parts.hasMaterials());
  EXPECT_EQ(parts.materialNames[parts.triangleMaterial[0]], "red");
  EXPECT_EQ(parts.materialNames[parts.triangleMaterial[1]], "blue");
}

TEST(MeshParts, PlyVertexColours) {
  const std::string path = ::testing::TempDir() + "parts_colours.ply";
  {
    std::ofstream out(path);
    out << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
           "property list uchar int vertex_indices\nend_header\n"
           "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 51\n3 0 1 2\n";
  }
  const MeshParts parts = loadMeshParts(path, {.joinVertices = false});
  ASSERT_TRUE(parts.hasColors());
  ASSERT_EQ(parts.mesh.triangleCount(), 1u);
  vec3 sum(0.0f);
  for (int k = 0; k < 3; ++k) sum += vec3(parts.colors[parts.mesh.indices[std::size_t(k)]]);
  EXPECT_NEAR(sum.r, 1.0f, 1e-6f);
  EXPECT_NEAR(sum.g, 1.0f, 1e-6f);
  EXPECT_NEAR(sum.b, 0.2f, 1e-6f);
  EXPECT_FALSE(parts.hasMaterials());
  std::remove(path.c_str());
}
