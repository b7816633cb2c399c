// One tangent space, proven (issue 6, item 6). A high poly is baked onto a low poly;
// the low poly is rendered with the baked map through render::bump::NormalMapping, the high
// poly with its own vertex normals, from the same views and lights; away from
// silhouettes the shading normals and the lit colours must agree.
//
// Two cases:
//   coincident  the high poly lies exactly on the low poly's facets (subdivided) and only
//               its normals carry detail: no parallax, so any disagreement is the tool and
//               the engine disagreeing about the tangent frame. Tight tolerance.
//   studded     a displaced torus over a smooth low poly: a realistic bake, where the two
//               renders also differ by parallax (the same pixel sees points up to the stud
//               height apart). Looser tolerance, stated below.
// A control renders the coincident case with the generator's analytic tangents instead
// of the baked mesh's MikkTSpace ones: it must fail the tight tolerance, so the test
// can tell a mismatched frame from a matched one.
#include "bake_test_util.h"
#include "support/gl_test.h"

#include "glint/bake/baker.h"
#include "glint/bake/samples.h"
#include "glint/core/log.h"
#include "glint/gl/render_target.h"
#include "glint/render/bump/textures.h"
#include "glint/render/bump/normal_mapping.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <vector>

using namespace glint;
using glint::testing::GlTest;

namespace {

constexpr int kSize = 256;

struct Agreement {
  double meanAngle = 0, p99Angle = 0, meanShade = 0, p99Shade = 0;
  std::size_t pixels = 0;
};

/// Per-pixel normals (float) and lit colours of one mesh from one view.
struct Frame {
  Image normals;  // RGBA F32, (n + 1) / 2, alpha 1 where drawn
  Image lit;      // RGBA F32
};

Frame renderFrame(const render::GpuMesh& mesh, const glint::Camera& camera, render::bump::ShadingNormal source,
                  const gl::Texture* map) {
  static const render::bump::DirectionalLight lights[] = {
      {.direction = {0.6f, 0.8f, 0.3f}, .color = vec3(0.8f)},
      {.direction = {-0.7f, 0.2f, 0.5f}, .color = vec3(0.35f, 0.3f, 0.25f)},
  };
  Frame frame;
  for (const auto output : {render::bump::NormalMappingOutput::WorldNormal, render::bump::NormalMappingOutput::Lit}) {
    const render::bump::NormalMapping technique({.normal = source, .output = output});
    gl::RenderTarget target({kSize, kSize}, GL_RGBA32F, "roundtrip");
    target.target().bind();
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    technique.draw(mesh, mat4(1.0f), camera, lights, {.specular = 0.3f}, map);
    (output == render::bump::NormalMappingOutput::Lit ? frame.lit : frame.normals) =
        gl::readTexture(target.color(), 0, 0, 4, PixelType::F32);
  }
  return frame;
}

/// Compares two frames on pixels both cover, at least `margin` pixels from any uncovered one,
/// where the reference (b) faces the viewer at least `minFacing` (cosine; roughly: the
/// view direction is taken from the eye to the origin).
Agreement compare(const Frame& a, const Frame& b, int margin, const vec3& toEye, double minFacing) {
  std::vector<double> angles, shades;
  for (int y = margin; y < kSize - margin; ++y) {
    for (int x = margin; x < kSize - margin; ++x) {
      bool interior = true;
      for (int dy = -margin; dy <= margin && interior; ++dy)
        for (int dx = -margin; dx <= margin && interior; ++dx)
          interior = a.normals.at(x + dx, y + dy, 3) > 0.5f && b.normals.at(x + dx, y + dy, 3) > 0.5f;
      if (!interior) continue;
      const glm::dvec3 na = glm::dvec3(bake_test::texel(a.normals, x, y)) * 2.0 - 1.0;
      const glm::dvec3 nb = glm::dvec3(bake_test::texel(b.normals, x, y)) * 2.0 - 1.0;
      if (glm::dot(glm::normalize(nb), glm::dvec3(toEye)) < minFacing) continue;
      angles.push_back(bake_test::angleDeg(na, nb));
      double shade = 0;
      for (int c = 0; c < 3; ++c) shade = std::max(shade, double(std::abs(a.lit.at(x, y, c) - b.lit.at(x, y, c))));
      shades.push_back(shade);
    }
  }
  Agreement r;
  r.pixels = angles.size();
  for (std::size_t i = 0; i < angles.size(); ++i) {
    r.meanAngle += angles[i] / double(angles.size());
    r.meanShade += shades[i] / double(shades.size());
  }
  r.p99Angle = bake_test::percentile(angles, 0.99);
  r.p99Shade = bake_test::percentile(shades, 0.99);
  return r;
}

/// Bakes high onto low, renders both from three views; returns the worst view's numbers.
Agreement roundTrip(const Mesh& low, const Mesh& high, const bake::BakeOptions& options, const char* label,
                    double minFacing, const Mesh* renderLowInstead = nullptr) {
  const bake::BakeResult baked = bake::bake(low, high, options);
  const gl::Texture map = render::bump::uploadImage(baked.normal, {.label = "baked-normals"});
  const render::GpuMesh lowMesh(renderLowInstead ? *renderLowInstead : baked.low, {}, "low");
  const render::GpuMesh highMesh(high, {}, "high");
  Agreement worst;
  for (float azimuth : {0.3f, 2.4f, 4.4f}) {
    const auto camera = glint::Camera::orbit(vec3(0.0f), 3.2f, azimuth, 0.6f, 40.0f, 1.0f);
    const Frame withMap = renderFrame(lowMesh, camera, render::bump::ShadingNormal::TangentMap, &map);
    const Frame reference = renderFrame(highMesh, camera, render::bump::ShadingNormal::Vertex, nullptr);
    const Agreement a = compare(withMap, reference, 2, glm::normalize(camera.position), minFacing);
    // For eyes: low poly with the map | high poly, lit (test-output/bake-roundtrip/).
    const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "bake-roundtrip";
    std::filesystem::create_directories(dir);
    Image pair(2 * kSize, kSize, 4, PixelType::F32);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int c = 0; c < 4; ++c) {
          pair.set(x, y, c, c == 3 ? 1.0f : withMap.lit.at(x, y, c));
          pair.set(x + kSize, y, c, c == 3 ? 1.0f : reference.lit.at(x, y, c));
        }
    saveImage(pair.converted(PixelType::U8), dir / fmt::format("{}-{:.1f}.png", label, azimuth));
    Image err(kSize, kSize, 1, PixelType::F32);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        if (withMap.normals.at(x, y, 3) < 0.5f || reference.normals.at(x, y, 3) < 0.5f) continue;
        const glm::dvec3 na = glm::dvec3(bake_test::texel(withMap.normals, x, y)) * 2.0 - 1.0;
        const glm::dvec3 nb = glm::dvec3(bake_test::texel(reference.normals, x, y)) * 2.0 - 1.0;
        err.set(x, y, 0, float(bake_test::angleDeg(na, nb) / 20.0));
      }
    saveImage(err.converted(PixelType::U8), dir / fmt::format("{}-{:.1f}-error.png", label, azimuth));
    std::printf("%s, azimuth %.1f: %zu pixels, normal angle mean %.3f° p99 %.3f°, colour mean %.4f p99 %.4f\n", label,
                azimuth, a.pixels, a.meanAngle, a.p99Angle, a.meanShade, a.p99Shade);
    EXPECT_GT(a.pixels, 5000u);
    if (a.meanAngle > worst.meanAngle) worst.meanAngle = a.meanAngle;
    if (a.p99Angle > worst.p99Angle) worst.p99Angle = a.p99Angle;
    if (a.meanShade > worst.meanShade) worst.meanShade = a.meanShade;
    if (a.p99Shade > worst.p99Shade) worst.p99Shade = a.p99Shade;
  }
  return worst;
}

/// The coincident case: the low torus subdivided onto its own facets, with normals bent by
/// a smooth pattern (what a high poly's detail looks like to the shading).
Mesh coincidentHighPoly(const Mesh& low) {
  Mesh high = bake::subdivideFlat(low, 12);
  for (std::size_t i = 0; i < high.vertexCount(); ++i) {
    const vec3 p = high.positions[i];
    const vec3 bend(std::sin(9.0f * p.y + 3.0f * p.x), std::sin(7.0f * p.z), std::cos(8.0f * p.x - 2.0f * p.z));
    high.normals[i] = glm::normalize(high.normals[i] + 0.35f * bend);
  }
  return high;
}

/// The mesh unwelded, each corner with its triangle's own tangent (dP/du made orthogonal
/// to the corner's normal) instead of MikkTSpace's vertex average.
Mesh perFaceTangents(const Mesh& mesh) {
  Mesh out;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t* v = &mesh.indices[3 * t];
    const vec3 e1 = mesh.positions[v[1]] - mesh.positions[v[0]], e2 = mesh.positions[v[2]] - mesh.positions[v[0]];
    const vec2 a = mesh.uvs[v[1]] - mesh.uvs[v[0]], b = mesh.uvs[v[2]] - mesh.uvs[v[0]];
    const float det = a.x * b.y - a.y * b.x;
    const vec3 dpdu = (e1 * b.y - e2 * a.y) / det;
    for (int k = 0; k < 3; ++k) {
      const vec3 n = mesh.normals[v[k]];
      out.positions.push_back(mesh.positions[v[k]]);
      out.normals.push_back(n);
      out.uvs.push_back(mesh.uvs[v[k]]);
      out.tangents.emplace_back(glm::normalize(dpdu - glm::dot(dpdu, n) * n), det < 0.0f ? -1.0f : 1.0f);
      out.indices.push_back(std::uint32_t(out.indices.size()));
    }
  }
  return out;
}

}  // namespace

TEST_F(GlTest, BakedMapReproducesTheHighPolyShading) {
  log::setLevel(log::Level::Error);
  const Mesh low = makeTorus(1.0f, 0.35f, 24, 12);
  bake::BakeOptions options;
  options.width = options.height = 1024;
  options.samples = 1;

  // Tolerance (coincident): the map is 8-bit (±0.2° per channel step), bilinearly filtered
  // between texels whose normals differ, and the high poly's normals are interpolated over
  // its own small triangles — a few tenths of a degree, nothing like the several degrees a
  // different tangent frame causes.
  const Mesh high = coincidentHighPoly(low);
  const Agreement exact = roundTrip(low, high, options, "coincident", -1.0);
  EXPECT_LT(exact.meanAngle, 0.25);
  EXPECT_LT(exact.p99Angle, 1.5);
  EXPECT_LT(exact.meanShade, 0.004);
  EXPECT_LT(exact.p99Shade, 0.02);

  // Control: the same map rendered with per-triangle tangents (each face's own dP/du, the
  // way a naive engine computes them) must disagree visibly: the test sees a mismatch.
  const Mesh naive = perFaceTangents(bake::bake(low, high, {.width = 16, .height = 16}).low);
  const Agreement control = roundTrip(low, high, options, "control", -1.0, &naive);
  EXPECT_GT(control.meanAngle, 3.0 * exact.meanAngle);
  EXPECT_GT(control.p99Angle, 2.0 * exact.p99Angle);
}

TEST_F(GlTest, StuddedTorusRoundTrip) {
  log::setLevel(log::Level::Error);
  const Mesh low = makeTorus(1.0f, 0.35f, 48, 24);
  const Mesh high = bake::makeStuddedTorus({.segments = 384, .sides = 192, .studHeight = 0.01f, .grooveDepth = 0.005f});
  bake::BakeOptions options;
  options.width = options.height = 1024;
  options.samples = 4;
  // Tolerance (studded): the low and high surfaces are up to ~0.013 apart (studs 0.01,
  // facets 0.003), so a pixel sees high-poly points up to ~0.013·tan(view angle) away from
  // where the bake sampled. On the studs' slopes that moves the normal by a few degrees;
  // on average it stays under a degree. Pixels seen at more than 60° are left out: there
  // the parallax of any normal map grows without bound (tan θ).
  const Agreement a = roundTrip(low, high, options, "studded", 0.5);
  EXPECT_LT(a.meanAngle, 1.0);
  EXPECT_LT(a.p99Angle, 6.0);
  EXPECT_LT(a.meanShade, 0.006);
  EXPECT_LT(a.p99Shade, 0.05);
}
