// The procedural "Pipe Dream" stand-in (machine_room.h). Parts are appended one by one;
// each closed part shares its own vertices, so it is watertight on its own.
#include "glint/mesh/machine_room.h"

#include "glint/core/hash.h"

#include <algorithm>
#include <cmath>

namespace glint {

namespace {

constexpr float kModuleSize = 6.0f;  // metres between module centres
constexpr float kMargin = 3.0f;      // floor and walls beyond the outer modules
constexpr float kWallHeight = 10.0f;
constexpr int kTrianglesPerModule = 8668;  // counted from the parts below (see the test)

struct Random {
  std::uint32_t state;
  float next() {
    state = hash32(state + 0x9E3779B9u);
    return float(state >> 8) * (1.0f / 16777216.0f);
  }
  float range(float lo, float hi) { return lo + (hi - lo) * next(); }
};

/// Axis a closed tube runs along.
enum class Axis { X, Y, Z };

/// A closed cylinder (side in `rings` bands, both ends capped by fans) from `base` along
/// `axis` for `length`. Outward, counter-clockwise.
void addTube(Mesh& out, vec3 base, Axis axis, float length, float radius, int segments, int rings) {
  const std::uint32_t first = std::uint32_t(out.positions.size());
  const auto place = [&](float x, float y, float z) {
    // Local y is the tube's axis; the rotations keep orientation (determinant +1).
    switch (axis) {
      case Axis::X: return base + vec3(y, -x, z);
      case Axis::Y: return base + vec3(x, y, z);
      case Axis::Z: return base + vec3(x, -z, y);
    }
    return base;
  };
  for (int k = 0; k <= rings; ++k) {
    const float y = length * float(k) / float(rings);
    for (int s = 0; s < segments; ++s) {
      const float a = 2.0f * kPi * float(s) / float(segments);
      out.positions.push_back(place(radius * std::cos(a), y, radius * std::sin(a)));
    }
  }
  const std::uint32_t bottom = std::uint32_t(out.positions.size());
  out.positions.push_back(place(0.0f, 0.0f, 0.0f));
  out.positions.push_back(place(0.0f, length, 0.0f));
  const auto v = [&](int k, int s) { return first + std::uint32_t(k * segments + (s % segments)); };
  for (int k = 0; k < rings; ++k)
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = v(k, s), b = v(k, s + 1), c = v(k + 1, s + 1), d = v(k + 1, s);
      out.indices.insert(out.indices.end(), {a, c, b, a, d, c});
    }
  for (int s = 0; s < segments; ++s) {
    out.indices.insert(out.indices.end(), {bottom, v(0, s), v(0, s + 1)});
    out.indices.insert(out.indices.end(), {bottom + 1, v(rings, s + 1), v(rings, s)});
  }
}

/// A closed box, outward.
void addBox(Mesh& out, vec3 lo, vec3 hi) {
  const std::uint32_t first = std::uint32_t(out.positions.size());
  for (int i = 0; i < 8; ++i)
    out.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads)
    out.indices.insert(out.indices.end(), {first + q[0], first + q[1], first + q[2], first + q[0], first + q[2], first + q[3]});
}

/// An open grid of nu × nv quads spanning origin + [0, 1]·u + [0, 1]·v, facing u × v.
void addGrid(Mesh& out, vec3 origin, vec3 u, vec3 v, int nu, int nv) {
  const std::uint32_t first = std::uint32_t(out.positions.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) out.positions.push_back(origin + u * (float(i) / float(nu)) + v * (float(j) / float(nv)));
  const auto at = [&](int i, int j) { return first + std::uint32_t(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      out.indices.insert(out.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
}

int gridWidth(int modules) { return std::max(1, int(std::ceil(std::sqrt(double(std::max(1, modules)))))); }

/// One instrument module centred at (cx, 0, cz).
void addModule(Mesh& out, float cx, float cz, Random& rng) {
  // A low platform the instruments stand on.
  addBox(out, {cx - 2.5f, 0.0f, cz - 2.5f}, {cx + 2.5f, 0.3f, cz + 2.5f});
  // Three drums at the front.
  for (int i = 0; i < 3; ++i) {
    const float r = rng.range(0.45f, 0.8f);
    addTube(out, {cx - 1.6f + 1.6f * float(i), 0.3f, cz + 1.3f + rng.range(-0.2f, 0.2f)}, Axis::Y, rng.range(0.5f, 1.0f), r, 48, 4);
  }
  // A bank of upright pipes at the back, of rising heights.
  for (int i = 0; i < 6; ++i) {
    const float h = 2.0f + 0.5f * float(i) + rng.range(0.0f, 0.6f);
    addTube(out, {cx - 2.0f + 0.8f * float(i), 0.3f, cz - 1.6f}, Axis::Y, h, rng.range(0.15f, 0.25f), 32, 12);
  }
  // Two horizontal pipes crossing above, on four struts.
  const float hx = rng.range(2.4f, 3.2f), hz = rng.range(3.4f, 4.2f);
  addTube(out, {cx - 2.7f, hx, cz + 0.2f}, Axis::X, 5.4f, rng.range(0.12f, 0.2f), 32, 16);
  addTube(out, {cx + 0.9f, hz, cz - 2.7f}, Axis::Z, 5.4f, rng.range(0.12f, 0.2f), 32, 16);
  addBox(out, {cx - 2.45f, 0.3f, cz + 0.15f}, {cx - 2.35f, hx, cz + 0.25f});
  addBox(out, {cx + 2.35f, 0.3f, cz + 0.15f}, {cx + 2.45f, hx, cz + 0.25f});
  addBox(out, {cx + 0.85f, 0.3f, cz - 2.45f}, {cx + 0.95f, hz, cz - 2.35f});
  addBox(out, {cx + 0.85f, 0.3f, cz + 2.35f}, {cx + 0.95f, hz, cz + 2.45f});
}

}  // namespace

Mesh makeMachineRoom(const MachineRoomOptions& options) {
  const int modules = std::max(1, options.modules);
  const int width = gridWidth(modules);
  const float stage = float(width) * kModuleSize;
  const int cells = int(std::ceil(stage + 2.0f * kMargin));
  const float extent = float(cells);  // floor and walls in 1 m cells
  const float origin = -0.5f * stage - kMargin;
  Mesh out;
  addGrid(out, {origin, 0.0f, origin}, {0.0f, 0.0f, extent}, {extent, 0.0f, 0.0f}, cells, cells);            // floor, up
  addGrid(out, {origin, 0.0f, origin}, {extent, 0.0f, 0.0f}, {0.0f, kWallHeight, 0.0f}, cells, int(kWallHeight));  // back wall, +z
  addGrid(out, {origin, 0.0f, origin}, {0.0f, kWallHeight, 0.0f}, {0.0f, 0.0f, extent}, int(kWallHeight), cells);  // left wall, +x
  Random rng{options.seed * 7919u + 17u};
  for (int m = 0; m < modules; ++m) {
    const int i = m % width, j = m / width;
    addModule(out, -0.5f * stage + kModuleSize * (float(i) + 0.5f), -0.5f * stage + kModuleSize * (float(j) + 0.5f), rng);
  }
  computeNormals(out);
  return out;
}

int machineRoomModulesFor(std::size_t triangles) {
  return std::max(1, int(std::lround(double(triangles) / double(kTrianglesPerModule))));
}

std::array<vec3, 2> machineRoomLights(const MachineRoomOptions& options) {
  const float stage = float(gridWidth(options.modules)) * kModuleSize;
  // Off every grid line and plane of the stage: no surface grazes a light.
  return {vec3(-0.21f * stage + 0.137f, 9.0f + 0.3f * stage + 0.071f, 0.33f * stage + 0.193f),
          vec3(0.38f * stage + 0.113f, 6.0f + 0.1f * stage + 0.057f, 0.12f * stage - 0.089f)};
}

}  // namespace glint
