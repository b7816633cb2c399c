// The motion-blur ball's mesh and the CPU side of its vertex shader (motion_blur.h).
#include "glint/pipedream/motion_blur.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cmath>

namespace glint::pipedream {

BlurBallMesh buildBlurBall(int segments, int rings) {
  if (segments < 3 || rings < 2 || rings % 2 != 0)
    fail(ErrorKind::Usage, "a blur ball needs at least 3 segments and an even ring count of at least 2, got {} and {}",
         segments, rings);
  BlurBallMesh m;
  const int half = rings / 2;
  // Ring k runs from the south pole (k = 0, z = −1) to the north pole (k = rings, z = +1);
  // the equator k = half is there twice: once for each half.
  const auto ringPoint = [&](int k, int s) {
    const float theta = kPi * float(k) / float(rings);  // from the south pole
    const float phi = 2.0f * kPi * float(s % segments) / float(segments);
    const float z = k == 0 ? -1.0f : k == rings ? 1.0f : k == half ? 0.0f : -std::cos(theta);
    const float r = (k == 0 || k == rings) ? 0.0f : k == half ? 1.0f : std::sin(theta);
    return vec3(r * std::cos(phi), r * std::sin(phi), z);
  };
  // Vertex tables: rear half rings 0..half, front half rings half..rings. Poles are one vertex.
  std::vector<std::vector<std::uint32_t>> rearRing(std::size_t(half + 1)), frontRing(std::size_t(half + 1));
  const auto add = [&](vec3 p, float rear) {
    m.positions.push_back(p);
    m.rear.push_back(rear);
    return std::uint32_t(m.positions.size() - 1);
  };
  for (int k = 0; k <= half; ++k) {
    const int n = (k == 0) ? 1 : segments;
    for (int s = 0; s < n; ++s) rearRing[std::size_t(k)].push_back(add(ringPoint(k, s), 1.0f));
  }
  for (int k = half; k <= rings; ++k) {
    const int n = (k == rings) ? 1 : segments;
    for (int s = 0; s < n; ++s) frontRing[std::size_t(k - half)].push_back(add(ringPoint(k, s), 0.0f));
  }
  const auto at = [&](const std::vector<std::vector<std::uint32_t>>& table, int k, int s) {
    const auto& ring = table[std::size_t(k)];
    return ring.size() == 1 ? ring[0] : ring[std::size_t(s % segments)];
  };
  // Bands between consecutive rings; seen from outside, increasing s turns counter-clockwise
  // about +z and increasing k goes north, so (k,s) (k,s+1) (k+1,s+1) (k+1,s) is counter-
  // clockwise. Triangles touching a pole lose their collapsed corner.
  const auto band = [&](const std::vector<std::vector<std::uint32_t>>& table, int k) {
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = at(table, k, s), b = at(table, k, s + 1), c = at(table, k + 1, s + 1), d = at(table, k + 1, s);
      if (a != b) m.indices.insert(m.indices.end(), {a, b, c});
      if (c != d) m.indices.insert(m.indices.end(), {a, c, d});
    }
  };
  for (int k = 0; k < half; ++k) band(rearRing, k);
  for (int k = 0; k < half; ++k) band(frontRing, k);
  // The seam: the rear half's equator (below, once stretched) to the front half's.
  const std::size_t before = m.indices.size();
  for (int s = 0; s < segments; ++s) {
    const std::uint32_t a = at(rearRing, half, s), b = at(rearRing, half, s + 1), c = at(frontRing, 0, s + 1),
                        d = at(frontRing, 0, s);
    m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
  }
  m.seamTriangles = (m.indices.size() - before) / 3;
  return m;
}

BallBlur blurOf(vec3 velocity, float radius, float shutter, float minOpacity, float lodScale) {
  BallBlur b;
  b.stretch = glm::length(velocity) * shutter;
  const float diameter = 2.0f * radius;
  b.opacity = std::max(minOpacity, diameter / (diameter + b.stretch));
  b.lodBias = std::log2(1.0f + b.stretch / diameter) * lodScale;
  return b;
}

mat3 ballFrame(vec3 velocity) {
  const float speed = glm::length(velocity);
  if (speed < 1e-6f) return mat3(1.0f);
  const vec3 z = velocity / speed;
  const vec3 helper = std::abs(z.y) < 0.9f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
  const vec3 x = glm::normalize(glm::cross(helper, z));
  const vec3 y = glm::cross(z, x);
  return mat3(x, y, z);
}

vec3 stretchVertex(vec3 position, float rear, vec3 centre, vec3 velocity, float radius, float shutter) {
  return centre + ballFrame(velocity) * (radius * position) - rear * shutter * velocity;
}

}  // namespace glint::pipedream
