// Environment-map geometry (image/envmap.h) against the OpenGL spec's cube map table,
// the GL_SPHERE_MAP texgen formula and the WWDC 2001 talk's figures ("about 20%" wasted,
// "roughly 40%" for each half of the environment).
#include "glint/core/error.h"
#include "glint/image/envmap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace glint;

namespace {
void expectNear(vec3 a, vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}
}  // namespace

TEST(CubeMap, FaceCentresAndCornersFollowTheSpecTable) {
  const vec3 centres[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < kCubeFaces; ++f) expectNear(cubeFaceDirection(f, {0.5f, 0.5f}), centres[f]);
  // +X: sc = −rz, tc = −ry, so s = 0 looks towards +Z and t = 0 towards +Y.
  expectNear(cubeFaceDirection(0, {0.0f, 0.5f}), {1, 0, 1});
  expectNear(cubeFaceDirection(0, {0.5f, 0.0f}), {1, 1, 0});
  // +Y: sc = rx, tc = rz; −Z: sc = −rx.
  expectNear(cubeFaceDirection(2, {1.0f, 1.0f}), {1, 1, 1});
  expectNear(cubeFaceDirection(5, {0.0f, 0.5f}), {1, 0, -1});
}

TEST(CubeMap, LookupInvertsFaceDirections) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.01f, 0.99f);
  for (int f = 0; f < kCubeFaces; ++f)
    for (int i = 0; i < 200; ++i) {
      const vec2 st{u(rng), u(rng)};
      const CubeCoord c = cubeLookup(3.7f * cubeFaceDirection(f, st));  // length does not matter
      EXPECT_EQ(c.face, f);
      EXPECT_NEAR(c.st.x, st.x, 1e-5f);
      EXPECT_NEAR(c.st.y, st.y, 1e-5f);
    }
  expectNear(cubeTexelDirection(4, 0, 0, 2), {-0.5f, 0.5f, 1.0f});
}

TEST(Equirect, AxesLandWhereTheConventionSays) {
  EXPECT_NEAR(equirectUv({0, 0, -1}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(equirectUv({0, 0, -1}).y, 0.5f, 1e-6f);
  EXPECT_NEAR(equirectUv({1, 0, 0}).x, 0.75f, 1e-6f);
  EXPECT_NEAR(equirectUv({-1, 0, 0}).x, 0.25f, 1e-6f);
  EXPECT_NEAR(equirectUv({0, 1, 0}).y, 0.0f, 1e-6f);
  EXPECT_NEAR(equirectUv({0, -2, 0}).y, 1.0f, 1e-6f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.01f, 0.99f);
  for (int i = 0; i < 500; ++i) {
    const vec2 uv{u(rng), u(rng)};
    const vec2 back = equirectUv(equirectDirection(uv));
    EXPECT_NEAR(back.x, uv.x, 1e-5f);
    EXPECT_NEAR(back.y, uv.y, 1e-5f);
  }
}

TEST(Equirect, BilinearSamplingHitsTexelCentresAndWraps) {
  Image img(8, 4, 3, PixelType::F32);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) img.set(x, y, 0, float(10 * y + x));
  // The centre of texel (3, 1).
  const vec3 d = equirectDirection({3.5f / 8.0f, 1.5f / 4.0f});
  EXPECT_NEAR(sampleEquirect(img, d).x, 13.0f, 1e-3f);
  // Half-way between the last and the first column: the horizon wraps around.
  const vec3 seam = equirectDirection({0.0f, 1.5f / 4.0f});
  EXPECT_NEAR(sampleEquirect(img, seam).x, 0.5f * (17.0f + 10.0f), 1e-3f);
}

TEST(DisplayEncode, IsMonotoneFromBlackToWhite) {
  EXPECT_NEAR(displayEncode(vec3(0.0f)).x, 0.0f, 1e-3f);
  EXPECT_GT(displayEncode(vec3(100.0f)).x, 0.99f);
  float previous = -1.0f;
  for (float v = 0.0f; v < 20.0f; v += 0.05f) {
    const float e = displayEncode(vec3(v)).x;
    EXPECT_GE(e, previous);
    previous = e;
  }
  // Exposure scales radiance before the curve.
  EXPECT_NEAR(displayEncode(vec3(0.5f), 2.0f).y, displayEncode(vec3(1.0f)).y, 1e-6f);
}

TEST(SphereMap, TexgenFormulaAndItsInverseAgree) {
  // Facing the viewer: the centre. Perpendicular (90°): radius sin 45° = 0.707.
  EXPECT_NEAR(sphereMapUv({0, 0, 1}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(sphereMapUv({1, 0, 0}).x, 0.5f + 0.5f * std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(sphereMapUv({0, 1, 0}).y, 0.5f + 0.5f * std::sqrt(0.5f), 1e-6f);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    const vec2 st{u(rng), u(rng)};
    bool inside = false;
    const vec3 r = sphereMapDirection(st, &inside);
    if (!inside) continue;
    EXPECT_NEAR(glm::length(r), 1.0f, 1e-5f);
    if (r.z < -0.999f) continue;  // next to the singular rim the inverse is ill-conditioned
    const vec2 back = sphereMapUv(r);
    EXPECT_NEAR(back.x, st.x, 2e-4f);
    EXPECT_NEAR(back.y, st.y, 2e-4f);
  }
}

TEST(SphereMap, WastesAboutAFifthAndSplitsTheRestEvenly) {
  const SphereMapCoverage c = sphereMapCoverage(512);
  EXPECT_NEAR(c.wastedFraction, 1.0 - M_PI / 4.0, 2e-3);  // the WWDC 2001 talk: "about 20%"
  EXPECT_NEAR(c.frontFraction, M_PI / 8.0, 2e-3);         // "roughly 40%" front
  EXPECT_NEAR(c.backFraction, M_PI / 8.0, 2e-3);          // and 40% back
  EXPECT_NEAR(c.wastedFraction + c.frontFraction + c.backFraction, 1.0, 1e-12);
}

TEST(SphereMap, ResolutionMatchesTheMappingsDerivative) {
  // Numerically differentiate (s, t) along the great circle in the XZ plane and
  // around the view axis, and compare with the closed forms.
  const int size = 512;
  for (double theta : {0.2, 0.8, M_PI / 2, 2.5, 3.0}) {
    const double h = 5e-3;  // float (s, t): a larger step keeps rounding out of the quotient
    auto at = [](double t, double phi) {
      return sphereMapUv(vec3(float(std::sin(t) * std::cos(phi)), float(std::sin(t) * std::sin(phi)), float(std::cos(t))));
    };
    const double radial = double(glm::length(at(theta + h, 0.3) - at(theta - h, 0.3))) / (2 * h) * size;
    const double tangential =
        double(glm::length(at(theta, 0.3 + h) - at(theta, 0.3 - h))) / (2 * h * std::sin(theta)) * size;
    const AngularResolution r = sphereMapResolution(size, theta);
    EXPECT_NEAR(radial / r.radial, 1.0, 5e-3) << "theta " << theta;
    EXPECT_NEAR(tangential / r.tangential, 1.0, 5e-3) << "theta " << theta;
  }
  EXPECT_NEAR(sphereMapResolution(size, M_PI).radial, 0.0, 1e-9);  // the back-side singularity
  // A 512² sphere map matches a 256² cube map only straight ahead.
  EXPECT_NEAR(sphereMapResolution(512, 0.0).radial, cubeMapResolution(256), 1e-9);
  EXPECT_NEAR(equivalentCubeFaceSize(512, M_PI / 2), 512 * std::cos(M_PI / 4) / 2, 1e-9);
}

TEST(Validation, RejectsBadEquirectsAndCubeFacesWithOneLine) {
  EXPECT_NO_THROW(validateEquirect(Image(8, 4, 3, PixelType::F32), "ok.exr"));
  try {
    validateEquirect(Image(9, 4, 3, PixelType::F32), "wide.exr");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("twice as wide"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  Image nan(8, 4, 3, PixelType::F32);
  nan.set(1, 1, 1, NAN);
  EXPECT_THROW(validateEquirect(nan, "nan.exr"), Error);
  EXPECT_THROW(validateEquirect(Image(8, 4, 1), "gray.png"), Error);

  std::vector<Image> faces(6, Image(16, 16, 3));
  const std::vector<std::string> names = {"px.png", "nx.png", "py.png", "ny.png", "pz.png", "nz.png"};
  EXPECT_NO_THROW(validateCubeFaces(faces, names));
  faces[2] = Image(16, 12, 3);
  try {
    validateCubeFaces(faces, names);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("py.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("square"), std::string::npos) << e.what();
  }
  faces[2] = Image(32, 32, 3);
  try {
    validateCubeFaces(faces, names);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("equal"), std::string::npos) << e.what();
  }
  faces.pop_back();
  EXPECT_THROW(validateCubeFaces(faces, names), Error);
}
