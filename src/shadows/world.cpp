// The shadow worlds: plain data shared by the shadow scenes, the ray-traced oracle
// tests and the benchmark.
#include "glint/shadows/world.h"

#include "glint/core/error.h"
#include "glint/core/locations.h"
#include "glint/core/log.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace glint::shadows {

Mesh World::worldMesh(std::size_t i) const {
  Mesh m = objects.at(i).mesh;
  m.transform(objects[i].transform);
  return m;
}

Bounds World::bounds() const {
  Bounds out;
  bool first = true;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const Bounds b = worldMesh(i).bounds();
    out = first ? b : Bounds{glm::min(out.min, b.min), glm::max(out.max, b.max)};
    first = false;
  }
  return out;
}

std::size_t World::triangleCount() const {
  std::size_t n = 0;
  for (const auto& o : objects) n += o.mesh.triangleCount();
  return n;
}

namespace {
constexpr vec3 kGroundColor{0.78f, 0.76f, 0.70f};

WorldObject ground(float size) {
  return {.name = "ground", .mesh = makePlane(size), .color = kGroundColor, .castsShadow = false, .ground = true};
}

// Demo sphere path: x(t) swings through the slab's volume wall, period 8 s.
vec3 demoSphereCenter(double time) {
  constexpr float kRadius = 0.5f;
  const float x = 2.2f + 1.8f * float(std::sin(2.0 * 3.14159265358979 * time / 8.0));
  return {x, kRadius, -0.5f};
}
}  // namespace

World makeDemoWorld(double time, bool sphereCasts) {
  World w;
  w.lightPosition = {-2.0f, 5.5f, 1.2f};
  w.objects.push_back(ground(12.0f));
  // The slab: a flattened cube, 1.6 × 0.12 × 1.6, hovering at y = 2.2.
  w.objects.push_back({.name = "slab",
                       .mesh = makeCube(1.0f),
                       .transform = glm::scale(glm::translate(mat4(1.0f), {0.0f, 2.2f, 0.0f}), {1.6f, 0.12f, 1.6f}),
                       .color = {0.85f, 0.55f, 0.25f}});
  w.objects.push_back({.name = "sphere",
                       .mesh = makeUvSphere(0.5f, 40, 20),
                       .color = {0.35f, 0.55f, 0.9f},
                       .castsShadow = sphereCasts});
  animateDemoWorld(w, time);
  return w;
}

void animateDemoWorld(World& world, double time) {
  world.objects.at(2).transform = glm::translate(mat4(1.0f), demoSphereCenter(time));
}

namespace {
// Three square fins sharing one vertical edge: a non-manifold edge (three faces) and
// open edges everywhere else — the kind of modelling shortcut (grass cards, leaves)
// that breaks naive silhouette extraction.
Mesh makePinwheel(float size) {
  Mesh m;
  for (int k = 0; k < 3; ++k) {
    const float a = float(k) * 2.0f * kPi / 3.0f;
    const vec3 dir{std::cos(a), 0.0f, std::sin(a)};
    const vec3 n{-dir.z, 0.0f, dir.x};
    const auto base = std::uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {vec3(0.0f), size * dir, size * dir + vec3(0, size, 0), vec3(0, size, 0)});
    m.normals.insert(m.normals.end(), 4, -n);
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  return m;
}
}  // namespace

World makeBunnyWorld(const Mesh& bunny, bool openBase) {
  World w;
  w.lightPosition = {2.4f, 4.0f, -1.6f};
  w.objects.push_back(ground(8.0f));
  Mesh b = bunny;
  const Bounds bb = b.bounds();
  const float scale = 1.0f / bb.extent().y;
  if (openBase) {
    // The scanned bunny has holes in its base: remove every triangle lying within
    // 2.5% of the height above the bottom, which opens several holes there.
    const float cut = bb.min.y + 0.025f * bb.extent().y;
    std::vector<std::uint32_t> kept;
    for (std::size_t t = 0; t < b.triangleCount(); ++t) {
      const float y0 = b.positions[b.indices[3 * t]].y, y1 = b.positions[b.indices[3 * t + 1]].y,
                  y2 = b.positions[b.indices[3 * t + 2]].y;
      if (std::max({y0, y1, y2}) >= cut) kept.insert(kept.end(), b.indices.begin() + long(3 * t), b.indices.begin() + long(3 * t + 3));
    }
    b.indices = std::move(kept);
  }
  const vec3 offset{-bb.center().x, -bb.min.y, -bb.center().z};
  w.objects.push_back({.name = "bunny",
                       .mesh = std::move(b),
                       .transform = glm::scale(mat4(1.0f), vec3(scale)) * glm::translate(mat4(1.0f), offset),
                       .color = {0.82f, 0.78f, 0.72f}});
  w.objects.push_back({.name = "pinwheel",
                       .mesh = makePinwheel(0.45f),
                       .transform = glm::translate(mat4(1.0f), {-1.1f, 0.0f, 0.6f}),
                       .color = {0.4f, 0.7f, 0.4f}});
  return w;
}

World makeBenchWorld(std::size_t triangles) {
  World w;
  w.lightPosition = {1.5f, 9.0f, 2.0f};
  w.objects.push_back(ground(14.0f));
  constexpr int kGrid = 8;  // 64 spheres
  // A UV sphere with s segments and s/2 rings has s·(s − 2) triangles.
  const double perSphere = double(triangles) / double(kGrid * kGrid);
  const int segments = std::max(6, int(std::lround(1.0 + std::sqrt(1.0 + perSphere))));
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const vec3 c{-4.9f + 1.4f * float(i), 0.9f + 0.35f * float((i + j) % 3), -4.9f + 1.4f * float(j)};
      w.objects.push_back({.name = "sphere",
                           .mesh = makeUvSphere(0.45f, segments, segments / 2),
                           .transform = glm::translate(mat4(1.0f), c),
                           .color = {0.5f + 0.06f * float(i), 0.55f, 0.9f - 0.06f * float(j)}});
    }
  }
  return w;
}

Camera sceneCamera(SceneView view, float aspect) {
  switch (view) {
    case SceneView::Demo: return Camera::lookAt({2.2f, 3.4f, 5.6f}, {0.9f, 0.8f, -0.4f}, {0, 1, 0}, 45.0f, aspect, 0.5f, 60.0f);
    case SceneView::Inside:
      return Camera::lookAt({-0.1f, 0.9f, -0.2f}, {2.6f, 0.2f, 1.6f}, {0, 1, 0}, 70.0f, aspect, 0.05f, 60.0f);
    case SceneView::Bunny:
      return Camera::lookAt({0.9f, 1.5f, 2.7f}, {-0.35f, 0.25f, 0.1f}, {0, 1, 0}, 45.0f, aspect, 0.3f, 40.0f);
  }
  return {};
}

std::filesystem::path bunnyPath() { return findDataFile("bunny/bunny.ply", "the Stanford bunny"); }

Mesh loadBunny() {
  const auto path = bunnyPath();
  const log::Level saved = log::level();
  log::setLevel(std::max(saved, log::Level::Error));  // "no normals; generating" is expected for the PLY
  Mesh mesh;
  try {
    mesh = loadMesh(path);
  } catch (...) {
    log::setLevel(saved);
    throw;
  }
  log::setLevel(saved);
  // Outward winding: the signed volume (divergence theorem) of a closed mesh is positive.
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
        c(mesh.positions[mesh.indices[3 * t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  if (volume < 0.0) {
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
    for (auto& n : mesh.normals) n = -n;
  }
  return mesh;
}

}  // namespace glint::shadows
