// The procedural "Pipe Dream" stand-in (machine_room.h). Parts are appended one by one;
// each closed part shares its own vertices, so it is watertight on its own.
#include "glint/pipedream/machine_room.h"

#include "glint/core/hash.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace glint {

namespace {

constexpr float kModuleSize = 6.0f;  // metres between module centres
constexpr float kMargin = 3.0f;      // floor and walls beyond the outer modules
constexpr float kWallHeight = 10.0f;
constexpr int kTrianglesPerModule = 8668;  // counted from the parts below (see the test)

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
void addModule(Mesh& out, float cx, float cz, HashSequence& rng) {
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
  HashSequence rng{options.seed * 7919u + 17u};
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

// ------------------------------------------------------------------ the instrument machine
namespace glint {

namespace {

/// Appends parts with normals and a material per triangle. Every part shares positions
/// only bit for bit (flat faces have their own vertices), so each is watertight once
/// welded and shades with flat edges.
class PartBuilder {
public:
  explicit PartBuilder(Mesh& mesh, std::vector<MachineMaterial>* materials = nullptr)
      : m_mesh(mesh), m_materials(materials) {}
  void material(MachineMaterial m) { m_material = m; }

  std::uint32_t vertex(vec3 p, vec3 n) {
    m_mesh.positions.push_back(p);
    m_mesh.normals.push_back(n);
    return std::uint32_t(m_mesh.positions.size() - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    m_mesh.indices.insert(m_mesh.indices.end(), {a, b, c});
    if (m_materials) m_materials->push_back(m_material);
  }
  /// a-b-c-d counter-clockwise seen from the front.
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }

  /// A tube of `radius` swept along `path` (at least two points), frames carried along by
  /// parallel transport, both ends capped flat. Outward, counter-clockwise.
  void sweep(const std::vector<vec3>& path, float radius, int segments) {
    const std::size_t n = path.size();
    std::vector<vec3> tangent(n);
    for (std::size_t i = 0; i < n; ++i)
      tangent[i] = glm::normalize(path[std::min(i + 1, n - 1)] - path[i == 0 ? 0 : i - 1]);
    // A first normal across the first tangent; then each frame turned minimally onto the next.
    const vec3 t0 = tangent[0];
    const vec3 helper = std::abs(t0.y) < 0.9f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
    vec3 normal = glm::normalize(glm::cross(helper, t0));
    std::vector<std::vector<vec3>> rings(n);
    const std::uint32_t first = std::uint32_t(m_mesh.positions.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0) normal = glm::normalize(normal - glm::dot(normal, tangent[i]) * tangent[i]);
      const vec3 binormal = glm::cross(tangent[i], normal);
      rings[i].resize(std::size_t(segments));
      for (int s = 0; s < segments; ++s) {
        const float a = 2.0f * kPi * float(s) / float(segments);
        const vec3 radial = std::cos(a) * normal + std::sin(a) * binormal;
        rings[i][std::size_t(s)] = path[i] + radius * radial;
        vertex(rings[i][std::size_t(s)], radial);
      }
    }
    const auto v = [&](std::size_t i, int s) { return first + std::uint32_t(i * std::size_t(segments) + std::size_t(s % segments)); };
    for (std::size_t i = 0; i + 1 < n; ++i)
      for (int s = 0; s < segments; ++s) quad(v(i, s), v(i, s + 1), v(i + 1, s + 1), v(i + 1, s));
    cap(path.front(), rings.front(), -tangent.front(), false);
    cap(path.back(), rings.back(), tangent.back(), true);
  }

  /// A straight tube from `base` along `axis` (unit) for `length`, in `bands` bands.
  void tube(vec3 base, vec3 axis, float length, float radius, int segments, int bands = 1) {
    std::vector<vec3> path;
    for (int k = 0; k <= bands; ++k) path.push_back(base + axis * (length * float(k) / float(bands)));
    sweep(path, radius, segments);
  }

  /// An axis-aligned box, flat faces.
  void box(vec3 lo, vec3 hi) {
    const vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z},
                       {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}};
    struct Face {
      int a, b, c, d;
      vec3 n;
    };
    const Face faces[6] = {{0, 2, 3, 1, {0, 0, -1}}, {4, 5, 7, 6, {0, 0, 1}}, {0, 1, 5, 4, {0, -1, 0}},
                           {2, 6, 7, 3, {0, 1, 0}},  {0, 4, 6, 2, {-1, 0, 0}}, {1, 3, 7, 5, {1, 0, 0}}};
    for (const Face& f : faces)
      quad(vertex(c[f.a], f.n), vertex(c[f.b], f.n), vertex(c[f.c], f.n), vertex(c[f.d], f.n));
  }

  /// An open grid of nu × nv quads over origin + [0, 1]·u + [0, 1]·v, facing u × v.
  void grid(vec3 origin, vec3 u, vec3 v, int nu, int nv) {
    const vec3 n = glm::normalize(glm::cross(u, v));
    const std::uint32_t first = std::uint32_t(m_mesh.positions.size());
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) vertex(origin + u * (float(i) / float(nu)) + v * (float(j) / float(nv)), n);
    const auto at = [&](int i, int j) { return first + std::uint32_t(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  }

private:
  /// A flat fan over a ring; `forward`: the ring runs counter-clockwise seen from `normal`.
  void cap(vec3 centre, const std::vector<vec3>& ring, vec3 normal, bool forward) {
    const std::uint32_t c = vertex(centre, normal);
    const std::uint32_t first = std::uint32_t(m_mesh.positions.size());
    for (const vec3& p : ring) vertex(p, normal);
    const std::uint32_t n = std::uint32_t(ring.size());
    for (std::uint32_t s = 0; s < n; ++s) {
      const std::uint32_t a = first + s, b = first + (s + 1) % n;
      if (forward) triangle(c, a, b);
      else triangle(c, b, a);
    }
  }

  Mesh& m_mesh;
  std::vector<MachineMaterial>* m_materials;
  MachineMaterial m_material = MachineMaterial::Steel;
};

/// Points of a circular arc in the plane of `u` (from centre to start) and `v`, from angle a0 to a1.
void arc(std::vector<vec3>& path, vec3 centre, vec3 u, vec3 v, float a0, float a1, int samples, bool skipFirst) {
  for (int k = skipFirst ? 1 : 0; k <= samples; ++k) {
    const float a = a0 + (a1 - a0) * float(k) / float(samples);
    path.push_back(centre + std::cos(a) * u + std::sin(a) * v);
  }
}

/// The cymbal: a thin closed disc of radius 1, bell up: a top cone from the bell to the
/// rim, a narrow band at the rim, a flatter bottom cone.
Mesh makeCymbalMesh(int segments) {
  Mesh m;
  PartBuilder b(m);
  const float topApex = 0.09f, rimTop = 0.0f, rimBottom = -0.012f, bottomApex = 0.06f;
  std::vector<vec3> ring(static_cast<std::size_t>(segments));
  for (int s = 0; s < segments; ++s) {
    const float a = 2.0f * kPi * float(s) / float(segments);
    ring[std::size_t(s)] = vec3(std::cos(a), 0.0f, -std::sin(a));  // counter-clockwise seen from above
  }
  const auto cone = [&](float apex, float rimY, bool up) {
    // Normal of a cone through the apex and the rim: perpendicular to the slant.
    const float slope = (apex - rimY);  // rise over a run of 1
    const std::uint32_t tip = b.vertex({0.0f, apex, 0.0f}, {0.0f, up ? 1.0f : -1.0f, 0.0f});
    std::vector<std::uint32_t> rim;
    for (const vec3& r : ring) {
      const vec3 n = glm::normalize(vec3(r.x * slope, 1.0f, r.z * slope)) * (up ? 1.0f : -1.0f);
      rim.push_back(b.vertex(vec3(r.x, rimY, r.z), n));
    }
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t p = rim[std::size_t(s)], q = rim[std::size_t((s + 1) % segments)];
      if (up) b.triangle(tip, p, q);
      else b.triangle(tip, q, p);
    }
  };
  cone(topApex, rimTop, true);
  cone(bottomApex, rimBottom, false);
  std::vector<std::uint32_t> upper, lower;
  for (const vec3& r : ring) {
    upper.push_back(b.vertex(vec3(r.x, rimTop, r.z), r));
    lower.push_back(b.vertex(vec3(r.x, rimBottom, r.z), r));
  }
  for (int s = 0; s < segments; ++s) {
    const std::size_t i = std::size_t(s), j = std::size_t((s + 1) % segments);
    b.quad(lower[i], lower[j], upper[j], upper[i]);
  }
  return m;
}

/// Rings of a mallet head of `segments` segments.
int malletRings(int segments) { return std::max(4, segments / 2); }

/// A mallet: an arm from the pivot (origin) along −x to a head at (−1, 0, 0): the arm's
/// box (the first 12 triangles), then the head.
Mesh makeMalletMesh(int segments, float headRadius = 0.075f) {
  Mesh m;
  PartBuilder b(m);
  b.box({-0.93f, -0.012f, -0.012f}, {0.02f, 0.012f, 0.012f});
  Mesh head = makeUvSphere(headRadius, segments, malletRings(segments));
  head.uvs.clear();
  head.tangents.clear();
  head.transform(glm::translate(mat4(1.0f), vec3(-1.0f, 0.0f, 0.0f)));
  m.append(head);
  return m;
}

/// One module's sizes: segment counts from the detail level, the deck's height.
struct ModuleSizes {
  explicit ModuleSizes(int detail)
      : big(8 + 6 * detail), pipe(6 + 4 * detail), thin(4 + 2 * detail), bands(detail), detail(detail) {}
  int big;     ///< drums, collectors
  int pipe;    ///< pipes
  int thin;    ///< posts, stands
  int bands;   ///< bands along straight tubes
  int detail;
  vec3 up{0.0f, 1.0f, 0.0f};
  float deck = 0.3f;
};

/// Two drums at the front, each with a mallet on a post to its right.
void addDrums(PartBuilder& b, InstrumentMachine& out, vec3 c, const ModuleSizes& z, HashSequence& rng) {
  const int big = z.big, bands = z.bands;
  const vec3 up = z.up;
  const float deck = z.deck;
  // Two drums at the front, each with a mallet on a post to its right.
  const vec2 drumAt[2] = {{-1.35f, 1.3f}, {0.35f, 1.55f}};
  for (int i = 0; i < 2; ++i) {
    const float r = i == 0 ? rng.range(0.5f, 0.6f) : rng.range(0.38f, 0.46f);
    const float h = rng.range(0.55f, 0.8f);
    const vec3 base = c + vec3(drumAt[i].x, deck, drumAt[i].y);
    b.material(MachineMaterial::Drum);
    b.tube(base, up, h, r, big, bands);
    out.drums.push_back({base + vec3(0.0f, h, 0.0f), r});
    const vec3 post = base + vec3(r + 0.28f, 0.0f, 0.0f);
    b.material(MachineMaterial::Steel);
    b.box(post + vec3(-0.035f, 0.0f, -0.035f), post + vec3(0.035f, h + 0.5f, 0.035f));
    out.mallets.push_back({post + vec3(0.0f, h + 0.5f, 0.0f), int(out.drums.size()) - 1});
  }
}

/// A cymbal stand at the front right.
void addCymbalStand(PartBuilder& b, InstrumentMachine& out, vec3 c, const ModuleSizes& z, HashSequence& rng) {
  const int pipe = z.pipe, thin = z.thin, bands = z.bands;
  const vec3 up = z.up;
  const float deck = z.deck;
  // A cymbal stand at the front right.
  const vec3 stand = c + vec3(1.85f, deck, 0.85f);
  const float standHeight = rng.range(1.5f, 1.9f);
  b.material(MachineMaterial::Steel);
  b.tube(stand, up, 0.03f, 0.22f, pipe);
  b.tube(stand + vec3(0.0f, 0.03f, 0.0f), up, standHeight - 0.03f, 0.025f, thin, bands);
  out.cymbals.push_back({stand + vec3(0.0f, standHeight + 0.02f, 0.0f), rng.range(0.42f, 0.5f)});
}

/// A xylophone: two rails on four legs, eight bars of falling length across them.
void addXylophone(PartBuilder& b, InstrumentMachine& out, vec3 c, const ModuleSizes& z) {
  const float deck = z.deck;
  // A xylophone: two rails on four legs, eight bars of falling length across them.
  const float railTop = 0.85f, x0 = -2.3f, x1 = 0.55f, za = -0.25f, zb = -0.95f;
  b.material(MachineMaterial::Steel);
  for (const float z : {za, zb}) {
    b.box(c + vec3(x0, railTop - 0.06f, z - 0.04f), c + vec3(x1, railTop, z + 0.04f));
    for (const float x : {x0 + 0.05f, x1 - 0.05f})
      b.box(c + vec3(x - 0.03f, deck, z - 0.03f), c + vec3(x + 0.03f, railTop - 0.06f, z + 0.03f));
  }
  b.material(MachineMaterial::Wood);
  for (int i = 0; i < 8; ++i) {
    const float x = x0 + 0.2f + 0.345f * float(i);
    const float length = 1.05f - 0.055f * float(i);
    const vec3 lo = c + vec3(x - 0.12f, railTop, -0.6f - 0.5f * length);
    const vec3 hi = c + vec3(x + 0.12f, railTop + 0.05f, -0.6f + 0.5f * length);
    b.box(lo, hi);
    out.bars.push_back({vec3(0.5f * (lo.x + hi.x), hi.y, 0.5f * (lo.z + hi.z)), hi - lo});
  }
}

/// A bank of upright pipes at the back, of rising heights.
void addPipeBank(PartBuilder& b, vec3 c, const ModuleSizes& z, HashSequence& rng) {
  const int pipe = z.pipe, bands = z.bands;
  const vec3 up = z.up;
  const float deck = z.deck;
  // A bank of upright pipes at the back, of rising heights.
  b.material(MachineMaterial::Brass);
  for (int i = 0; i < 6; ++i) {
    const float h = 2.0f + 0.45f * float(i) + rng.range(0.0f, 0.5f);
    b.tube(c + vec3(-2.05f + 0.62f * float(i), deck, -2.0f), up, h, rng.range(0.14f, 0.2f), pipe, 2 * bands);
  }
}

/// The launcher: a pipe along the deck, bent upwards, rising to its mouth, with a clamp.
void addLauncher(PartBuilder& b, InstrumentMachine& out, vec3 c, const ModuleSizes& z, HashSequence& rng) {
  const int pipe = z.pipe, detail = z.detail;
  const float deck = z.deck;
  // The launcher: a pipe along the deck, bent upwards, rising to its mouth.
  {
    const float r = 0.13f, bend = 0.45f;
    const float mouthHeight = rng.range(2.3f, 2.9f);
    const float x = 2.2f, y = deck + r + 0.02f;
    std::vector<vec3> path;
    const int run = 2 + 2 * detail, turn = 4 + 3 * detail;
    for (int k = 0; k <= run; ++k) path.push_back(c + vec3(x, y, 1.6f - 1.9f * float(k) / float(run)));
    // Quarter circle from travelling −z to travelling +y.
    arc(path, c + vec3(x, y + bend, -0.3f), vec3(0.0f, -bend, 0.0f), vec3(0.0f, 0.0f, -bend), 0.0f, 0.5f * kPi, turn, true);
    const vec3 top = c + vec3(x, mouthHeight, -0.3f - bend);
    const vec3 from = path.back();
    for (int k = 1; k <= run; ++k) path.push_back(glm::mix(from, top, float(k) / float(run)));
    b.material(MachineMaterial::Copper);
    b.sweep(path, r, pipe);
    out.launchers.push_back({top, r});
    // A clamp holding the riser: a strut from the deck.
    b.material(MachineMaterial::Steel);
    b.box(c + vec3(x + r, deck, -0.3f - bend - 0.03f), c + vec3(x + r + 0.06f, 0.5f * (deck + mouthHeight), -0.3f - bend + 0.03f));
  }
}

/// A collector at the left.
void addCollector(PartBuilder& b, InstrumentMachine& out, vec3 c, const ModuleSizes& z, HashSequence& rng) {
  const int big = z.big, bands = z.bands;
  const vec3 up = z.up;
  const float deck = z.deck;
  // A collector at the left.
  b.material(MachineMaterial::Teal);
  const vec3 collector = c + vec3(-2.15f, deck, 0.35f);
  const float collectorHeight = rng.range(0.9f, 1.2f);
  b.tube(collector, up, collectorHeight, 0.3f, big, bands);
  out.collectors.push_back({collector + vec3(0.0f, collectorHeight, 0.0f), 0.3f});
}

/// Overhead: a straight pipe on two struts, and a pipe arched across the module.
void addOverhead(PartBuilder& b, vec3 c, const ModuleSizes& z, HashSequence& rng) {
  const int pipe = z.pipe, bands = z.bands, detail = z.detail;
  const float deck = z.deck;
  // Overhead: a straight pipe on two struts, and a pipe arched across the module.
  const float hx = rng.range(3.1f, 3.6f);
  b.material(MachineMaterial::Brass);
  b.tube(c + vec3(-2.7f, hx, 0.25f), vec3(1.0f, 0.0f, 0.0f), 5.4f, rng.range(0.1f, 0.14f), pipe, 4 * bands);
  b.material(MachineMaterial::Steel);
  b.box(c + vec3(-2.5f, deck, 0.2f), c + vec3(-2.4f, hx, 0.3f));
  b.box(c + vec3(2.4f, deck, 0.2f), c + vec3(2.5f, hx, 0.3f));
  {
    std::vector<vec3> path;
    const float rise = rng.range(3.8f, 4.4f);
    const int samples = 8 + 6 * detail;
    const vec3 centre = c + vec3(-0.9f, deck + 0.02f, -0.05f);
    for (int k = 0; k <= samples; ++k) {
      const float a = kPi * float(k) / float(samples);
      path.push_back(centre + vec3(0.0f, rise * std::sin(a), 2.45f * std::cos(a)));
    }
    b.material(MachineMaterial::Brass);
    b.sweep(path, 0.1f, pipe);
  }
}

/// One module of instruments around `c`. Its parts draw from `rng` in this order, and the
/// stage's geometry (and so its cached cut and the golden pictures) depends on that order.
void addInstrumentModule(PartBuilder& b, InstrumentMachine& out, vec3 c, int detail, HashSequence& rng) {
  const ModuleSizes z(detail);
  b.material(MachineMaterial::Platform);
  b.box(c + vec3(-2.6f, 0.0f, -2.6f), c + vec3(2.6f, z.deck, 2.6f));
  addDrums(b, out, c, z, rng);
  addCymbalStand(b, out, c, z, rng);
  addXylophone(b, out, c, z);
  addPipeBank(b, c, z, rng);
  addLauncher(b, out, c, z, rng);
  addCollector(b, out, c, z, rng);
  addOverhead(b, c, z, rng);
}

}  // namespace

vec3 machineMaterialColor(MachineMaterial material) {
  switch (material) {
    case MachineMaterial::Floor: return {0.42f, 0.43f, 0.46f};
    case MachineMaterial::Wall: return {0.62f, 0.58f, 0.52f};
    case MachineMaterial::Platform: return {0.30f, 0.22f, 0.16f};
    case MachineMaterial::Drum: return {0.62f, 0.12f, 0.10f};
    case MachineMaterial::Brass: return {0.78f, 0.60f, 0.28f};
    case MachineMaterial::Copper: return {0.75f, 0.38f, 0.22f};
    case MachineMaterial::Steel: return {0.36f, 0.38f, 0.42f};
    case MachineMaterial::Wood: return {0.70f, 0.48f, 0.26f};
    case MachineMaterial::Teal: return {0.16f, 0.50f, 0.50f};
  }
  return vec3(0.5f);
}

InstrumentMachine makeInstrumentMachine(const InstrumentMachineOptions& options) {
  const int detail = std::clamp(options.detail, 1, 16);
  InstrumentMachine out;
  PartBuilder b(out.staticMesh, &out.triangleMaterial);
  // The room: x in [-10.5, 10.5], z in [-6.8, 7.6], walls 8 m high; no ceiling, no front wall.
  const float x0 = -10.5f, x1 = 10.5f, z0 = -6.8f, z1 = 7.6f, height = 8.0f;
  const int cellsPerMetre = std::max(1, (detail + 1) / 2);
  const int nx = int(std::lround((x1 - x0) * float(cellsPerMetre))), nz = int(std::lround((z1 - z0) * float(cellsPerMetre)));
  const int ny = int(std::lround(height * float(cellsPerMetre)));
  b.material(MachineMaterial::Floor);
  b.grid({x0, 0.0f, z0}, {0.0f, 0.0f, z1 - z0}, {x1 - x0, 0.0f, 0.0f}, nz, nx);  // up
  b.material(MachineMaterial::Wall);
  b.grid({x0, 0.0f, z0}, {x1 - x0, 0.0f, 0.0f}, {0.0f, height, 0.0f}, nx, ny);  // back, facing +z
  b.grid({x0, 0.0f, z0}, {0.0f, height, 0.0f}, {0.0f, 0.0f, z1 - z0}, ny, nz);  // left, facing +x
  b.grid({x1, 0.0f, z1}, {0.0f, height, 0.0f}, {0.0f, 0.0f, z0 - z1}, ny, nz);  // right, facing −x
  out.room = {{x0, 0.0f, z0}, {x1, height, z1}};
  out.shellTriangles = out.staticMesh.triangleCount();

  // Long pipes on brackets along the back and left walls: WWDC 2003 session 212's "horizontal bar" whose
  // shadow on the wall is cut in, and which the balls' shadows cross.
  const int pipe = 6 + 4 * detail;
  for (const float y : {4.3f, 5.7f}) {
    b.material(MachineMaterial::Brass);
    b.tube({x0 + 0.6f, y, z0 + 0.55f}, {1.0f, 0.0f, 0.0f}, (x1 - x0) - 1.2f, 0.16f, pipe, 8 * detail);
    b.tube({x0 + 0.55f, y - 0.8f, z0 + 1.1f}, {0.0f, 0.0f, 1.0f}, (z1 - z0) - 2.4f, 0.12f, pipe, 6 * detail);
    b.material(MachineMaterial::Steel);
    for (int k = 0; k < 5; ++k) {
      const float x = x0 + 1.5f + 4.5f * float(k);
      b.box({x - 0.05f, y - 0.05f, z0}, {x + 0.05f, y + 0.05f, z0 + 0.55f});
    }
    for (int k = 0; k < 3; ++k) {
      const float z = z0 + 2.0f + 5.0f * float(k);
      b.box({x0, y - 0.85f, z - 0.05f}, {x0 + 0.55f, y - 0.75f, z + 0.05f});
    }
  }

  HashSequence rng{options.seed * 7919u + 101u};
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 3; ++col)
      addInstrumentModule(b, out, vec3(-6.4f + 6.4f * float(col), 0.0f, row == 0 ? -3.0f : 3.2f), detail, rng);

  out.lights = {{.position = {-4.137f, 7.213f, 4.371f}, .range = 17.5f, .intensity = 1.3f, .name = "key"},
                {.position = {6.529f, 5.171f, -0.813f}, .range = 12.0f, .intensity = 0.85f, .name = "fill"}};

  const int round = 8 + 4 * detail;
  {
    PartBuilder skin(out.skin);
    skin.tube({0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.02f, 1.0f, round);
  }
  out.cymbal = makeCymbalMesh(round);
  const int malletSegments = std::max(8, round / 2);
  out.mallet = makeMalletMesh(malletSegments);
  // A third of the segments and rings: the proxy's vertices lie at every third of the
  // head's angles (to rounding: the head's sphere is shrunk by 1e-4 so that rounding
  // cannot put a vertex outside), so the proxy is inside the convex head.
  const int proxy = malletSegments / 3;
  const bool subset = malletSegments % 3 == 0 && proxy >= 8 && malletRings(malletSegments) == 3 * malletRings(proxy);
  out.malletShadow = subset ? makeMalletMesh(proxy, 0.075f * (1.0f - 1e-4f)) : out.mallet;
  return out;
}

}  // namespace glint
