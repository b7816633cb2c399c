// Rays through the BVH on the GPU (scenes/bake_tracer.h).
#include "glint/scenes/bake_tracer.h"

#include "glint/core/error.h"

#include <algorithm>
#include <chrono>
#include <cstring>

namespace glint::scenes {

namespace {

/// A ray as the shader's RayIn (vec3 origin, float tnear, vec3 direction, float tfar).
struct GpuRay {
  vec3 origin;
  float tnear;
  vec3 direction;
  float tfar;
};
static_assert(sizeof(GpuRay) == 32, "GpuRay is the shader's RayIn");

template <typename T>
gl::Buffer storage(const std::vector<T>& data, const char* name) {
  // An empty buffer cannot be made: one zeroed element stands in (the shader checks lengths).
  if (data.empty()) {
    const T zero{};
    return gl::Buffer(sizeof(T), &zero, 0, name);
  }
  return gl::Buffer(data.size() * sizeof(T), data.data(), 0, name);
}

}  // namespace

BakeTracer::BakeTracer(const raytrace::Bvh& bvh, std::span<const vec3> cornerNormals, std::size_t batch)
    : m_trace(gl::Program::fromFiles({"bake/trace.comp"})),
      m_hemisphere(gl::Program::fromFiles({"bake/hemisphere.comp"})),
      m_curvature(gl::Program::fromFiles({"bake/curvature.comp"})),
      m_nodes(storage(bvh.nodes, "bake-bvh-nodes")),
      m_triangles(storage(bvh.triangles, "bake-bvh-triangles")),
      m_ids(storage(bvh.ids, "bake-bvh-ids")),
      m_batch(batch) {
  if (batch == 0) fail(ErrorKind::Usage, "BakeTracer: a batch of 0 items");
  const raytrace::HemisphereTurns& turns = raytrace::hemisphereTurns();
  std::vector<vec2> table(raytrace::HemisphereTurns::kCount);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = {turns.cosine[i], turns.sine[i]};
  m_turns = storage(table, "bake-turns");
  m_cornerNormals = storage(std::vector<vec3>(cornerNormals.begin(), cornerNormals.end()), "bake-corner-normals");
  m_normalsGiven = !cornerNormals.empty();
  // The largest item either way: a hemisphere job (80 bytes) up, 32 for a ray.
  m_up = gl::Buffer(batch * sizeof(raytrace::HemisphereJob), nullptr, GL_DYNAMIC_STORAGE_BIT, "bake-batch-up");
  m_down = gl::Buffer(batch * sizeof(BakeHit), nullptr, 0, "bake-batch-down");
  if (glGetError() == GL_OUT_OF_MEMORY)
    fail(ErrorKind::NoGpu, "the GPU has not enough memory for the bake's {} MiB", gpuBytes() >> 20);
  m_empty = bvh.nodes.empty();
  std::uint32_t triangles = 0;
  for (const std::uint32_t id : bvh.ids) triangles = std::max(triangles, id + 1);
  m_normals.assign(triangles, vec3(0.0f));
  for (std::size_t k = 0; k < bvh.ids.size(); ++k) {
    const raytrace::BvhTriangle& t = bvh.triangles[k];
    m_normals[bvh.ids[k]] = glm::normalize(glm::cross(vec3(t.b) - vec3(t.a), vec3(t.c) - vec3(t.a)));
  }
}

void BakeTracer::run(gl::Program& program, const void* up, std::size_t upBytes, void* down, std::size_t downBytes,
                    std::size_t count, double raysPerItem) {
  program.use();
  m_nodes.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  m_triangles.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  m_ids.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
  m_up.bindBase(GL_SHADER_STORAGE_BUFFER, 3);
  m_down.bindBase(GL_SHADER_STORAGE_BUFFER, 4);
  m_turns.bindBase(GL_SHADER_STORAGE_BUFFER, 5);
  m_cornerNormals.bindBase(GL_SHADER_STORAGE_BUFFER, 6);
  const auto* in = static_cast<const std::byte*>(up);
  auto* out = static_cast<std::byte*>(down);
  constexpr double kTargetMs = 30.0;
  for (std::size_t first = 0; first < count;) {
    const std::size_t budget = std::size_t(std::max(1.0, m_raysPerDispatch / std::max(raysPerItem, 1.0)));
    const std::size_t n = std::min({m_batch, count - first, budget});
    const auto start = std::chrono::steady_clock::now();
    m_up.update(0, n * upBytes, in + first * upBytes);
    program.set("uCount", std::uint32_t(n));
    glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    m_down.read(0, n * downBytes, out + first * downBytes);  // waits for the dispatch
    if (const GLenum error = glGetError(); error == GL_OUT_OF_MEMORY || error == GL_CONTEXT_LOST)
      fail(ErrorKind::NoGpu, "the GPU {} during the bake", error == GL_OUT_OF_MEMORY ? "ran out of memory" : "was lost");
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++m_dispatches;
    m_longestMs = std::max(m_longestMs, ms);
    // The next dispatch sized to take about kTargetMs, growing at most 4× at a time.
    const double rays = double(n) * raysPerItem;
    m_raysPerDispatch = std::clamp(rays * kTargetMs / std::max(ms, 0.05), m_raysPerDispatch * 0.25, m_raysPerDispatch * 4.0);
    m_raysPerDispatch = std::clamp(m_raysPerDispatch, 1024.0, double(std::size_t(1) << 28));
    first += n;
  }
}

std::vector<BakeHit> BakeTracer::trace(std::span<const raytrace::Ray> rays, bool anyHit) {
  std::vector<BakeHit> out(rays.size());
  if (m_empty || rays.empty()) return out;
  std::vector<GpuRay> upload(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const raytrace::Ray& r = rays[i];
    upload[i] = {r.origin, r.tnear, r.direction, r.tfar};
  }
  m_trace.use();
  m_trace.set("uAnyHit", anyHit);
  run(m_trace, upload.data(), sizeof(GpuRay), out.data(), sizeof(BakeHit), upload.size(), 1.0);
  return out;
}

void BakeTracer::hemisphere(std::span<const raytrace::HemisphereJob> jobs, std::span<raytrace::HemisphereSum> sums) {
  if (sums.size() != jobs.size()) fail(ErrorKind::Internal, "BakeTracer::hemisphere: {} sums for {} jobs", sums.size(), jobs.size());
  std::uint32_t most = 0;
  double rays = 0.0;
  for (const raytrace::HemisphereJob& job : jobs) {
    most = std::max(most, job.count);
    rays += double(job.count);
  }
  if (most > raytrace::HemisphereTurns::kCount)
    fail(ErrorKind::Internal, "BakeTracer::hemisphere: {} rays a job (at most {})", most, raytrace::HemisphereTurns::kCount);
  if (m_empty) {  // nothing to hit: every ray escapes or runs its whole length
    for (std::size_t j = 0; j < jobs.size(); ++j) sums[j] = {};
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      if (jobs[j].closest) sums[j].value = float(jobs[j].count) * jobs[j].distance;
    }
    if (std::any_of(jobs.begin(), jobs.end(), [](const auto& job) { return job.closest == 0; }))
      fail(ErrorKind::Internal, "BakeTracer::hemisphere: AO on an empty hierarchy");
    return;
  }
  if (jobs.empty()) return;
  run(m_hemisphere, jobs.data(), sizeof(raytrace::HemisphereJob), sums.data(), sizeof(raytrace::HemisphereSum), jobs.size(),
      rays / double(jobs.size()));
}

void BakeTracer::curvature(std::span<const raytrace::CurvatureJob> jobs, float epsilon, std::span<raytrace::CurvatureSum> sums) {
  if (sums.size() != jobs.size()) fail(ErrorKind::Internal, "BakeTracer::curvature: {} sums for {} jobs", sums.size(), jobs.size());
  if (!m_normalsGiven && !m_empty) fail(ErrorKind::Internal, "BakeTracer::curvature without corner normals");
  if (jobs.empty()) return;
  if (m_empty) {
    for (std::size_t j = 0; j < jobs.size(); ++j) sums[j] = {.sum = 0.0f, .found = 0, .rays = 32};
    return;
  }
  m_curvature.use();
  m_curvature.set("uEpsilon", epsilon);
  run(m_curvature, jobs.data(), sizeof(raytrace::CurvatureJob), sums.data(), sizeof(raytrace::CurvatureSum), jobs.size(), 12.0);
}

std::vector<std::optional<raytrace::Hit>> BakeTracer::intersect(std::span<const raytrace::Ray> rays) {
  std::vector<std::optional<raytrace::Hit>> out(rays.size());
  intersect(rays, out);
  return out;
}

void BakeTracer::intersect(std::span<const raytrace::Ray> rays, std::span<std::optional<raytrace::Hit>> out) {
  if (out.size() != rays.size()) fail(ErrorKind::Internal, "BakeTracer::intersect: {} hits for {} rays", out.size(), rays.size());
  const std::vector<BakeHit> hits = trace(rays);
  for (std::size_t i = 0; i < hits.size(); ++i) {
    out[i].reset();
    if (!hits[i].hit()) continue;
    out[i] = raytrace::Hit{.t = hits[i].t, .mesh = 0, .triangle = hits[i].triangle, .u = hits[i].u, .v = hits[i].v,
                           .geometricNormal = m_normals[hits[i].triangle]};
  }
}

std::size_t BakeTracer::gpuBytes() const {
  return m_nodes.size() + m_triangles.size() + m_ids.size() + m_turns.size() + m_cornerNormals.size() + m_up.size() +
         m_down.size();
}

}  // namespace glint::scenes
