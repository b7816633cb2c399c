// The GPU's waves (trace.h, traceWave): many samples' first rays traced on the GPU, each
// hit settled and shaded on the CPU as traceGroup settles it, and every hit's AO, thickness
// and curvature rays sent to the GPU as jobs (bake/gpu_backend.h) made from the same seeds
// and sets (rays.h), the results finished on the CPU.
#include "rays.h"
#include "trace.h"

#include "glint/core/error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace glint::bake::detail {
namespace {

/// The GPU's share of one sample's hit work: the jobs that hold its answers (-1: none).
struct WaveWork {
  std::int32_t ao = -1, thickness = -1, curvature = -1;
};

/// What one chunk of a wave hands the GPU: its samples' jobs, then the vertices it claimed
/// for the vertex cache (VertexCache: measured once, by the chunk that first needs them).
struct WaveJobs {
  std::vector<HemisphereJob> hemisphere;
  std::vector<CurvatureJob> curvature;
  std::vector<std::uint32_t> thicknessVertices, curvatureVertices;
};

constexpr std::size_t kWaveChunk = 2048;  ///< samples a task of a wave's CPU stages takes

/// AO's rays at a hit, as ambientOcclusion casts them.
HemisphereJob aoJob(const Context& ctx, const Found& f, const vec3& normal, std::uint64_t seed) {
  const vec3 facet = outwardFacet(*f.hit, normal);
  const vec3 p = f.ray.at(f.hit->t) + ctx.epsilon * facet;
  return CosineSet(normal, seed, ctx.options.aoSamples).job(p, facet, ctx.aoDistance, false);
}

/// Thickness's rays, as thicknessFrom casts them.
HemisphereJob thicknessJob(const Context& ctx, const vec3& point, const vec3& inward, const vec3& normal, std::uint64_t seed,
                           int samples) {
  const vec3 p = point + ctx.epsilon * inward;
  return CosineSet(-normal, mix(seed ^ kThicknessStream), samples).job(p, inward, ctx.thicknessDistance, true);
}

/// Curvature's points, as curvatureFrom drops them.
CurvatureJob curvatureJob(const Context& ctx, const vec3& p, const vec3& normal, std::uint64_t seed) {
  CurvatureJob job{.point = p, .radius = ctx.curvatureRadius, .normal = normal};
  job.turn = curvatureFrame(normal, seed, job.tangent, job.bitangent);
  return job;
}

/// Claims for measurement the vertices of a hit's triangle no one has claimed yet.
void claimVertices(const VertexCache& cache, const VertexCache::Values& values, std::uint32_t triangle,
                   std::vector<std::uint32_t>& claimed) {
  for (std::size_t k = 0; k < 3; ++k) {
    const std::uint32_t v = cache.vertexOfCorner[3 * std::size_t(triangle) + k];
    std::uint8_t now = kUnmeasured;
    if (values.state[v].load(std::memory_order_relaxed) == kUnmeasured &&
        values.state[v].compare_exchange_strong(now, kMeasuring, std::memory_order_relaxed))
      claimed.push_back(v);
  }
}

/// A cached map's value at a hit: its (measured) corners interpolated.
float cachedAtHit(const VertexCache& cache, const VertexCache::Values& values, const raytrace::Hit& hit) {
  float corner[3];
  for (std::size_t k = 0; k < 3; ++k) corner[k] = values.value[cache.vertexOfCorner[3 * std::size_t(hit.triangle) + k]];
  return (1.0f - hit.u - hit.v) * corner[0] + hit.u * corner[1] + hit.v * corner[2];
}

/// Stage 1 of a wave: each sample's low-poly geometry and first ray (closest: the sweep
/// towards the front; front first: the front ray, else the rear one; a cage: the cage's
/// ray). A sample without one gets an empty ray (tfar < tnear), which hits nothing.
void firstRays(const Context& ctx, std::span<const SampleInput> samples, std::size_t begin, std::size_t end,
               std::span<Geometry> geometry, std::span<raytrace::Ray> rays, const Caster& caster) {
  const bool closest = !ctx.options.cage && ctx.options.selection == HitSelection::Closest;
  for (std::size_t i = begin; i < end; ++i) {
    geometryAt(ctx, samples[i].slot, geometry[i]);
    const Geometry& g = geometry[i];
    raytrace::Ray& ray = rays[i];
    ray = {g.position, g.dir, 1.0f, 0.0f};
    float toLow = 0.0f;
    if (ctx.options.cage) ray = caster.cageRay(g, samples[i].slot, toLow);
    else if (!closest && ctx.front > 0.0f) ray = {g.position, g.dir, 0.0f, ctx.front};
    else if (!closest && ctx.rear > 0.0f) ray = {g.position, -g.dir, 0.0f, ctx.rear};
    else if (closest && ctx.front + ctx.rear > 0.0f) ray = {g.position - ctx.rear * g.dir, g.dir, 0.0f, ctx.front + ctx.rear};
    if (ray.tnear <= ray.tfar) caster.note(ray);
  }
}

/// One wave's samples through the stages of traceWave, each a method; the per-sample state
/// lives in the wave's arrays (about 460 bytes a sample: internal.h, kWaveBytesPerSample).
class Wave {
public:
  Wave(const Context& ctx, std::span<const SampleInput> samples, std::span<SampleResult> results)
      : m_ctx(ctx), m_samples(samples), m_results(results), m_n(samples.size()),
        m_chunks((m_n + kWaveChunk - 1) / kWaveChunk), m_counters(m_chunks), m_geometry(m_n), m_rays(m_n),
        m_hits(m_n), m_found(m_n), m_work(m_n), m_jobs(m_chunks) {}

  /// 1–2. Each sample's geometry and first ray; the rays traced on the GPU.
  void traceFirstRays() {
    forChunks([&](std::size_t, std::size_t begin, std::size_t end, const Caster& caster) {
      firstRays(m_ctx, m_samples, begin, end, m_geometry, m_rays, caster);
    });
    m_ctx.gpu->closest(m_rays, m_hits);
  }

  /// 3. Each hit settled as the CPU settles it (the rare second rays — behind P, a retry — on
  /// the CPU's BVH), the sample shaded, and its hit work written as jobs.
  void settleHits() {
    forChunks([&](std::size_t c, std::size_t begin, std::size_t end, const Caster& caster) {
      for (std::size_t i = begin; i < end; ++i) settle(i, caster, m_counters[c], m_jobs[c]);
    });
  }

  /// 4–5. The jobs in one list per kernel (the chunks' in order, then the vertices claimed
  /// for the vertex cache), traced on the GPU.
  void traceHitWork() {
    m_hemisphereFirst.resize(m_chunks);
    m_curvatureFirst.resize(m_chunks);
    for (std::size_t c = 0; c < m_chunks; ++c) {
      m_hemisphereFirst[c] = m_hemisphere.size();
      m_curvatureFirst[c] = m_curvature.size();
      m_hemisphere.insert(m_hemisphere.end(), m_jobs[c].hemisphere.begin(), m_jobs[c].hemisphere.end());
      m_curvature.insert(m_curvature.end(), m_jobs[c].curvature.begin(), m_jobs[c].curvature.end());
    }
    m_thicknessVertexFirst = m_hemisphere.size();
    m_curvatureVertexFirst = m_curvature.size();
    for (const WaveJobs& j : m_jobs) {
      m_thicknessVertices.insert(m_thicknessVertices.end(), j.thicknessVertices.begin(), j.thicknessVertices.end());
      m_curvatureVertices.insert(m_curvatureVertices.end(), j.curvatureVertices.begin(), j.curvatureVertices.end());
    }
    const VertexCache* cache = m_ctx.vertexCache.get();
    for (const std::uint32_t v : m_thicknessVertices) {  // (as interpolatedAtHit measures a vertex)
      const std::uint32_t corner = cache->cornerOfVertex[v];
      const vec3 normal = glm::normalize(m_ctx.highCornerNormals[corner]);
      m_hemisphere.push_back(thicknessJob(m_ctx, cache->position(corner), -normal, normal,
                                          mix(std::uint64_t(v) ^ kVertexStream), vertexSamples()));
    }
    for (const std::uint32_t v : m_curvatureVertices) {
      const std::uint32_t corner = cache->cornerOfVertex[v];
      const vec3 normal = glm::normalize(m_ctx.highCornerNormals[corner]);
      m_curvature.push_back(curvatureJob(m_ctx, cache->position(corner), normal, mix(std::uint64_t(v) ^ kVertexStream)));
    }
    m_hemisphereSums.resize(m_hemisphere.size());
    m_curvatureSums.resize(m_curvature.size());
    m_ctx.gpu->hemisphere(m_hemisphere, m_hemisphereSums);
    m_ctx.gpu->curvature(m_curvature, m_ctx.epsilon, m_curvatureSums);
  }

  /// 6. The vertices' values, then every sample finished as shade() would have; the wave's
  /// counts added to `counters`.
  void finish(Counters& counters) {
    storeVertexValues(counters);
    forChunks([&](std::size_t c, std::size_t begin, std::size_t end, const Caster&) {
      for (std::size_t i = begin; i < end; ++i) finishSample(i, c);
    });
    for (const Counters& c : m_counters) {
      counters.rays += c.rays;
      counters.aoRays += c.aoRays;
      counters.thicknessRays += c.thicknessRays;
      counters.curvatureRays += c.curvatureRays;
    }
  }

private:
  template <typename Body>
  void forChunks(const Body& body) {
    tbb::parallel_for(std::size_t(0), m_chunks, [&](std::size_t c) {
      body(c, c * kWaveChunk, std::min(m_n, (c + 1) * kWaveChunk), Caster(m_ctx, m_counters[c], nullptr));
    });
  }

  int vertexSamples() const { return std::min(kVertexSampleFactor * m_ctx.options.aoSamples, int(BaseTurns::kCount)); }

  void settle(std::size_t i, const Caster& caster, Counters& counters, WaveJobs& out) {
    const Context& ctx = m_ctx;
    const bool closest = !ctx.options.cage && ctx.options.selection == HitSelection::Closest;
    const Geometry& g = m_geometry[i];
    Found& f = m_found[i];
    const bool traced = m_rays[i].tnear <= m_rays[i].tfar;
    if (ctx.options.cage) f = caster.fromCage(g, m_samples[i].slot, &m_hits[i]);
    else if (!closest && traced) f = caster.frontFirst(g, &m_hits[i]);
    else if (closest && traced) caster.resolve(g, m_rays[i], m_hits[i], ctx.rear, 1.0f, f);
    m_results[i] = shade(ctx, g, f, m_samples[i], counters, true);
    if (!f.hit) return;
    const vec3 normal = highNormal(ctx, *f.hit);
    const std::uint64_t seed = m_samples[i].seed;
    const VertexCache* cache = ctx.vertexCache.get();
    if (ctx.hemisphere) {
      m_work[i].ao = std::int32_t(out.hemisphere.size());
      out.hemisphere.push_back(aoJob(ctx, f, normal, seed));
      counters.aoRays += std::uint64_t(ctx.options.aoSamples);
    }
    if (ctx.baking(Map::Thickness) && cache && (cache->small[f.hit->triangle] & VertexCache::kThickness)) {
      claimVertices(*cache, cache->thickness, f.hit->triangle, out.thicknessVertices);
    } else if (ctx.baking(Map::Thickness)) {
      m_work[i].thickness = std::int32_t(out.hemisphere.size());
      out.hemisphere.push_back(
          thicknessJob(ctx, f.ray.at(f.hit->t), -outwardFacet(*f.hit, normal), normal, seed, ctx.options.aoSamples));
      counters.thicknessRays += std::uint64_t(ctx.options.aoSamples);
    }
    if (ctx.baking(Map::Curvature) && cache && (cache->small[f.hit->triangle] & VertexCache::kCurvature)) {
      claimVertices(*cache, cache->curvature, f.hit->triangle, out.curvatureVertices);
    } else if (ctx.baking(Map::Curvature)) {
      m_work[i].curvature = std::int32_t(out.curvature.size());
      out.curvature.push_back(curvatureJob(ctx, f.ray.at(f.hit->t), normal, seed));
    }
  }

  void storeVertexValues(Counters& counters) {
    const VertexCache* cache = m_ctx.vertexCache.get();
    const float thicknessScale = 1.0f / (float(vertexSamples()) * m_ctx.thicknessDistance);
    for (std::size_t k = 0; k < m_thicknessVertices.size(); ++k) {
      cache->thickness.value[m_thicknessVertices[k]] = m_hemisphereSums[m_thicknessVertexFirst + k].value * thicknessScale;
      cache->thickness.state[m_thicknessVertices[k]].store(kMeasured, std::memory_order_relaxed);
      counters.thicknessRays += std::uint64_t(vertexSamples());
    }
    for (std::size_t k = 0; k < m_curvatureVertices.size(); ++k) {
      const CurvatureSum& sum = m_curvatureSums[m_curvatureVertexFirst + k];
      cache->curvature.value[m_curvatureVertices[k]] = sum.found ? sum.sum / float(sum.found) : 0.0f;
      cache->curvature.state[m_curvatureVertices[k]].store(kMeasured, std::memory_order_relaxed);
      counters.curvatureRays += sum.rays;
    }
    counters.vertexMeasurements += m_thicknessVertices.size() + m_curvatureVertices.size();
  }

  void finishSample(std::size_t i, std::size_t c) {
    const Context& ctx = m_ctx;
    SampleResult& r = m_results[i];
    const Found& f = m_found[i];
    const WaveWork& work = m_work[i];
    vec3 bent = m_geometry[i].dir;
    if (f.hit) {
      const vec3 normal = highNormal(ctx, *f.hit);
      const VertexCache* cache = ctx.vertexCache.get();
      if (work.ao >= 0) {
        const HemisphereSum& sum = m_hemisphereSums[m_hemisphereFirst[c] + std::size_t(work.ao)];
        const float len = glm::length(sum.directions);
        r.ao = sum.value / float(ctx.options.aoSamples);
        bent = sum.value > 0.0f && len > 0.0f ? sum.directions * (1.0f / len) : normal;
      }
      if (work.thickness >= 0) {
        r.thickness = m_hemisphereSums[m_hemisphereFirst[c] + std::size_t(work.thickness)].value /
                      (float(ctx.options.aoSamples) * ctx.thicknessDistance);
      } else if (ctx.baking(Map::Thickness)) {
        r.thickness = cachedAtHit(*cache, cache->thickness, *f.hit);
      }
      if (work.curvature >= 0) {
        const CurvatureSum& sum = m_curvatureSums[m_curvatureFirst[c] + std::size_t(work.curvature)];
        r.curvature = sum.found ? sum.sum / float(sum.found) : 0.0f;
        m_counters[c].curvatureRays += sum.rays;
      } else if (ctx.baking(Map::Curvature)) {
        r.curvature = cachedAtHit(*cache, cache->curvature, *f.hit);
      }
    }
    if (ctx.baking(Map::BentNormal)) r.bent = inSpace(ctx, m_geometry[i], bent);
  }

  const Context& m_ctx;
  std::span<const SampleInput> m_samples;
  std::span<SampleResult> m_results;
  std::size_t m_n, m_chunks;
  std::vector<Counters> m_counters;  ///< per chunk
  std::vector<Geometry> m_geometry;
  std::vector<raytrace::Ray> m_rays;
  std::vector<std::optional<raytrace::Hit>> m_hits;
  std::vector<Found> m_found;
  std::vector<WaveWork> m_work;
  std::vector<WaveJobs> m_jobs;  ///< per chunk
  std::vector<HemisphereJob> m_hemisphere;
  std::vector<CurvatureJob> m_curvature;
  std::vector<std::size_t> m_hemisphereFirst, m_curvatureFirst;  ///< per chunk: its first job in the lists
  std::size_t m_thicknessVertexFirst = 0, m_curvatureVertexFirst = 0;
  std::vector<std::uint32_t> m_thicknessVertices, m_curvatureVertices;
  std::vector<HemisphereSum> m_hemisphereSums;
  std::vector<CurvatureSum> m_curvatureSums;
};

}  // namespace

void traceWave(const Context& ctx, std::span<const SampleInput> samples, std::span<SampleResult> results, Counters& counters) {
  if (!ctx.gpu) fail(ErrorKind::Internal, "bake: a GPU wave without a GPU scene");
  Wave wave(ctx, samples, results);
  wave.traceFirstRays();
  wave.settleHits();
  wave.traceHitWork();
  wave.finish(counters);
}

}  // namespace glint::bake::detail
