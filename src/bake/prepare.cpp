// Input checking and preparation for the baker: every problem a user can cause is
// reported here, in one line, before any time is spent tracing.
#include "glint/bake/baker.h"
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/mesh/tangents.h"
#include "glint/raytrace/raytracer.h"
#include "internal.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace glint::bake::detail {
namespace {

template <typename V>
void checkFinite(const std::vector<V>& values, const char* mesh, const char* what) {
  // One branch-free pass first (|x| ≤ FLT_MAX fails for inf and NaN),
  // the offender is looked for only when there is one.
  bool finite = true;
  for (const V& v : values) {
    for (int c = 0; c < V::length(); ++c) finite &= std::fabs(v[c]) <= FLT_MAX;
  }
  for (std::size_t i = 0; !finite && i < values.size(); ++i) {
    for (int c = 0; c < V::length(); ++c) {
      if (!std::isfinite(values[i][c])) fail(ErrorKind::Input, "{}: {} {} is not finite", mesh, what, i);
    }
  }
}

void warn(std::vector<std::string>& warnings, std::string message) {
  log::warn("{}", message);
  warnings.push_back(std::move(message));
}

/// Positions shared by vertices with different normals: hard edges, where rays fan apart.
std::size_t countHardEdgeVertices(const Mesh& mesh) {
  struct Hash {
    std::size_t operator()(const vec3& p) const {
      std::uint32_t b[3];
      std::memcpy(b, &p, sizeof(b));
      return std::size_t(b[0]) * 73856093u ^ std::size_t(b[1]) * 19349663u ^ std::size_t(b[2]) * 83492791u;
    }
  };
  std::unordered_map<vec3, std::pair<vec3, bool>, Hash> seen;
  std::size_t hard = 0;
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    auto [it, inserted] = seen.try_emplace(mesh.positions[i], mesh.normals[i], false);
    if (!inserted && !it->second.second && glm::dot(it->second.first, mesh.normals[i]) < 0.9999f) {
      it->second.second = true;
      ++hard;
    }
  }
  return hard;
}

}  // namespace

Prepared prepareInputs(const Mesh& low, const Mesh& high, const BakeOptions& options, BakeStats& stats,
                       std::vector<std::string>& warnings) {
  validateOptions(options);

  // Low poly: UVs first, it is the error users meet most.
  if (low.indices.empty()) fail(ErrorKind::Input, "low-poly mesh: has no triangles");
  if (!low.hasUvs()) {
    fail(ErrorKind::Input, "low-poly mesh has no UVs: unwrap it (one UV set, islands spaced apart) before baking");
  }
  low.validate("low-poly mesh");
  raytrace::checkRange(low.positions, "low-poly mesh");  // the rays start on it
  checkFinite(low.uvs, "low-poly mesh", "UV");
  checkFinite(low.normals, "low-poly mesh", "normal");
  high.validate("high-poly mesh");
  raytrace::checkRange(high.positions, "high-poly mesh");
  checkFinite(high.normals, "high-poly mesh", "normal");

  Prepared p;
  p.low = low;
  p.low.tangents.clear();
  p.diagonal = p.low.bounds().diagonal();
  if (!(p.diagonal > 0.0f)) fail(ErrorKind::Input, "low-poly mesh: all vertices are at one point");
  if (!p.low.hasNormals()) {
    warn(warnings, "low-poly mesh has no normals: generated smooth normals");
    generateSmoothNormals(p.low);  // as a file without normals gets them (mesh.h)
  }
  p.high = &high;
  if (!high.hasNormals()) {
    warn(warnings, "high-poly mesh has no normals: generated smooth normals");
    p.highWithNormals = high;
    generateSmoothNormals(p.highWithNormals);
    p.high = &p.highWithNormals;
  }
  if (options.cage) {
    const Mesh& cage = *options.cage;
    cage.validate("cage mesh");
    raytrace::checkRange(cage.positions, "cage mesh");
    if (cage.vertexCount() != low.vertexCount() || cage.indices != low.indices) {
      fail(ErrorKind::Input, "cage mesh must have the low poly's vertices and triangles ({} vertices, {} triangles), "
           "got {} and {}", low.vertexCount(), low.triangleCount(), cage.vertexCount(), cage.triangleCount());
    }
  }
  if (options.detail && options.detail->height.empty()) fail(ErrorKind::Input, "height detail map is empty");

  // Diagnostics the artist notes talk about.
  for (std::size_t t = 0; t < p.low.triangleCount(); ++t) {
    const vec2 a = p.low.uvs[p.low.indices[3 * t]], b = p.low.uvs[p.low.indices[3 * t + 1]],
               c = p.low.uvs[p.low.indices[3 * t + 2]];
    const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (std::fabs(area) <= 1e-12f) ++stats.degenerateUvTriangles;
    else if (area < 0.0f) ++stats.mirroredTriangles;
  }
  if (stats.degenerateUvTriangles) {
    warn(warnings, fmt::format("low-poly mesh: {} triangles have zero UV area and are skipped",
                               stats.degenerateUvTriangles));
  }
  if (stats.degenerateUvTriangles == p.low.triangleCount()) {
    fail(ErrorKind::Input, "low-poly mesh: every triangle has zero UV area; nothing to bake");
  }
  if (stats.mirroredTriangles) {
    warn(warnings, fmt::format("low-poly mesh: {} of {} triangles have mirrored UVs (baked; the bitangent "
                               "sign handles them in tangent space)", stats.mirroredTriangles,
                               p.low.triangleCount()));
  }
  stats.hardEdgeVertices = countHardEdgeVertices(p.low);
  if (stats.hardEdgeVertices) {
    warn(warnings, fmt::format("low-poly mesh: {} positions have unshared normals (hard edges); rays fan apart "
                               "there and may miss high-poly detail — see 'glint bake --help'",
                               stats.hardEdgeVertices));
  }

  p.originalIndices = p.low.indices;
  stats.addedVertices = frameLowPolyInPlace(p.low);  // unit normals, MikkTSpace tangents
  return p;
}

float sampleHeight(const Image& height, vec2 uv) {
  const int w = height.width(), h = height.height();
  const float fx = uv.x * float(w) - 0.5f, fy = (1.0f - uv.y) * float(h) - 0.5f;
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float ax = fx - x0f, ay = fy - y0f;
  const auto wrap = [](long i, int n) { return int(((i % n) + n) % n); };
  const int x0 = wrap(long(x0f), w), x1 = wrap(long(x0f) + 1, w);
  const int y0 = wrap(long(y0f), h), y1 = wrap(long(y0f) + 1, h);
  const float top = (1.0f - ax) * height.at(x0, y0, 0) + ax * height.at(x1, y0, 0);
  const float bottom = (1.0f - ax) * height.at(x0, y1, 0) + ax * height.at(x1, y1, 0);
  return (1.0f - ay) * top + ay * bottom;
}

vec3 detailNormal(const HeightDetail& detail, vec2 uv) {
  const float du = 1.0f / float(detail.height.width()), dv = 1.0f / float(detail.height.height());
  // Height change per texel along +u and +v (v up, like the tangent frame's bitangent).
  const float dhdx = 0.5f * (sampleHeight(detail.height, uv + vec2(du, 0.0f)) - sampleHeight(detail.height, uv - vec2(du, 0.0f)));
  const float dhdy = 0.5f * (sampleHeight(detail.height, uv + vec2(0.0f, dv)) - sampleHeight(detail.height, uv - vec2(0.0f, dv)));
  return glm::normalize(vec3(-detail.scale * dhdx, -detail.scale * dhdy, 1.0f));
}

vec3 combineDetail(const vec3& base, const vec3& detail) {
  // Reoriented normal mapping (Barré-Brisebois & Hill 2012): the rotation taking +Z to
  // `base`, applied to `detail`. Exact for any base except straight down (-Z).
  const vec3 t = base + vec3(0.0f, 0.0f, 1.0f);
  if (t.z <= 1e-6f) return base;
  const vec3 u = detail * vec3(-1.0f, -1.0f, 1.0f);
  return glm::normalize(t * glm::dot(t, u) / t.z - u);
}

}  // namespace glint::bake::detail

namespace glint::bake {

void validateOptions(const BakeOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > 32768 || options.height > 32768) {
    fail(ErrorKind::Usage, "bake size must be 1..32768 on each side, got {}x{}", options.width, options.height);
  }
  if (!validSampleCount(options.samples)) {
    fail(ErrorKind::Usage, "samples per texel must be a square (1, 4, 9, 16, 25, 36, 49, 64, ... {}), got {}", kMaxSamples,
         options.samples);
  }
  if (options.maps.needs(kHemisphereRays | kInwardRays) &&
      (options.aoSamples < 1 || options.aoSamples > kMaxAoSamples)) {
    fail(ErrorKind::Usage, "AO samples must be 1..{}, got {}", kMaxAoSamples, options.aoSamples);
  }
  if (options.maxFront.value < 0.0f || options.maxRear.value < 0.0f || options.aoDistance.value < 0.0f ||
      options.thicknessDistance.value < 0.0f || options.curvatureRadius.value < 0.0f) {
    fail(ErrorKind::Usage, "ray distances must not be negative");
  }
  if (options.maps.has(Map::Thickness) && !(options.thicknessDistance.value > 0.0f)) {
    fail(ErrorKind::Usage, "--thickness-distance must be more than 0 (it is the distance that reads 1)");
  }
  if (options.maps.has(Map::Curvature) && !(options.curvatureRadius.value > 0.0f)) {
    fail(ErrorKind::Usage, "--curvature-radius must be more than 0 (it is the scale curvature is measured at)");
  }
  if (options.padding < 0) fail(ErrorKind::Usage, "--padding must not be negative, got {}", options.padding);
}

}  // namespace glint::bake
