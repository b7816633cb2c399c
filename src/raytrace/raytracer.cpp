// Embree (3 or 4: the seam is embree.h) behind glint::raytrace::Scene: one device and one scene per Scene,
// one triangle geometry per mesh, buffers owned by Embree (copied in) so the
// Scene never dangles on a caller's Mesh.
#include "glint/raytrace/raytracer.h"

#include "glint/core/error.h"

#include "embree.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <string>

namespace glint::raytrace {

struct Scene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Bounds bounds;
  std::size_t meshes = 0;
  std::size_t triangles = 0;
  std::atomic<std::int64_t> memory{0};
  std::mutex errorMutex;
  std::string firstError;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

RTCBuildQuality toEmbree(SceneOptions::Quality q) {
  switch (q) {
    case SceneOptions::Quality::Fast: return RTC_BUILD_QUALITY_LOW;
    case SceneOptions::Quality::Default: return RTC_BUILD_QUALITY_MEDIUM;
    case SceneOptions::Quality::High: return RTC_BUILD_QUALITY_HIGH;
  }
  return RTC_BUILD_QUALITY_MEDIUM;
}

}  // namespace

void checkRange(std::span<const vec3> positions, const std::string& what) {
  // Embree's range: beyond it, its builder and traversal abort the process.
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const vec3& p = positions[i];
    for (int k = 0; k < 3; ++k)
      if (std::isfinite(p[k]) && std::fabs(p[k]) > kMaxCoordinate)
        fail(ErrorKind::Input, "{}: vertex {} at ({}, {}, {}) lies beyond ±{:.4g}, the range Embree traces", what, i, p.x, p.y, p.z,
             kMaxCoordinate);
  }
}

namespace {

void checkMesh(const Mesh& mesh, const std::string& what) {
  if (mesh.indices.empty()) fail(ErrorKind::Input, "{}: has no triangles", what);
  if (mesh.indices.size() % 3 != 0) {
    fail(ErrorKind::Input, "{}: index count {} is not a multiple of 3", what, mesh.indices.size());
  }
  const std::size_t n = mesh.positions.size();
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= n) {
      fail(ErrorKind::Input, "{}: index {} is {}, out of range for {} vertices", what, i, mesh.indices[i], n);
    }
  }
  checkRange(mesh.positions, what);
}

/// The hit, written in place (see embree::fill); a miss resets `out`.
void toHit(const RTCRayHit& rh, std::optional<Hit>& out) {
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    out.reset();
    return;
  }
  Hit& hit = out.emplace();
  hit.t = rh.ray.tfar;
  hit.mesh = rh.hit.geomID;
  hit.triangle = rh.hit.primID;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  // Embree's unnormalized triangle Ng is parallel to cross(v1 - v0, v2 - v0): it
  // points to the counter-clockwise side, glint's front (checked by the tests).
  const vec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  const float len = glm::length(ng);
  hit.geometricNormal = len > 0.0f ? ng * (1.0f / len) : vec3(0.0f);
}

// Batches are split into chunks of this many rays: large enough to amortise
// TBB's task overhead, small enough to balance two to a hundred cores.
constexpr std::size_t kBatchGrain = 256;

}  // namespace

Scene::Scene(const Mesh& mesh, const SceneOptions& options) : Scene(std::span<const Mesh>(&mesh, 1), options) {}

Scene::Scene(std::span<const Mesh> meshes, const SceneOptions& options) : m_impl(std::make_unique<Impl>()) {
  if (meshes.empty()) fail(ErrorKind::Input, "ray-tracing scene: no meshes");
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    checkMesh(meshes[i], meshes.size() == 1 ? std::string("ray-tracing mesh") : fmt::format("ray-tracing mesh {}", i));
  }

  Impl& impl = *m_impl;
  impl.device = rtcNewDevice("verbose=0");
  if (!impl.device) fail(ErrorKind::Internal, "cannot create an Embree device (error {})", int(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(
      impl.device,
      [](void* user, RTCError code, const char* message) {
        auto* self = static_cast<Impl*>(user);
        std::lock_guard lock(self->errorMutex);
        if (self->firstError.empty()) {
          self->firstError = fmt::format("Embree error {}: {}", int(code), message ? message : "");
        }
      },
      &impl);
  rtcSetDeviceMemoryMonitorFunction(
      impl.device,
      [](void* user, ssize_t bytes, bool /*post*/) {
        static_cast<Impl*>(user)->memory.fetch_add(bytes, std::memory_order_relaxed);
        return true;  // never refuse an allocation
      },
      &impl);

  impl.scene = rtcNewScene(impl.device);
  rtcSetSceneBuildQuality(impl.scene, toEmbree(options.quality));
  rtcSetSceneFlags(impl.scene, options.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);

  bool first = true;
  for (const Mesh& mesh : meshes) {
    RTCGeometry geometry = rtcNewGeometry(impl.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geometry, toEmbree(options.quality));
    // Embree's 16-byte loads of the last vertex must stay in allocated memory: a shared
    // vector needs spare capacity after it, Embree's own buffers come padded.
    if (options.shareMeshes && mesh.positions.capacity() > mesh.positions.size()) {
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.positions.data(), 0,
                                 sizeof(vec3), mesh.positions.size());
    } else {
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                   RTC_FORMAT_FLOAT3, sizeof(vec3),
                                                                   mesh.positions.size()));
      if (vertices) std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(vec3));
    }
    if (options.shareMeshes) {
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(), 0,
                                 3 * sizeof(std::uint32_t), mesh.triangleCount());
    } else {
      auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), mesh.triangleCount()));
      if (indices) std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
    }
    if (!rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0) ||
        !rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_INDEX, 0)) {
      rtcReleaseGeometry(geometry);
      fail(ErrorKind::Internal, "cannot allocate ray-tracing buffers ({})", impl.firstError);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(impl.scene, geometry);  // ids are 0, 1, ... in attach order
    rtcReleaseGeometry(geometry);

    const Bounds b = mesh.bounds();
    impl.bounds.min = first ? b.min : glm::min(impl.bounds.min, b.min);
    impl.bounds.max = first ? b.max : glm::max(impl.bounds.max, b.max);
    first = false;
    impl.triangles += mesh.triangleCount();
  }
  impl.meshes = meshes.size();
  rtcCommitScene(impl.scene);
  if (rtcGetDeviceError(impl.device) != RTC_ERROR_NONE || !impl.firstError.empty()) {
    fail(ErrorKind::Internal, "cannot build the ray-tracing scene: {}", impl.firstError);
  }
}

Scene::~Scene() = default;
Scene::Scene(Scene&& other) noexcept = default;
Scene& Scene::operator=(Scene&& other) noexcept = default;

std::optional<Hit> Scene::intersect(const Ray& ray) const {
  if (!embree::traceable(ray)) [[unlikely]] return std::nullopt;
  RTCRayHit rh;
  embree::fill(ray, rh);
  embree::intersect(m_impl->scene, rh);
  std::optional<Hit> hit;
  toHit(rh, hit);
  return hit;
}

bool Scene::occluded(const Ray& ray) const {
  if (!embree::traceable(ray)) [[unlikely]] return false;
  RTCRayHit rh;
  embree::fill(ray, rh);
  return embree::occluded(m_impl->scene, rh.ray);
}

void Scene::intersectBatch(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const {
  if (rays.size() != hits.size()) {
    fail(ErrorKind::Usage, "intersectBatch: {} rays but room for {} hits", rays.size(), hits.size());
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), kBatchGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) hits[i] = intersect(rays[i]);
                    });
}

void Scene::intersectCoherent(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const {
  if (rays.size() != hits.size()) {
    fail(ErrorKind::Usage, "intersectCoherent: {} rays but room for {} hits", rays.size(), hits.size());
  }
  constexpr std::size_t kGroup = 64;  // Embree 3 packetizes within a call; 64 keeps the copy on the stack
  RTCRayHit buffer[kGroup];
  for (std::size_t first = 0; first < rays.size(); first += kGroup) {
    const std::size_t count = std::min(kGroup, rays.size() - first);
    for (std::size_t i = 0; i < count; ++i) embree::fill(rays[first + i], buffer[i]);
    embree::intersectGroup(m_impl->scene, buffer, count);
    for (std::size_t i = 0; i < count; ++i) toHit(buffer[i], hits[first + i]);
  }
}

std::vector<std::optional<Hit>> Scene::intersectBatch(std::span<const Ray> rays) const {
  std::vector<std::optional<Hit>> hits(rays.size());
  intersectBatch(rays, hits);
  return hits;
}

void Scene::occludedBatch(std::span<const Ray> rays, std::span<std::uint8_t> blocked) const {
  if (rays.size() != blocked.size()) {
    fail(ErrorKind::Usage, "occludedBatch: {} rays but room for {} answers", rays.size(), blocked.size());
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), kBatchGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        blocked[i] = occluded(rays[i]) ? 1 : 0;
                      }
                    });
}

std::vector<std::uint8_t> Scene::occludedBatch(std::span<const Ray> rays) const {
  std::vector<std::uint8_t> blocked(rays.size());
  occludedBatch(rays, blocked);
  return blocked;
}

Bounds Scene::bounds() const { return m_impl->bounds; }
std::size_t Scene::meshCount() const { return m_impl->meshes; }
std::size_t Scene::triangleCount() const { return m_impl->triangles; }
std::size_t Scene::memoryBytes() const {
  const std::int64_t bytes = m_impl->memory.load(std::memory_order_relaxed);
  return bytes > 0 ? std::size_t(bytes) : 0;
}

}  // namespace glint::raytrace
