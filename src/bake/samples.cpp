#include "glint/bake/samples.h"

#include "glint/core/error.h"
#include "glint/core/hash.h"
#include "glint/core/file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace glint::bake {

Mesh makeStuddedTorus(const StuddedTorusOptions& o) {
  Mesh mesh = makeTorus(o.majorRadius, o.minorRadius, o.segments, o.sides);
  // Displacement from the UVs (u around the axis, v around the tube, v = 0 on the outer
  // equator): seam vertices get the same value on both sides, so the surface stays closed.
  const auto dome = [](float x) {  // x: distance from a stud centre in cell units, 0..~0.7
    const float r = x / 0.38f;
    return r < 1.0f ? 0.5f + 0.5f * std::cos(kPi * r) : 0.0f;  // C1 at the rim
  };
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    const vec2 uv = mesh.uvs[i];
    const float cu = uv.x * float(o.studsAround), cv = uv.y * float(o.studsAcross);
    const float du = cu - std::floor(cu) - 0.5f, dv = cv - std::floor(cv) - 0.5f;
    float h = o.studHeight * dome(std::sqrt(du * du + dv * dv));
    // Groove: a smooth trough on the outer equator (v = 0 and v = 1 are the same circle).
    const float fromEquator = std::min(uv.y, 1.0f - uv.y) * 2.0f * kPi * o.minorRadius;
    const float width = 0.04f;
    if (fromEquator < width) h -= o.grooveDepth * (0.5f + 0.5f * std::cos(kPi * fromEquator / width));
    mesh.positions[i] += h * mesh.normals[i];
  }
  computeNormals(mesh);
  mesh.tangents.clear();
  // computeNormals averages per vertex; the u and v seams duplicate vertices, so their
  // twins must agree: average the normals of coincident positions.
  const int rowLength = o.segments + 1;
  for (int j = 0; j <= o.sides; ++j) {
    const std::size_t a = std::size_t(j * rowLength), b = a + std::size_t(o.segments);
    const vec3 n = glm::normalize(mesh.normals[a] + mesh.normals[b]);
    mesh.normals[a] = mesh.normals[b] = n;
  }
  for (int i = 0; i <= o.segments; ++i) {
    const std::size_t a = std::size_t(i), b = std::size_t(o.sides * rowLength + i);
    const vec3 n = glm::normalize(mesh.normals[a] + mesh.normals[b]);
    mesh.normals[a] = mesh.normals[b] = n;
  }
  return mesh;
}

Mesh subdivideFlat(const Mesh& mesh, int k) {
  if (k < 1) fail(ErrorKind::Usage, "subdivideFlat: k must be at least 1, got {}", k);
  Mesh out;
  const bool normals = mesh.hasNormals(), uvs = mesh.hasUvs();
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1], i2 = mesh.indices[3 * t + 2];
    const auto base = std::uint32_t(out.positions.size());
    // Row r has k − r + 1 vertices; vertex (r, c) has weights (1 − (r + c)/k, c/k, r/k).
    const auto index = [&](int r, int c) { return base + std::uint32_t(r * (k + 1) - r * (r - 1) / 2 + c); };
    for (int r = 0; r <= k; ++r) {
      for (int c = 0; c <= k - r; ++c) {
        const float w1 = float(c) / float(k), w2 = float(r) / float(k), w0 = 1.0f - w1 - w2;
        out.positions.push_back(w0 * mesh.positions[i0] + w1 * mesh.positions[i1] + w2 * mesh.positions[i2]);
        if (normals) out.normals.push_back(glm::normalize(w0 * mesh.normals[i0] + w1 * mesh.normals[i1] + w2 * mesh.normals[i2]));
        if (uvs) out.uvs.push_back(w0 * mesh.uvs[i0] + w1 * mesh.uvs[i1] + w2 * mesh.uvs[i2]);
      }
    }
    for (int r = 0; r < k; ++r) {
      for (int c = 0; c < k - r; ++c) {
        out.indices.insert(out.indices.end(), {index(r, c), index(r, c + 1), index(r + 1, c)});
        if (c + 1 < k - r) out.indices.insert(out.indices.end(), {index(r, c + 1), index(r + 1, c + 1), index(r + 1, c)});
      }
    }
  }
  return out;
}

Image makeScratchesAndPores(int size, int pores, int scratches) {
  if (size < 4) fail(ErrorKind::Usage, "detail map size must be at least 4, got {}", size);
  Image image(size, size, 1, PixelType::F32);
  auto px = image.pixels<float>();
  std::fill(px.begin(), px.end(), 1.0f);
  HashSequence rng{12345u};  // core/hash.h's generator: a fixed sequence, the same picture everywhere
  const auto random = [&] { return rng.next(); };
  const float s = float(size);
  // Wrapped offset: the map tiles, so distances are measured on a torus.
  const auto wrapped = [&](float d) { return d - s * std::round(d / s); };
  const auto carve = [&](int x, int y, float depth) {
    float& h = px[std::size_t(((y % size + size) % size) * size + ((x % size + size) % size))];
    h = std::min(h, 1.0f - depth);
  };
  for (int i = 0; i < pores; ++i) {
    const float cx = random() * s, cy = random() * s, radius = 1.5f + 2.5f * random();
    const int r = int(std::ceil(radius));
    for (int y = int(cy) - r; y <= int(cy) + r; ++y)
      for (int x = int(cx) - r; x <= int(cx) + r; ++x) {
        const float d = std::hypot(wrapped(float(x) + 0.5f - cx), wrapped(float(y) + 0.5f - cy)) / radius;
        if (d < 1.0f) carve(x, y, 0.6f * (0.5f + 0.5f * std::cos(kPi * d)));
      }
  }
  for (int i = 0; i < scratches; ++i) {
    const float x0 = random() * s, y0 = random() * s, angle = random() * 2.0f * kPi, length = s * (0.15f + 0.3f * random());
    const vec2 dir(std::cos(angle), std::sin(angle));
    for (float t = 0.0f; t < length; t += 0.25f) {
      const vec2 p = vec2(x0, y0) + t * dir;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int x = int(std::floor(p.x)) + dx, y = int(std::floor(p.y)) + dy;
          const vec2 c(float(x) + 0.5f, float(y) + 0.5f);
          const float across = std::abs(glm::dot(c - p, vec2(-dir.y, dir.x)));
          if (across < 1.2f) carve(x, y, 0.35f * (1.0f - across / 1.2f));
        }
    }
  }
  return image;
}

void writeObj(const Mesh& mesh, const std::filesystem::path& path) {
  std::string text;
  text.reserve(mesh.vertexCount() * 96 + mesh.indices.size() * 12);
  // %.9g round-trips floats exactly: both tools read the same numbers.
  for (const vec3& p : mesh.positions) text += fmt::format("v {:.9g} {:.9g} {:.9g}\n", p.x, p.y, p.z);
  for (const vec2& t : mesh.uvs) text += fmt::format("vt {:.9g} {:.9g}\n", t.x, t.y);
  for (const vec3& n : mesh.normals) text += fmt::format("vn {:.9g} {:.9g} {:.9g}\n", n.x, n.y, n.z);
  const bool uvs = mesh.hasUvs(), normals = mesh.hasNormals();
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    text += 'f';
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[i + k] + 1;
      if (uvs && normals) text += fmt::format(" {}/{}/{}", v, v, v);
      else if (uvs) text += fmt::format(" {}/{}", v, v);
      else if (normals) text += fmt::format(" {}//{}", v, v);
      else text += fmt::format(" {}", v);
    }
    text += '\n';
  }
  writeTextAtomically(path, text);
}

}  // namespace glint::bake
