// Environment maps on the GPU (render/env) against independent CPU computations:
// equirect → cube faces vs CPU sampling of the equirect, dynamic cube faces vs analytic
// directions, mirror reflections vs ray-traced reflection directions, sphere maps vs
// their coverage analysis, and one-line errors for bad input.
#include "../support/gl_test.h"

#include "glint/core/error.h"
#include "glint/gl/render_target.h"
#include "glint/image/envmap.h"
#include "glint/render/env/dynamic_cube.h"
#include "glint/render/env/environment.h"
#include "glint/render/env/reflection.h"
#include "glint/render/state.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace glint;
namespace renv = glint::render::env;
namespace fs = std::filesystem;

namespace {
class EnvGl : public glint::testing::GlTest {};

fs::path outDir() {
  fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "render";
  fs::create_directories(dir);
  return dir;
}

// Face `face` of a cube map as an image indexed by GL row (row 0 = t ≈ 0).
Image readFace(const gl::Texture& cube, int face, int level = 0) {
  Image img = gl::readTexture(cube, level, face);
  img.flipVertical();  // readTexture returns row 0 = top; undo to index by GL row
  return img;
}

vec3 encodeDirection(vec3 d) { return 0.5f + 0.5f * glm::normalize(d); }

// Six solid faces, distinct colours: the expected colour of a direction is its face's.
const vec3 kFaceColors[6] = {{1, 0, 0}, {0, 1, 1}, {0, 1, 0}, {1, 0, 1}, {0, 0, 1}, {1, 1, 0}};
gl::Texture solidFaceCube(int size) {
  std::vector<Image> faces;
  for (int f = 0; f < 6; ++f) {
    Image img(size, size, 3);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        for (int c = 0; c < 3; ++c) img.set(x, y, c, kFaceColors[f][c]);
    faces.push_back(img);
  }
  gl::Texture cube = renv::cubeFromFaces(faces);
  // Level 0 only: the test is about directions; mip blending near silhouettes, where r
  // turns fast, would mix faces over a wide band.
  cube.filtering(GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
  return cube;
}

// A direction's margin from the nearest cube edge (0 on an edge): filtering blends faces there.
float edgeMargin(vec3 d) {
  vec3 a = glm::abs(d);
  float m = std::max({a.x, a.y, a.z});
  float second = a.x + a.y + a.z - m - std::min({a.x, a.y, a.z});
  return (m - second) / m;
}

template <typename F>
void expectMessage(F&& f, ErrorKind kind, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "no error thrown (expected one containing '" << part << "')";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), kind) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
  }
}
}  // namespace

TEST_F(EnvGl, EquirectToCubeMatchesCpuSamplingOfTheEquirect) {
  // A smooth random HDR panorama (values up to 4) so the tone curve is exercised.
  Image equirect(64, 32, 3, PixelType::F32);
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) equirect.set(x, y, c, u(rng));
  const int size = 16, samples = 2;
  const gl::Texture cube = renv::cubeFromEquirect(equirect, {.faceSize = size, .exposure = 0.8f, .samples = samples});
  EXPECT_EQ(cube.levels(), 5);  // 16, 8, 4, 2, 1: mipmapped
  double worst = 0;
  for (int f = 0; f < 6; ++f) {
    const Image face = readFace(cube, f);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        // The same supersampling the shader does, on the CPU.
        vec3 sum(0.0f);
        for (int j = 0; j < samples; ++j)
          for (int i = 0; i < samples; ++i) {
            const vec2 st = (vec2(x, y) + (vec2(i, j) + 0.5f) / float(samples)) / float(size);
            sum += sampleEquirect(equirect, cubeFaceDirection(f, st));
          }
        const vec3 expected = displayEncode(sum / float(samples * samples), 0.8f);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(face.at(x, y, c) - expected[c])));
      }
  }
  // 8-bit storage (±0.5/255) plus the GPU's filtering precision on a random texture.
  EXPECT_LT(worst, 4.0 / 255.0);
}

TEST_F(EnvGl, CubeFromFacesKeepsEachFaceWhereGlPutsIt) {
  // Each texel of each face encodes its own direction; a lookup along any direction
  // must find that direction's colour.
  const int size = 8;
  std::vector<Image> faces;
  for (int f = 0; f < 6; ++f) {
    Image img(size, size, 3);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const vec3 c = encodeDirection(cubeTexelDirection(f, x, y, size));  // row 0 uploaded first = t ≈ 0
        for (int k = 0; k < 3; ++k) img.set(x, y, k, c[k]);
      }
    faces.push_back(img);
  }
  const gl::Texture cube = renv::cubeFromFaces(faces);
  for (int f = 0; f < 6; ++f) {
    const Image face = readFace(cube, f);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        EXPECT_NEAR(face.at(x, y, 0), faces[std::size_t(f)].at(x, y, 0), 0.5 / 255.0);
  }
}

TEST_F(EnvGl, DynamicCubeFacesSeeTheirOwnDirections) {
  // Render a skybox whose colour encodes direction into a dynamic cube map through the
  // six face cameras; every texel must show the direction through its centre.
  const int size = 32;
  std::vector<Image> faces;
  for (int f = 0; f < 6; ++f) {
    Image img(64, 64, 3);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const vec3 c = encodeDirection(cubeTexelDirection(f, x, y, 64));
        for (int k = 0; k < 3; ++k) img.set(x, y, k, c[k]);
      }
    faces.push_back(img);
  }
  const gl::Texture source = renv::cubeFromFaces(faces);
  renv::Skybox sky;
  renv::DynamicCubeMap dynamic(size);
  dynamic.render(vec3(3.0f, -1.0f, 2.0f), [&](const glint::Camera& face) { sky.draw(source, face); });
  EXPECT_EQ(dynamic.texture().levels(), 6);
  double worst = 0;
  for (int f = 0; f < 6; ++f) {
    const Image face = readFace(dynamic.texture(), f);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const vec3 expected = encodeDirection(cubeTexelDirection(f, x, y, size));
        for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(face.at(x, y, c) - expected[c])));
      }
  }
  // Two 8-bit quantisations and bilinear interpolation of a smooth, curved function.
  EXPECT_LT(worst, 4.0 / 255.0);
}

namespace {
struct ReflectionCheck {
  int checked = 0;
  int matched = 0;
};

// Renders a mirror ball of radius 1 at the origin and compares each pixel with the face
// colour of the analytically reflected direction (ray/sphere intersection on the CPU).
ReflectionCheck checkMirrorBall(const renv::Reflector& mirror, const gl::Texture& environment, const mat3& sphereFrame,
                                float maxAngleFromViewer) {
  const ivec2 size{96, 96};
  const auto camera = glint::Camera::orbit(vec3(0.0f), 3.5f, 0.7f, 0.3f, 45.0f, 1.0f);
  render::GpuMesh ball(makeUvSphere(1.0f, 128, 64));
  gl::RenderTarget target(size);
  target.target().bind();
  render::PipelineState{.depthTest = true}.apply();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  mirror.draw(ball, mat4(1.0f), camera, environment, sphereFrame);
  const Image image = gl::readColor(target.framebuffer(), size);
  const mat4 invViewProj = glm::inverse(camera.viewProjection());
  ReflectionCheck result;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      const vec2 ndc{(float(x) + 0.5f) / float(size.x) * 2.0f - 1.0f, 1.0f - (float(y) + 0.5f) / float(size.y) * 2.0f};
      vec4 far = invViewProj * vec4(ndc, 1.0f, 1.0f);
      const vec3 dir = glm::normalize(vec3(far) / far.w - camera.position);
      const vec3 o = camera.position;
      const float b = glm::dot(o, dir), c = glm::dot(o, o) - 1.0f, disc = b * b - c;
      if (disc < 0.04f) continue;  // miss, or too close to the silhouette (tessellation)
      const vec3 n = glm::normalize(o + (-b - std::sqrt(disc)) * dir);
      const vec3 r = glm::reflect(dir, n);
      if (edgeMargin(r) < 0.08f) continue;  // filtering blends faces near cube edges
      const vec3 towardsViewer = glm::transpose(sphereFrame) * vec3(0, 0, 1);
      if (std::acos(glm::clamp(glm::dot(r, towardsViewer), -1.0f, 1.0f)) > maxAngleFromViewer) continue;
      const vec3 expected = kFaceColors[cubeLookup(r).face];
      ++result.checked;
      bool same = true;
      for (int k = 0; k < 3; ++k) same = same && std::abs(image.at(x, y, k) - expected[k]) < 3.0f / 255.0f;
      result.matched += same;
    }
  return result;
}
}  // namespace

TEST_F(EnvGl, CubeMapReflectionFollowsTheAnalyticReflectionVector) {
  const gl::Texture cube = solidFaceCube(32);
  for (bool perVertex : {false, true}) {
    renv::Reflector mirror({.lookup = renv::Lookup::CubeMap, .perVertex = perVertex});
    const ReflectionCheck r = checkMirrorBall(mirror, cube, mat3(1.0f), kPi);
    EXPECT_GT(r.checked, 3000);
    // Per pixel is exact; per vertex interpolates r across triangles, which can move a
    // face edge by a pixel.
    EXPECT_GE(double(r.matched) / r.checked, perVertex ? 0.99 : 0.999) << "perVertex " << perVertex;
  }
}

TEST_F(EnvGl, SphereMapReflectionFollowsItOutsideTheSingularRim) {
  const gl::Texture cube = solidFaceCube(32);
  const auto camera = glint::Camera::orbit(vec3(0.0f), 3.5f, 0.7f, 0.3f, 45.0f, 1.0f);
  gl::Texture sphereMap = renv::sphereMapFromCube(cube, {.size = 256, .worldToFrame = camera.rotation()});
  sphereMap.filtering(GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
  renv::Reflector mirror({.lookup = renv::Lookup::SphereMap});
  // Within 120° of the viewer the sphere map resolves the faces; beyond, the rim squeezes
  // whole faces into a few texels (tested as a figure in envmap_test).
  const ReflectionCheck r = checkMirrorBall(mirror, sphereMap, camera.rotation(), glm::radians(120.0f));
  EXPECT_GT(r.checked, 2000);
  EXPECT_GE(double(r.matched) / r.checked, 0.99);
}

TEST_F(EnvGl, SphereMapWastesExactlyTheTexelsOutsideTheBall) {
  const gl::Texture cube = solidFaceCube(16);
  for (int size : {64, 100}) {
    const gl::Texture map = renv::sphereMapFromCube(cube, {.size = size});
    const Image texels = gl::readTexture(map);
    std::size_t wasted = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) wasted += texels.at(x, y, 3) < 0.5f;
    const auto coverage = sphereMapCoverage(size);
    EXPECT_EQ(wasted, std::size_t(std::llround(coverage.wastedFraction * size * size))) << size;
    // The centre texel looks back at the viewer: +Z, the +Z face (blue).
    const int mid = size / 2;
    EXPECT_NEAR(texels.at(mid, mid, 2), 1.0f, 1.0f / 255.0f);
    EXPECT_NEAR(texels.at(mid, mid, 0), 0.0f, 1.0f / 255.0f);
  }
}

TEST_F(EnvGl, BadEnvironmentInputGivesOneLineErrors) {
  expectMessage([] { renv::findEnvironment("no-such-environment"); }, ErrorKind::Input, "scripts/setup");
  expectMessage([] { renv::loadEquirect(outDir() / "missing.exr"); }, ErrorKind::Input, "no such file");
  const fs::path corrupt = outDir() / "corrupt.exr";
  std::ofstream(corrupt, std::ios::binary) << "this is not an OpenEXR file";
  expectMessage([&] { renv::loadEquirect(corrupt); }, ErrorKind::Input, "corrupt.exr");
  const fs::path square = outDir() / "square.png";
  saveImage(Image(16, 16, 3), square);
  expectMessage([&] { renv::loadEquirect(square); }, ErrorKind::Input, "twice as wide");

  std::vector<Image> faces(6, Image(8, 8, 3));
  faces[3] = Image(8, 6, 3);
  expectMessage([&] { renv::cubeFromFaces(faces); }, ErrorKind::Input, "square");
  faces[3] = Image(16, 16, 3);
  expectMessage([&] { renv::cubeFromFaces(faces); }, ErrorKind::Input, "equal");
  const std::vector<fs::path> paths = {square, square, square, square, square, outDir() / "nz-missing.png"};
  expectMessage([&] { renv::loadCubeFaces(paths); }, ErrorKind::Input, "nz-missing.png");
}
