#pragma once
// Independent helpers for the baker tests: find the low-poly surface point under a
// texel centre by brute force, decode a tangent-space texel with the MikkTSpace
// per-pixel rule written out by hand, and find where a ray meets an analytic surface
// (signed distance function) by bracketing and bisection — nothing shared with the
// baker's own code paths except the mesh it baked.
#include "glint/bake/baker.h"
#include "glint/mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace bake_test {

using namespace glint;

struct SurfacePoint {
  vec3 position;
  vec3 normal;   ///< interpolated, not normalized
  vec4 tangent;  ///< interpolated, not normalized
};

/// The low-poly surface point whose UV is `uv`, or nothing outside the islands.
inline std::optional<SurfacePoint> surfaceAt(const Mesh& low, vec2 uv) {
  for (std::size_t t = 0; t < low.triangleCount(); ++t) {
    const std::uint32_t i0 = low.indices[3 * t], i1 = low.indices[3 * t + 1], i2 = low.indices[3 * t + 2];
    const glm::dvec2 a(low.uvs[i0]), b(low.uvs[i1]), c(low.uvs[i2]), p(uv);
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (std::abs(area) < 1e-14) continue;
    const double w1 = ((p.x - a.x) * (c.y - a.y) - (p.y - a.y) * (c.x - a.x)) / area;
    const double w2 = ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / area;
    const double w0 = 1.0 - w1 - w2;
    if (w0 < 0 || w1 < 0 || w2 < 0) continue;
    SurfacePoint s;
    s.position = vec3(w0 * glm::dvec3(low.positions[i0]) + w1 * glm::dvec3(low.positions[i1]) + w2 * glm::dvec3(low.positions[i2]));
    s.normal = vec3(w0 * glm::dvec3(low.normals[i0]) + w1 * glm::dvec3(low.normals[i1]) + w2 * glm::dvec3(low.normals[i2]));
    if (low.hasTangents()) {
      s.tangent = vec4(w0 * glm::dvec4(low.tangents[i0]) + w1 * glm::dvec4(low.tangents[i1]) + w2 * glm::dvec4(low.tangents[i2]));
    }
    return s;
  }
  return std::nullopt;
}

/// UV of the centre of texel (x, row) in an image whose row 0 is v = 1.
inline vec2 texelCentre(int x, int row, int width, int height) {
  return {(float(x) + 0.5f) / float(width), 1.0f - (float(row) + 0.5f) / float(height)};
}

inline vec3 texel(const Image& image, int x, int row) {
  return {image.at(x, row, 0), image.at(x, row, 1), image.at(x, row, 2)};
}

/// MikkTSpace per-pixel decode: normalize(m.x T + m.y B + m.z N), B = sign·cross(N, T).
inline vec3 decodeTangentSpace(const vec3& rgb, const SurfacePoint& s) {
  const glm::dvec3 m = glm::dvec3(rgb) * 2.0 - 1.0;
  const glm::dvec3 n(s.normal), t(s.tangent);
  const glm::dvec3 b = (s.tangent.w < 0 ? -1.0 : 1.0) * glm::cross(n, t);
  return vec3(glm::normalize(m.x * t + m.y * b + m.z * n));
}

/// Smallest-|t| root of sdf(origin + t·dir) on [-rear, front], or nothing.
inline std::optional<double> rayRoot(const std::function<double(const glm::dvec3&)>& sdf, const glm::dvec3& origin,
                                     const glm::dvec3& dir, double rear, double front) {
  const int steps = 2000;
  std::optional<double> best;
  const auto f = [&](double t) { return sdf(origin + t * dir); };
  double t0 = -rear, f0 = f(t0);
  for (int i = 1; i <= steps; ++i) {
    const double t1 = -rear + (rear + front) * double(i) / steps, f1 = f(t1);
    if ((f0 <= 0) != (f1 <= 0)) {
      double lo = t0, hi = t1, flo = f0;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi), fm = f(mid);
        if ((fm <= 0) == (flo <= 0)) { lo = mid; flo = fm; } else { hi = mid; }
      }
      const double root = 0.5 * (lo + hi);
      if (!best || std::abs(root) < std::abs(*best)) best = root;
    }
    t0 = t1;
    f0 = f1;
  }
  return best;
}

inline double sphereSdf(const glm::dvec3& p) { return glm::length(p) - 1.0; }
inline std::function<double(const glm::dvec3&)> torusSdf(double R, double r) {
  return [=](const glm::dvec3& p) { return glm::length(glm::dvec2(glm::length(glm::dvec2(p.x, p.z)) - R, p.y)) - r; };
}
/// Outward normal of the sphere / torus at (or near) a surface point.
inline glm::dvec3 sphereNormal(const glm::dvec3& p) { return glm::normalize(p); }
inline std::function<glm::dvec3(const glm::dvec3&)> torusNormal(double R) {
  return [=](const glm::dvec3& p) {
    const glm::dvec3 ring = R * glm::normalize(glm::dvec3(p.x, 0.0, p.z));
    return glm::normalize(p - ring);
  };
}

inline double angleDeg(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)));
}

inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(p * double(v.size())))];
}

/// Maps a mesh's UVs into [margin, 1 - margin]², leaving room for padding around them.
inline void shrinkUvs(Mesh& mesh, float margin) {
  for (vec2& uv : mesh.uvs) uv = vec2(margin) + (1.0f - 2.0f * margin) * uv;
}

}  // namespace bake_test
