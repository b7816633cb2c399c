// Rays and shading for the samples of one texel: where the low poly is, which high-poly
// hit counts (closest |t|, front first, or through the cage), and what is stored.
#include "rays.h"
#include "trace.h"

#include "glint/bake/gpu_backend.h"
#include "glint/core/error.h"
#include "glint/mesh/tangents.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include "glint/core/hash.h"

#include <cmath>
#include <optional>
#include <thread>
#include <unordered_map>

namespace glint::bake::detail {
namespace {

struct Occlusion {
  float open = 1.0f;        ///< fraction of the rays that escaped
  vec3 bent{0.0f, 0.0f, 1.0f};  ///< unit mean of their directions; the normal if none did
};

/// Ambient occlusion and the bent normal at a high-poly hit: cosine-weighted hemisphere
/// rays, a Hammersley set rotated by a per-sample random offset (stratified, deterministic).
Occlusion ambientOcclusion(const Context& ctx, const Found& f, const vec3& normal, std::uint64_t seed, Counters& counters) {
  // The facet, not the smooth normal, decides what is above the surface: start just above
  // the facet and mirror rays that would dive under it (they would report the surface
  // itself as an occluder, speckling convex shapes).
  const vec3 facet = outwardFacet(*f.hit, normal);
  const vec3 p = f.ray.at(f.hit->t) + ctx.epsilon * facet;
  const CosineSet set(normal, seed, ctx.options.aoSamples);
  const int k = set.size();
  int open = 0;
  vec3 sum(0.0f);
  for (int i = 0; i < k; ++i) {
    vec3 d = set[i];
    const float below = glm::dot(d, facet);
    if (below < 0.0f) d -= 2.0f * below * facet;
    if (!ctx.scene.occluded({p, d, 0.0f, ctx.aoDistance})) {
      ++open;
      sum += d;
    }
  }
  counters.aoRays += std::uint64_t(k);
  const float len = glm::length(sum);
  return {float(open) / float(k), open > 0 && len > 0.0f ? sum * (1.0f / len) : normal};
}

/// Thickness at a point of the high poly: rays into the surface (cosine-weighted around
/// −normal, the AO set with a stream of its own) from just under it, each the distance to
/// the first surface it meets, capped at thicknessDistance; their mean over that distance,
/// 0..1. `inward` is the side the rays start on: those that would leave through that plane
/// are mirrored back inside.
float thicknessFrom(const Context& ctx, const vec3& point, const vec3& inward, const vec3& normal, std::uint64_t seed,
                    int samples, Counters& counters) {
  const vec3 p = point + ctx.epsilon * inward;
  const CosineSet set(-normal, mix(seed ^ kThicknessStream), samples);
  const int k = set.size();
  const float cap = ctx.thicknessDistance;
  float sum = 0.0f;
  for (int i = 0; i < k; ++i) {
    vec3 d = set[i];
    const float outside = glm::dot(d, inward);
    if (outside < 0.0f) d -= 2.0f * outside * inward;
    const auto hit = ctx.scene.intersect({p, d, 0.0f, cap});
    sum += hit ? std::min(hit->t, cap) : cap;
  }
  counters.thicknessRays += std::uint64_t(k);
  return sum / (float(k) * cap);
}

/// The same at a hit: under its facet, not its smooth normal.
float thicknessAt(const Context& ctx, const Found& f, const vec3& normal, std::uint64_t seed, Counters& counters) {
  return thicknessFrom(ctx, f.ray.at(f.hit->t), -outwardFacet(*f.hit, normal), normal, seed, ctx.options.aoSamples, counters);
}

/// Signed mean curvature at a point p of the high poly with unit normal `normal`, at the
/// scale ctx.curvatureRadius (baker.h, "Maps"): points around p in its tangent plane
/// dropped onto the high poly, each giving the normal curvature towards it from the normals
/// at both ends.
float curvatureFrom(const Context& ctx, const vec3& p, const vec3& normal, std::uint64_t seed, Counters& counters) {
  vec3 t, b;
  const float turn = curvatureFrame(normal, seed, t, b);
  const float step = 2.0f * kPi / float(kCurvaturePoints);
  float sum = 0.0f;
  int found = 0;
  std::uint64_t rays = 0;
  for (int i = 0; i < kCurvaturePoints; ++i) {
    const float angle = turn + step * float(i);
    const vec3 dir = std::cos(angle) * t + std::sin(angle) * b;
    // Where nothing is found (the surface falls away more steeply than 45° within r: a
    // silhouette, a tight bend or the end of an open mesh) the point moves in, up to 3 times.
    float r = ctx.curvatureRadius;
    for (int attempt = 0; attempt < 4; ++attempt, r *= 0.5f) {
      // From r above the tangent plane to r below it; the first surface that faces the
      // hit's way (a wall crossed from behind, e.g. a thin part's far side, is skipped).
      raytrace::Ray ray{p + r * dir + r * normal, -normal, 0.0f, 2.0f * r};
      std::optional<raytrace::Hit> hit;
      for (int crossing = 0; crossing < 3; ++crossing) {
        ++rays;
        hit = ctx.scene.intersect(ray);
        if (!hit || glm::dot(interpolatedHighNormal(ctx, *hit), normal) > 0.0f) break;
        ray.tnear = hit->t + ctx.epsilon;
        hit.reset();
      }
      if (!hit) continue;
      const vec3 e = ray.at(hit->t) - p;
      const float length2 = glm::dot(e, e);
      if (length2 > 0.0f) {
        sum += glm::dot(highNormal(ctx, *hit) - normal, e) / length2;
        ++found;
      }
      break;
    }
  }
  counters.curvatureRays += rays;
  return found ? sum / float(found) : 0.0f;
}

/// The same at a hit.
float curvatureAt(const Context& ctx, const Found& f, const vec3& normal, std::uint64_t seed, Counters& counters) {
  return curvatureFrom(ctx, f.ray.at(f.hit->t), normal, seed, counters);
}

template <typename Measure>
float cachedAtVertex(const VertexCache::Values& values, std::uint32_t v, Counters& counters, const Measure& measure) {
  std::atomic<std::uint8_t>& state = values.state[v];
  std::uint8_t now = state.load(std::memory_order_acquire);
  if (now == kMeasured) return values.value[v];
  if (now == kUnmeasured && state.compare_exchange_strong(now, kMeasuring, std::memory_order_acquire)) {
    values.value[v] = measure();
    ++counters.vertexMeasurements;
    state.store(kMeasured, std::memory_order_release);
    return values.value[v];
  }
  while (state.load(std::memory_order_acquire) != kMeasured) std::this_thread::yield();
  return values.value[v];
}

/// A map's value at a hit on a small triangle: its corners' values, interpolated.
template <typename Measure>
float interpolatedAtHit(const Context& ctx, const VertexCache::Values& values, const raytrace::Hit& hit, Counters& counters,
                        const Measure& measure) {
  const VertexCache& cache = *ctx.vertexCache;
  float corner[3];
  for (std::size_t k = 0; k < 3; ++k) {
    const std::uint32_t v = cache.vertexOfCorner[3 * std::size_t(hit.triangle) + k];
    corner[k] = cachedAtVertex(values, v, counters, [&] {
      const std::uint32_t c = cache.cornerOfVertex[v];
      const vec3 n = glm::normalize(ctx.highCornerNormals[c]);
      return measure(cache.position(c), n, mix(std::uint64_t(v) ^ kVertexStream));
    });
  }
  return (1.0f - hit.u - hit.v) * corner[0] + hit.u * corner[1] + hit.v * corner[2];
}

float thicknessOf(const Context& ctx, const Found& f, const vec3& normal, std::uint64_t seed, Counters& counters) {
  const VertexCache* cache = ctx.vertexCache.get();
  if (!cache || !(cache->small[f.hit->triangle] & VertexCache::kThickness)) return thicknessAt(ctx, f, normal, seed, counters);
  return interpolatedAtHit(ctx, cache->thickness, *f.hit, counters, [&](const vec3& p, const vec3& n, std::uint64_t s) {
    return thicknessFrom(ctx, p, -n, n, s, std::min(kVertexSampleFactor * ctx.options.aoSamples, int(BaseTurns::kCount)), counters);
  });
}

float curvatureOf(const Context& ctx, const Found& f, const vec3& normal, std::uint64_t seed, Counters& counters) {
  const VertexCache* cache = ctx.vertexCache.get();
  if (!cache || !(cache->small[f.hit->triangle] & VertexCache::kCurvature)) return curvatureAt(ctx, f, normal, seed, counters);
  return interpolatedAtHit(ctx, cache->curvature, *f.hit, counters, [&](const vec3& p, const vec3& n, std::uint64_t s) {
    return curvatureFrom(ctx, p, n, s, counters);
  });
}

/// A sample's value in the output space, painted detail applied in tangent space.
void store(const Context& ctx, const Geometry& g, vec3 objectNormal, const SampleInput& in, SampleResult& result) {
  const TangentFrame frame = TangentFrame::fromInterpolated(g.normal, g.tangent);
  vec3 m = ctx.options.space == NormalSpace::Tangent || ctx.options.detail ? frame.encode(objectNormal) : vec3(0, 0, 1);
  if (ctx.options.detail) {
    m = combineDetail(m, detailNormal(*ctx.options.detail, in.uv));
    objectNormal = frame.decode(m);
  }
  switch (ctx.options.space) {
    case NormalSpace::Tangent: result.value = m; break;
    case NormalSpace::Object: result.value = objectNormal; break;
    case NormalSpace::World: result.value = glm::normalize(ctx.worldNormalMatrix * objectNormal); break;
  }
}

/// Many samples' tangent-space values at once, as structure of arrays: the arithmetic of
/// highNormal, TangentFrame::fromInterpolated and TangentFrame::encode in one loop without
/// calls or branches, which the compiler runs four samples per instruction. (Measured: the
/// per-sample version was a third of the baker's own time at one ray per texel.)
struct EncodeLanes {
  std::array<float, kMaxGroup> hx, hy, hz;      ///< high-poly normal, interpolated (not unit; the facet
                                                ///< normal where that has no length)
  std::array<float, kMaxGroup> nx, ny, nz;      ///< low-poly interpolated normal
  std::array<float, kMaxGroup> tx, ty, tz, ts;  ///< low-poly interpolated tangent and sign (±1)
  std::array<float, kMaxGroup> mx, my, mz;      ///< out: the unit tangent-space normal
};

void encodeLanes(EncodeLanes& l, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    // The high poly's unit normal (highNormal). A zero vector (degenerate facet) stays
    // zero and ends up singular below.
    const float hi = 1.0f / std::max(std::sqrt(l.hx[i] * l.hx[i] + l.hy[i] * l.hy[i] + l.hz[i] * l.hz[i]), 1e-30f);
    const float vx = l.hx[i] * hi, vy = l.hy[i] * hi, vz = l.hz[i] * hi;
    // The frame: b = sign · cross(n, t) (fromInterpolated).
    const float nx = l.nx[i], ny = l.ny[i], nz = l.nz[i], tx = l.tx[i], ty = l.ty[i], tz = l.tz[i];
    const float bx = l.ts[i] * (ny * tz - nz * ty), by = l.ts[i] * (nz * tx - nx * tz), bz = l.ts[i] * (nx * ty - ny * tx);
    // Solve [t b n] m = v (encode).
    const float nn = nx * nx + ny * ny + nz * nz, tt = tx * tx + ty * ty + tz * tz, nt = nx * tx + ny * ty + nz * tz;
    const float gram = nn * tt - nt * nt;
    const float vt = vx * tx + vy * ty + vz * tz, vn = vx * nx + vy * ny + vz * nz, vb = vx * bx + vy * by + vz * bz;
    const float mx = nn * vt - nt * vn, my = vb, mz = tt * vn - nt * vt;
    const float ml = std::sqrt(mx * mx + my * my + mz * mz);
    const bool regular = (gram > 1e-12f * nn * tt) & (ml > 0.0f);  // &, not &&: no branch in the loop
    const float mi = 1.0f / std::max(ml, 1e-30f);
    l.mx[i] = regular ? mx * mi : 0.0f;
    l.my[i] = regular ? my * mi : 0.0f;
    l.mz[i] = regular ? mz * mi : 1.0f;
  }
}

}  // namespace

/// An object-space unit vector in the output space (no painted detail).
vec3 inSpace(const Context& ctx, const Geometry& g, const vec3& v) {
  switch (ctx.options.space) {
    case NormalSpace::Tangent: return TangentFrame::fromInterpolated(g.normal, g.tangent).encode(v);
    case NormalSpace::Object: return v;
    case NormalSpace::World: return glm::normalize(ctx.worldNormalMatrix * v);
  }
  return v;
}

SampleResult shade(const Context& ctx, const Geometry& g, const Found& f, const SampleInput& in, Counters& counters,
                   bool deferred) {
  SampleResult result;
  vec3 objectNormal = g.dir;  // a miss keeps the low poly's own normal
  vec3 bent = g.dir;
  if (f.hit) {
    result.hit = true;
    result.height = f.signedT;
    objectNormal = highNormal(ctx, *f.hit);
    result.inward = glm::dot(objectNormal, g.normal) < 0.0f;
    result.triangle = std::int32_t(f.hit->triangle);
    result.hitUv = vec2(f.hit->u, f.hit->v);
    if (ctx.hemisphere && !deferred) {
      const Occlusion o = ambientOcclusion(ctx, f, objectNormal, in.seed, counters);
      result.ao = o.open;
      bent = o.bent;
    }
    if (ctx.baking(Map::Thickness) && !deferred) result.thickness = thicknessOf(ctx, f, objectNormal, in.seed, counters);
    if (ctx.baking(Map::Curvature) && !deferred) result.curvature = curvatureOf(ctx, f, objectNormal, in.seed, counters);
    if (ctx.baking(Map::Position)) result.position = f.ray.at(f.hit->t);
  } else if (ctx.baking(Map::Position)) {
    result.position = g.position;
  }
  store(ctx, g, objectNormal, in, result);
  if (ctx.baking(Map::BentNormal) && !deferred) result.bent = inSpace(ctx, g, bent);
  return result;
}

// One function of ~125 lines on purpose: it is the bake's inner loop, a few stages over
// one group's samples that share the thread's scratch arrays, the sweep direction and the
// front/rear tally. Its layout (rays filled in place, the normals prefetched before the
// lean pass, lanes encoded together) is what the measurements in its comments timed; the
// parts that stand alone (geometryAt, Caster, shade, store, encodeLanes) are functions.
void traceGroup(const Context& ctx, std::span<const SampleInput> samples, std::span<SampleResult> results,
                Counters& counters, std::vector<raytrace::Ray>* rayLog, int& prediction) {
  if (samples.size() > kMaxGroup) fail(ErrorKind::Internal, "bake: a group of {} samples (at most {})", samples.size(), kMaxGroup);
  const Caster caster(ctx, counters, rayLog);
  // Per-sample working data, a stage at a time: simple loops over neighbouring samples let
  // the processor overlap one sample's square roots and divisions with the next. Reused
  // per thread (about 25 KB), not cleared per group.
  struct Scratch {
    std::array<Geometry, kMaxGroup> geometry;
    std::array<raytrace::Ray, kMaxGroup> sweeps;
    std::array<std::optional<raytrace::Hit>, kMaxGroup> hits;
    EncodeLanes lanes;
  };
  thread_local Scratch scratch;
  // Plain references, not a structured binding: lambdas below capture them (clang before 16
  // cannot capture bindings, and the sanitizer and fuzzing builds use clang).
  auto& geometry = scratch.geometry;
  auto& sweeps = scratch.sweeps;
  auto& hits = scratch.hits;
  auto& l = scratch.lanes;
  const std::size_t count = samples.size();
  for (std::size_t i = 0; i < count; ++i) geometryAt(ctx, samples[i].slot, geometry[i]);

  const bool closest = !ctx.options.cage && ctx.options.selection == HitSelection::Closest;
  if (!closest || ctx.front + ctx.rear <= 0.0f) {
    for (std::size_t i = 0; i < count; ++i) {
      Found f;
      if (ctx.options.cage) f = caster.fromCage(geometry[i], samples[i].slot);
      else if (ctx.options.selection == HitSelection::FrontFirst) f = caster.frontFirst(geometry[i]);
      results[i] = shade(ctx, geometry[i], f, samples[i], counters);
    }
    return;
  }

  // Closest |t| on each sample's segment [P − rear·N, P + front·N], starting with one ray
  // per sample that sweeps the whole segment towards the side where the previous group's
  // hits were (usually the only ray needed). The group's sweeps are coherent — neighbouring
  // origins, nearly parallel — so they go to Embree together.
  // A tile's first group has no previous one: its first sample is traced alone to decide.
  // Rays are filled in place, field by field: building a temporary and copying it made the
  // processor wait for partial stores it could not forward (a measured 15 % of this loop).
  const float length = ctx.front + ctx.rear;
  const auto sweepInto = [&](const Geometry& g, bool towardsFront, raytrace::Ray& ray) {
    const vec3 d = (towardsFront ? 1.0f : -1.0f) * g.dir;
    ray.origin = g.position - (towardsFront ? ctx.rear : ctx.front) * d;
    ray.direction = d;
    ray.tnear = 0.0f;
    ray.tfar = length;
  };
  int front = 0, rear = 0;
  const auto resolve = [&](std::size_t i, const raytrace::Ray& sweep, const std::optional<raytrace::Hit>& hit, bool towardsFront) {
    Found f;
    caster.resolve(geometry[i], sweep, hit, towardsFront ? ctx.rear : ctx.front, towardsFront ? 1.0f : -1.0f, f);
    if (f.hit) (f.signedT >= 0.0f ? front : rear) += 1;
    results[i] = shade(ctx, geometry[i], f, samples[i], counters);
  };
  std::size_t first = 0;
  if (prediction == 0 && count > 0) {
    raytrace::Ray sweep;
    sweepInto(geometry[0], true, sweep);
    resolve(0, sweep, caster.cast(sweep), true);
    if (front + rear > 0) prediction = front >= rear ? 1 : -1;
    first = 1;
  }
  const bool towardsFront = prediction >= 0;
  const float side = towardsFront ? 1.0f : -1.0f, before = towardsFront ? ctx.rear : ctx.front;
  const std::size_t n = count - first;
  for (std::size_t i = 0; i < n; ++i) {
    sweepInto(geometry[first + i], towardsFront, sweeps[i]);
    caster.note(sweeps[i]);
  }
  ctx.scene.intersectCoherent(std::span(sweeps).first(n), std::span(hits).first(n));
  // The hit triangles' normals are scattered over a large array: ask for them all now, so
  // the memory fetches overlap instead of stalling each sample in turn.
  for (std::size_t i = 0; i < n; ++i) {
    if (hits[i]) __builtin_prefetch(&ctx.highCornerNormals[3 * std::size_t(hits[i]->triangle)]);
  }
  // The usual case, kept lean: the sweep's first hit is at or beyond P, so it is the
  // closest either way and this one ray decides (Caster::resolve does the rest). For plain
  // tangent-space maps its samples are gathered into lanes and encoded together.
  const bool lean = !ctx.hitWork;
  const bool lanes = ctx.options.space == NormalSpace::Tangent && !ctx.options.detail;
  std::array<std::uint8_t, kMaxGroup> laneOf;  // sample i → lane, for the samples in lanes
  std::size_t laneCount = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::optional<raytrace::Hit>& hit = hits[i];
    const std::size_t k = first + i;
    if (!lean || !hit || hit->t < before) {
      resolve(k, sweeps[i], hit, towardsFront);
      continue;
    }
    SampleResult& r = results[k];
    r.ao = 1.0f;
    r.hit = true;
    r.height = side * (hit->t - before);
    if (ctx.baking(Map::Position)) r.position = sweeps[i].at(hit->t);
    (r.height >= 0.0f ? front : rear) += 1;
    if (!lanes) {
      const vec3 high = highNormal(ctx, *hit);
      r.inward = glm::dot(high, geometry[k].normal) < 0.0f;
      store(ctx, geometry[k], high, samples[k], r);
      continue;
    }
    const std::size_t j = laneCount++;
    laneOf[i] = std::uint8_t(j);
    const vec3 h = interpolatedHighNormal(ctx, *hit);
    r.inward = glm::dot(h, geometry[k].normal) < 0.0f;
    l.hx[j] = h.x;
    l.hy[j] = h.y;
    l.hz[j] = h.z;
    const Geometry& g = geometry[k];
    l.nx[j] = g.normal.x;
    l.ny[j] = g.normal.y;
    l.nz[j] = g.normal.z;
    l.tx[j] = g.tangent.x;
    l.ty[j] = g.tangent.y;
    l.tz[j] = g.tangent.z;
    l.ts[j] = g.tangent.w < 0.0f ? -1.0f : 1.0f;
  }
  if (laneCount > 0) {
    encodeLanes(l, laneCount);
    for (std::size_t i = 0; i < n; ++i) {
      const std::optional<raytrace::Hit>& hit = hits[i];
      if (!lean || !hit || hit->t < before) continue;
      const std::size_t j = laneOf[i];
      results[first + i].value = vec3(l.mx[j], l.my[j], l.mz[j]);
    }
  }
  if (front + rear > 0) prediction = front >= rear ? 1 : -1;
}


std::unique_ptr<VertexCache> buildVertexCache(const Context& ctx, const Mesh& mesh) {
  const bool thickness = ctx.baking(Map::Thickness), curvature = ctx.baking(Map::Curvature);
  if (!thickness && !curvature) return nullptr;
  const std::size_t triangles = mesh.triangleCount();
  // Worth it only where a bake's samples outnumber the vertices: a vertex's thickness costs
  // kVertexSampleFactor samples' rays, its curvature one sample's. A map keeps the cache when
  // the samples (at most width × height × samples, every texel covered) are at least twice
  // what measuring every vertex would cost. A closed mesh has about half as many vertices
  // as triangles: below that, nothing is joined.
  const double samples = double(ctx.options.width) * double(ctx.options.height) * double(ctx.options.samples);
  const auto worth = [&](double vertices, bool forThickness) {
    return samples >= 2.0 * (forThickness ? double(kVertexSampleFactor) : 1.0) * vertices;
  };
  if (!(thickness && worth(0.5 * double(triangles), true)) && !(curvature && worth(0.5 * double(triangles), false))) return nullptr;
  auto cache = std::make_unique<VertexCache>();
  cache->mesh = &mesh;
  cache->small.assign(triangles, 0);
  // "Small": the longest edge at most half the scale (VertexCache). Measured on the studded
  // torus of `glint bench bake` at 512², against the same maps measured at every texel:
  // curvature differs by 1.0e-4 on average (of the 8/16-bit range), thickness by 7.0e-4
  // from a 256-ray-per-texel reference, where 16 rays per texel are 1.2e-3 off.
  const float fraction = 0.5f;
  const float thicknessLimit = thickness ? fraction * ctx.thicknessDistance : 0.0f;
  const float curvatureLimit = curvature ? fraction * ctx.curvatureRadius : 0.0f;
  std::atomic<std::size_t> smallCount{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    std::size_t count = 0;
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const vec3 a = cache->position(std::uint32_t(3 * t)), b = cache->position(std::uint32_t(3 * t + 1)),
                 c = cache->position(std::uint32_t(3 * t + 2));
      const float longest = std::sqrt(std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)}));
      bool normals = std::isfinite(longest);
      for (std::size_t k = 0; k < 3; ++k) {
        const vec3& n = ctx.highCornerNormals[3 * t + k];
        normals = normals && std::isfinite(n.x + n.y + n.z) && glm::dot(n, n) > 0.0f;
      }
      if (!normals) continue;
      const std::uint8_t bits = std::uint8_t((longest <= thicknessLimit ? VertexCache::kThickness : 0) |
                                             (longest <= curvatureLimit ? VertexCache::kCurvature : 0));
      cache->small[t] = bits;
      count += bits != 0;
    }
    smallCount += count;
  });
  if (smallCount == 0) return nullptr;
  // Corners joined by exact position and normal.
  struct Key {
    std::array<std::uint32_t, 6> bits;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0;
      for (std::uint32_t b : k.bits) h = mix(h ^ b);
      return std::size_t(h);
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> ids;
  ids.reserve(triangles * 3 / 2);
  cache->vertexOfCorner.resize(3 * triangles);
  for (std::size_t c = 0; c < 3 * triangles; ++c) {
    const vec3 p = cache->position(std::uint32_t(c)), &n = ctx.highCornerNormals[c];
    const Key key{{std::bit_cast<std::uint32_t>(p.x), std::bit_cast<std::uint32_t>(p.y), std::bit_cast<std::uint32_t>(p.z),
                   std::bit_cast<std::uint32_t>(n.x), std::bit_cast<std::uint32_t>(n.y), std::bit_cast<std::uint32_t>(n.z)}};
    const auto [it, added] = ids.try_emplace(key, std::uint32_t(cache->cornerOfVertex.size()));
    if (added) cache->cornerOfVertex.push_back(std::uint32_t(c));
    cache->vertexOfCorner[c] = it->second;
  }
  const std::size_t vertices = cache->cornerOfVertex.size();
  const std::uint8_t keep = std::uint8_t((thickness && worth(double(vertices), true) ? VertexCache::kThickness : 0) |
                                         (curvature && worth(double(vertices), false) ? VertexCache::kCurvature : 0));
  if (keep == 0) return nullptr;
  for (std::uint8_t& bits : cache->small) bits &= keep;
  for (VertexCache::Values* values : {&cache->thickness, &cache->curvature}) {
    values->state = std::make_unique<std::atomic<std::uint8_t>[]>(vertices);  // value-initialized: unmeasured
    values->value = std::make_unique<float[]>(vertices);
  }
  return cache;
}

}  // namespace glint::bake::detail
