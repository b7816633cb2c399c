#include "glint/image/heightfield.h"

#include "glint/core/error.h"
#include "glint/core/hash.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace glint {
namespace {

float hash01(int a, int b, unsigned seed) {
  return float(hash32(std::uint32_t(a) * 73856093U ^ hash32(std::uint32_t(b) * 19349663U ^ seed)) & 0xFFFFFFU) / float(0xFFFFFF);
}

// Value noise on a lattice of `period` cells per tile, wrapping, smoothly interpolated.
float tileNoise(float u, float v, int period, unsigned seed) {
  const float x = u * float(period), y = v * float(period);
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = x - float(x0), fy = y - float(y0);
  auto at = [&](int i, int j) { return hash01(((i % period) + period) % period, ((j % period) + period) % period, seed); };
  const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  const float a = at(x0, y0) + sx * (at(x0 + 1, y0) - at(x0, y0));
  const float b = at(x0, y0 + 1) + sx * (at(x0 + 1, y0 + 1) - at(x0, y0 + 1));
  return a + sy * (b - a);
}

struct BrickSample {
  float edge;     // distance to the nearest brick edge, fraction of the tile (≤ 0 in mortar)
  int column;     // which brick (for per-brick variation)
  int row;
};

BrickSample brickAt(float u, float v, const BrickOptions& o) {
  const float rowHeight = 1.0f / float(o.rows), brickWidth = 1.0f / float(o.bricksPerRow);
  const int row = std::min(o.rows - 1, int(v / rowHeight));
  const float shift = (row % 2) ? 0.5f * brickWidth : 0.0f;
  float su = u + shift;
  su -= std::floor(su);
  const int column = std::min(o.bricksPerRow - 1, int(su / brickWidth));
  const float du = std::min(su - float(column) * brickWidth, float(column + 1) * brickWidth - su);
  const float dv = std::min(v - float(row) * rowHeight, float(row + 1) * rowHeight - v);
  return {std::min(du, dv) - 0.5f * o.mortar, column, row};
}

void checkSize(int size) {
  if (size < 8 || size > 16384) fail(ErrorKind::Usage, "procedural texture size must be 8..16384, got {}", size);
}
}  // namespace

Image makeBrickHeight(int size, const BrickOptions& o) {
  checkSize(size);
  Image out(size, size, 1, PixelType::F32);
  auto px = out.pixels<float>();
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = (float(x) + 0.5f) / float(size), v = (float(y) + 0.5f) / float(size);
      const BrickSample b = brickAt(u, v, o);
      float h = 0.1f;
      if (b.edge > 0.0f) {
        // A rounded (quarter-circle-like) bevel from the mortar up to the face.
        const float t = std::min(1.0f, b.edge / o.bevel);
        h = 0.1f + 0.75f * std::sqrt(t * (2.0f - t));
        // Pits and a slight per-brick tilt make the faces catch light unevenly.
        const float pits = tileNoise(u, v, 48, o.seed) * 0.6f + tileNoise(u, v, 96, o.seed + 1) * 0.4f;
        h += o.roughness * (pits - 0.5f) * 2.0f * t;
        h += 0.04f * (hash01(b.column, b.row, o.seed + 2) - 0.5f);
      } else {
        h += 0.04f * (tileNoise(u, v, 64, o.seed + 3) - 0.5f);  // gritty mortar
      }
      px[std::size_t(y) * std::size_t(size) + std::size_t(x)] = std::clamp(h, 0.0f, 1.0f);
    }
  }
  return out;
}

Image makeBrickAlbedo(int size, const BrickOptions& o) {
  checkSize(size);
  Image out(size, size, 4, PixelType::U8);
  const vec3 brick{0.62f, 0.27f, 0.18f}, mortar{0.72f, 0.70f, 0.66f};
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = (float(x) + 0.5f) / float(size), v = (float(y) + 0.5f) / float(size);
      const BrickSample b = brickAt(u, v, o);
      const float grain = tileNoise(u, v, 64, o.seed + 4);
      vec3 c;
      if (b.edge > 0.0f) {
        const float shade = 0.75f + 0.5f * hash01(b.column, b.row, o.seed + 5);
        c = brick * shade * (0.85f + 0.3f * grain);
        c.g += 0.05f * (hash01(b.row, b.column, o.seed + 6) - 0.5f);
      } else {
        c = mortar * (0.85f + 0.25f * grain);
      }
      for (int k = 0; k < 3; ++k) out.set(x, y, k, std::clamp(c[k], 0.0f, 1.0f));
      out.set(x, y, 3, 1.0f);
    }
  }
  return out;
}

Image makePoolTiles(int size, int tiles) {
  checkSize(size);
  if (tiles < 1 || tiles > size / 4) fail(ErrorKind::Usage, "tile count must be 1..{}, got {}", size / 4, tiles);
  Image out(size, size, 4, PixelType::U8);
  const float cell = float(size) / float(tiles);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float fx = (float(x) + 0.5f) / cell, fy = (float(y) + 0.5f) / cell;
      const int cx = int(fx), cy = int(fy);
      const float edge = std::min(std::min(fx - float(cx), float(cx + 1) - fx), std::min(fy - float(cy), float(cy + 1) - fy));
      const float shade = 0.93f + 0.07f * hash01(cx, cy, 11u);
      vec3 c = edge < 0.04f ? vec3(0.35f, 0.47f, 0.50f) : vec3(0.72f, 0.88f, 0.90f) * shade;
      c *= 0.95f + 0.05f * tileNoise((float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size), 32, 12u);
      for (int k = 0; k < 3; ++k) out.set(x, y, k, c[k]);
      out.set(x, y, 3, 1.0f);
    }
  }
  return out;
}

Image makeBumpsHeight(int size, int count) {
  checkSize(size);
  if (count < 1 || count > size / 4) fail(ErrorKind::Usage, "bump count must be 1..{}, got {}", size / 4, count);
  Image out(size, size, 1, PixelType::F32);
  auto px = out.pixels<float>();
  const float cell = float(size) / float(count);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float fx = (float(x) + 0.5f) / cell, fy = (float(y) + 0.5f) / cell;
      const int cx = int(fx), cy = int(fy);
      const float dx = fx - float(cx) - 0.5f, dy = fy - float(cy) - 0.5f;
      const float r = std::sqrt(dx * dx + dy * dy) / 0.4f;  // bump radius: 40% of a cell
      const float profile = r < 1.0f ? 0.5f + 0.5f * std::cos(kPi * r) : 0.0f;
      const float sign = ((cx + cy) % 2 == 0) ? 1.0f : -1.0f;
      px[std::size_t(y) * std::size_t(size) + std::size_t(x)] = 0.5f + 0.4f * sign * profile;
    }
  }
  return out;
}

}  // namespace glint
