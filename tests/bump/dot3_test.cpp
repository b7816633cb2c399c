// DOT3 arithmetic (image/dot3.h) against the OpenGL spec's formula and plain vector maths.
#include "glint/image/dot3.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace glint;

TEST(Dot3, SpecFormulaByHand) {
  // GL_DOT3_RGB = 4·Σ(a − ½)(b − ½), clamped to [0, 1].
  EXPECT_FLOAT_EQ(combineDot3Rgb({1.0f, 0.5f, 0.5f}, {1.0f, 0.5f, 0.5f}), 1.0f);        // 4·(½·½)
  EXPECT_FLOAT_EQ(combineDot3Rgb({0.75f, 0.5f, 0.5f}, {0.75f, 0.5f, 0.5f}), 0.25f);     // 4·(¼·¼)
  EXPECT_FLOAT_EQ(combineDot3Rgb({0.75f, 0.75f, 0.5f}, {0.75f, 0.75f, 1.0f}), 0.5f);    // 4·(1/16 + 1/16)
  EXPECT_FLOAT_EQ(combineDot3Rgb({1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}), 1.0f);        // 3 clamps to 1
  EXPECT_FLOAT_EQ(combineDot3Rgb({0.0f, 0.5f, 0.5f}, {1.0f, 0.5f, 0.5f}), 0.0f);        // −1 clamps to 0
  EXPECT_FLOAT_EQ(combineDot3Rgb({0.5f, 0.5f, 0.5f}, {0.2f, 0.9f, 0.1f}), 0.0f);        // zero vector
}

TEST(Dot3, EncodedVectorsGiveTheirDotProduct) {
  // (l + 1)/2 and (n + 1)/2 in bytes: 4·Σ(l/2)(n/2) = l·n up to the byte quantization
  // (each component off by ≤ 1/255 in [−1, 1]: |error| ≤ Σ|l_i|/255 + Σ|n_i|/255 ≤ 2√3/255).
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  for (int i = 0; i < 2000; ++i) {
    const vec3 l = glm::normalize(vec3(g(rng), g(rng), g(rng)));
    const vec3 n = glm::normalize(vec3(g(rng), g(rng), std::abs(g(rng))));
    const vec3 a = vec3(encodeLightVector(l)) / 255.0f, b = vec3(encodeLightVector(n)) / 255.0f;
    EXPECT_NEAR(combineDot3Rgb(a, b), std::clamp(glm::dot(l, n), 0.0f, 1.0f), 2.0f * std::sqrt(3.0f) / 255.0f);
  }
}

TEST(Dot3, ByteEncodingOfTheSeed) {
  // "a −1 vector component will map to 0, and a +1 vector component will map to 255"
  EXPECT_EQ(encodeLightVector({-1.0f, 1.0f, 0.0f}), u8vec3(0, 255, 128));
  EXPECT_EQ(encodeLightVector({-3.0f, 2.0f, 0.5f}), u8vec3(0, 255, 191));  // clamped; 0.75·255 = 191.25
  const vec3 v = decodeLightVector({0, 255, 128});
  EXPECT_FLOAT_EQ(v.x, -1.0f);
  EXPECT_FLOAT_EQ(v.y, 1.0f);
  EXPECT_NEAR(v.z, 1.0f / 255, 1e-6f);  // 128/255·2 − 1: zero is not representable in bytes
}

TEST(Dot3, LightIsRotatedByTheInversePolygonRotation) {
  // The polygon lies in its local XY plane (normal +Z). Turned −90° about X, its normal
  // faces world +Y: a light straight above it is straight "up" in local space.
  const quat lying = glm::angleAxis(glm::radians(-90.0f), vec3(1, 0, 0));
  const vec3 l = localLightVector(lying, vec3(0, 1, 0), vec3(0), vec3(0, 6, 0));
  EXPECT_NEAR(l.x, 0.0f, 1e-6f);
  EXPECT_NEAR(l.y, 0.0f, 1e-6f);
  EXPECT_NEAR(l.z, 1.0f, 1e-6f);
  // A light towards world −Z from a vertex is towards local +Y (rotating +Y by −90° about X gives −Z).
  const vec3 m = localLightVector(lying, vec3(0), vec3(0), vec3(0, 0, -3));
  EXPECT_NEAR(m.y, 1.0f, 1e-6f);
  // Identity with an arbitrary rotation: rotating the local vector forward gives the world direction.
  const quat q = glm::normalize(quat(0.3f, -0.4f, 0.8f, 0.2f));
  const vec3 vertex{0.3f, -0.7f, 0.0f}, light{2.0f, 3.0f, -1.0f}, t{0.5f, 0.1f, -2.0f};
  const vec3 local = localLightVector(q, t, vertex, light);
  const vec3 world = glm::normalize(light - (q * vertex + t));
  EXPECT_NEAR(glm::length(q * local - world), 0.0f, 1e-5f);
  EXPECT_EQ(localLightVector(q, t, vertex, q * vertex + t), vec3(0, 0, 1));  // light at the vertex
}
