// Rays and shading for the samples of one texel: where the low poly is, which high-poly
// hit counts (closest |t|, front first, or through the cage), and what is stored.
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

/// Per-texel random streams that do not depend on scheduling: core/hash.h's hash64.
constexpr std::uint64_t mix(std::uint64_t x) { return hash64(x); }
constexpr float toUnit(std::uint64_t x) { return unitFloat(x); }
/// The random streams of thickness, curvature and a vertex's measurement: each sample's seed
/// mixed with one of these.
constexpr std::uint64_t kThicknessStream = 0x7468696E6B6E6573ull, kCurvatureStream = 0x6375727661747572ull,
                        kVertexStream = 0x766572746578ull;

/// The low poly at a sample: position, interpolated frame, ray direction.
struct Geometry {
  vec3 position{0.0f};
  vec3 normal{0.0f};  ///< interpolated, not normalized: the shader's frame
  vec4 tangent{0.0f};
  vec3 dir{0.0f, 0.0f, 1.0f};  ///< the normal, normalized: the ray direction
};

/// Written in place, field by field: see sweepInto.
void geometryAt(const Context& ctx, const Slot& slot, Geometry& g) {
  const Context::LowCorners& c = ctx.lowCorners[std::size_t(slot.tri)];
  const float w0 = 1.0f - slot.w.x - slot.w.y;
  const auto lerp = [&](const auto& corner) { return w0 * corner[0] + slot.w.x * corner[1] + slot.w.y * corner[2]; };
  const Context::Float4 p = lerp(c.position), n = lerp(c.normal), t = lerp(c.tangent);
  g.position = vec3(p[0], p[1], p[2]);
  g.normal = vec3(n[0], n[1], n[2]);
  g.tangent = vec4(t[0], t[1], t[2], t[3]);
  const float len = glm::length(g.normal);
  g.dir = len > 0.0f ? g.normal * (1.0f / len) : vec3(0.0f, 0.0f, 1.0f);
}

/// The hit a sample settled on, the ray that found it, and the signed distance from the
/// low poly along its normal (+ in front).
struct Found {
  std::optional<raytrace::Hit> hit;
  raytrace::Ray ray;
  float signedT = 0.0f;
};

class Caster {
public:
  Caster(const Context& ctx, Counters& counters, std::vector<raytrace::Ray>* log)
      : m_ctx(ctx), m_counters(counters), m_log(log) {}

  void note(const raytrace::Ray& r) const {
    ++m_counters.rays;
    if (m_log) m_log->push_back(r);
  }
  std::optional<raytrace::Hit> cast(const raytrace::Ray& r) const {
    note(r);
    return m_ctx.scene.intersect(r);
  }
  /// The scene is built for speed, not watertightness: a ray exactly through a shared
  /// vertex or edge can slip between triangles. A primary ray that finds nothing is cast
  /// once more, moved sideways by a hair (deterministic, rare, far below a texel).
  std::optional<raytrace::Hit> retry(const raytrace::Ray& r, const Geometry& g) const {
    vec3 side = vec3(g.tangent) - glm::dot(vec3(g.tangent), g.dir) * g.dir;
    const float len = glm::length(side);
    side = len > 0.0f ? side / len : (std::fabs(g.dir.x) < 0.9f ? glm::normalize(glm::cross(g.dir, vec3(1, 0, 0)))
                                                                 : glm::normalize(glm::cross(g.dir, vec3(0, 1, 0))));
    raytrace::Ray nudged = r;
    nudged.origin += m_ctx.epsilon * side;
    return cast(nudged);
  }

  /// Closest |t|, given the sweep that started `before` behind P (along ±normal, `side`)
  /// and its hit. If the hit is at or beyond P nothing lies between the sweep's start and
  /// P: it is the closest. Otherwise the hit behind P bounds a short ray back from P, and
  /// that ray's hit bounds a last one forward.
  void resolve(const Geometry& g, const raytrace::Ray& sweep, const std::optional<raytrace::Hit>& sweepHit, float before,
               float side, Found& f) const {
    f.ray = sweep;
    f.hit = sweepHit ? sweepHit : retry(sweep, g);
    if (!f.hit) return;
    if (f.hit->t >= before) {
      f.signedT = side * (f.hit->t - before);
      return;
    }
    float behind = before - f.hit->t;
    const raytrace::Ray back{g.position, -sweep.direction, 0.0f, behind};
    if (const auto closer = cast(back)) {  // (rounding may lose the sweep's own hit: keep it then)
      f.hit = closer;
      f.ray = back;
      behind = closer->t;
    }
    f.signedT = -side * behind;
    if (behind > 0.0f) {
      const raytrace::Ray ahead{g.position, sweep.direction, 0.0f, behind};
      if (const auto front = cast(ahead); front && front->t < behind) {
        f.hit = front;
        f.ray = ahead;
        f.signedT = side * front->t;
      }
    }
  }

  /// `given`: the first ray's hit, traced elsewhere (the GPU: firstRay's ray); null: cast here.
  Found frontFirst(const Geometry& g, const std::optional<raytrace::Hit>* given = nullptr) const {
    Found f;
    const raytrace::Ray front{g.position, g.dir, 0.0f, m_ctx.front};
    if (m_ctx.front > 0.0f && ((f.hit = given ? *given : cast(front)) || (f.hit = retry(front, g)))) {
      f.ray = front;
      f.signedT = f.hit->t;
    } else if (m_ctx.rear > 0.0f) {
      f.ray = {g.position, -g.dir, 0.0f, m_ctx.rear};
      if ((f.hit = given && m_ctx.front <= 0.0f ? *given : cast(f.ray)) || (f.hit = retry(f.ray, g))) f.signedT = -f.hit->t;
    }
    return f;
  }

  /// From the cage towards the low poly: the ray, and its length to the low poly (0: the
  /// cage touches it there, and the ray is the rear one).
  raytrace::Ray cageRay(const Geometry& g, const Slot& slot, float& toLowLength) const {
    const auto& ci = m_ctx.in.originalIndices;
    const auto& cp = m_ctx.options.cage->positions;
    const std::size_t base = 3 * std::size_t(slot.tri);
    const vec3 origin = (1.0f - slot.w.x - slot.w.y) * cp[ci[base]] + slot.w.x * cp[ci[base + 1]] + slot.w.y * cp[ci[base + 2]];
    const vec3 toLow = g.position - origin;
    const float len = glm::length(toLow);
    const bool apart = len > 1e-7f * m_ctx.in.diagonal;
    toLowLength = apart ? len : 0.0f;
    return apart ? raytrace::Ray{origin, toLow / len, 0.0f, len + m_ctx.rear} : raytrace::Ray{g.position, -g.dir, 0.0f, m_ctx.rear};
  }

  /// From the cage towards the low poly, first hit, up to maxRear beyond it.
  Found fromCage(const Geometry& g, const Slot& slot, const std::optional<raytrace::Hit>* given = nullptr) const {
    Found f;
    float len = 0.0f;
    f.ray = cageRay(g, slot, len);
    f.hit = given ? *given : cast(f.ray);
    if (!f.hit) f.hit = retry(f.ray, g);
    if (f.hit) f.signedT = len > 0.0f ? len - f.hit->t : -f.hit->t;
    return f;
  }

private:
  const Context& m_ctx;
  Counters& m_counters;
  std::vector<raytrace::Ray>* m_log;
};

/// The turns of the hemisphere sets, shared with the GPU's (raytrace/jobs.h).
using BaseTurns = raytrace::HemisphereTurns;
const BaseTurns& baseTurns() { return raytrace::hemisphereTurns(); }

/// A stratified set of `count` cosine-weighted directions around `axis`: a Hammersley set
/// rotated by the random offsets (r1, r2) of one sample's stream (deterministic). The
/// offset r2 of the turn is a rotation by 2π·r2 of every direction around the axis, applied
/// as one rotation to the precomputed turns (no sine or cosine per ray).
class CosineSet {
public:
  CosineSet(const vec3& axis, std::uint64_t stream, int count) : m_n(axis), m_k(count) {
    const vec3 a = std::fabs(axis.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
    const vec3 t = glm::normalize(glm::cross(a, axis)), b = glm::cross(axis, t);
    m_r1 = toUnit(mix(stream * 2 + 1));
    const float turn = 2.0f * kPi * toUnit(mix(stream * 2 + 2));
    const float c = std::cos(turn), s = std::sin(turn);
    // (cos φ, sin φ) in the frame (t, b) turned by `turn` is (cos φ, sin φ) in (t', b').
    m_t = c * t + s * b;
    m_b = c * b - s * t;
  }
  int size() const { return m_k; }
  /// The set as a GPU job (bake/gpu_backend.h): its frame, offset and count.
  HemisphereJob job(const vec3& origin, const vec3& mirror, float distance, bool closest) const {
    return {.origin = origin, .r1 = m_r1, .tangent = m_t, .distance = distance, .bitangent = m_b,
            .count = std::uint32_t(m_k), .axis = m_n, .closest = closest ? 1u : 0u, .mirror = mirror};
  }
  vec3 operator[](int i) const {
    float u1 = (float(i) + 0.5f) / float(m_k) + m_r1;
    if (u1 >= 1.0f) u1 -= 1.0f;
    const BaseTurns& turns = baseTurns();
    const std::uint32_t j = std::uint32_t(i);
    const float r = std::sqrt(u1);
    return r * turns.cosine[j] * m_t + r * turns.sine[j] * m_b + std::sqrt(std::max(0.0f, 1.0f - u1)) * m_n;
  }

private:
  vec3 m_t, m_b, m_n;
  int m_k;
  float m_r1 = 0;
};

/// The facet normal at a hit, turned to the side of the (smooth) `normal`.
vec3 outwardFacet(const raytrace::Hit& hit, const vec3& normal) {
  const vec3 g = hit.geometricNormal;
  return glm::dot(g, normal) < 0.0f ? -g : g;
}

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

/// The high poly's interpolated normal at a hit, not normalized; its facet normal where the
/// interpolation has no length (opposite corner normals).
vec3 interpolatedHighNormal(const Context& ctx, const raytrace::Hit& hit) {
  const vec3* corner = &ctx.highCornerNormals[3 * std::size_t(hit.triangle)];
  const vec3 n = (1.0f - hit.u - hit.v) * corner[0] + hit.u * corner[1] + hit.v * corner[2];
  return n == vec3(0.0f) ? hit.geometricNormal : n;
}

/// The same, unit length.
vec3 highNormal(const Context& ctx, const raytrace::Hit& hit) {
  const vec3 n = interpolatedHighNormal(ctx, hit);
  const float len = glm::length(n);
  return len > 0.0f ? n * (1.0f / len) : n;
}

/// Points curvatureAt measures around a hit: evenly spaced, so opposite pairs cancel the
/// first-order error and the mean of the normal curvatures κ1 cos²θ + κ2 sin²θ is exactly
/// (κ1 + κ2) / 2 whatever the turn.
constexpr int kCurvaturePoints = 8;

/// The plane curvatureFrom measures in (t, b: unit, around `normal`) and its turn.
float curvatureFrame(const vec3& normal, std::uint64_t seed, vec3& t, vec3& b) {
  const vec3 a = std::fabs(normal.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
  t = glm::normalize(glm::cross(a, normal));
  b = glm::cross(normal, t);
  // A random turn per sample (its own stream): detail finer than the radius averages out
  // instead of printing the same 8 directions' pattern into every texel.
  return toUnit(mix(seed ^ kCurvatureStream)) * (2.0f * kPi / float(kCurvaturePoints));
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

// Vertex cache (trace.h, VertexCache): a vertex's value is measured by the first sample
// that needs it, exactly once (the others wait the few microseconds it takes), so the
// values and the ray counts do not depend on which thread got there first.
enum : std::uint8_t { kUnmeasured = 0, kMeasuring = 1, kMeasured = 2 };

/// A vertex's thickness takes this many times --ao-samples rays: its value stands for every
/// texel around it, so its noise would show as blotches the size of a triangle where the
/// same rays per texel show as grain (seen on the studded torus); four times the rays halve
/// that noise, and a vertex still costs far fewer rays than the texels it serves.
constexpr int kVertexSampleFactor = 4;

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

/// An object-space unit vector in the output space (no painted detail).
vec3 inSpace(const Context& ctx, const Geometry& g, const vec3& v) {
  switch (ctx.options.space) {
    case NormalSpace::Tangent: return TangentFrame::fromInterpolated(g.normal, g.tangent).encode(v);
    case NormalSpace::Object: return v;
    case NormalSpace::World: return glm::normalize(ctx.worldNormalMatrix * v);
  }
  return v;
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

/// `deferred`: the hit's own rays (AO, bent normal, thickness, curvature) are left to the
/// GPU's wave (traceWave), which also stores the bent normal.
SampleResult shade(const Context& ctx, const Geometry& g, const Found& f, const SampleInput& in, Counters& counters,
                   bool deferred = false) {
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

}  // namespace

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


// ------------------------------------------------------------------ the GPU's waves

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

}  // namespace

void traceWave(const Context& ctx, std::span<const SampleInput> samples, std::span<SampleResult> results, Counters& counters) {
  if (!ctx.gpu) fail(ErrorKind::Internal, "bake: a GPU wave without a GPU scene");
  const std::size_t n = samples.size();
  const std::size_t chunks = (n + kWaveChunk - 1) / kWaveChunk;
  std::vector<Counters> chunkCounters(chunks);
  const auto forChunks = [&](const auto& body) {
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
      body(c, c * kWaveChunk, std::min(n, (c + 1) * kWaveChunk), Caster(ctx, chunkCounters[c], nullptr));
    });
  };
  // 1–2. First rays, traced on the GPU.
  std::vector<Geometry> geometry(n);
  std::vector<raytrace::Ray> rays(n);
  forChunks([&](std::size_t, std::size_t begin, std::size_t end, const Caster& caster) {
    firstRays(ctx, samples, begin, end, geometry, rays, caster);
  });
  std::vector<std::optional<raytrace::Hit>> hits(n);
  ctx.gpu->closest(rays, hits);

  // 3. Each sample's hit settled as the CPU settles it (the rare second rays — behind P, a
  // retry — on the CPU's BVH), the sample shaded, and its hit work written as GPU jobs.
  const bool closest = !ctx.options.cage && ctx.options.selection == HitSelection::Closest;
  const VertexCache* cache = ctx.vertexCache.get();
  const bool thickness = ctx.baking(Map::Thickness), curvature = ctx.baking(Map::Curvature);
  std::vector<Found> found(n);
  std::vector<WaveWork> work(n);
  std::vector<WaveJobs> jobs(chunks);
  forChunks([&](std::size_t c, std::size_t begin, std::size_t end, const Caster& caster) {
    Counters& cc = chunkCounters[c];
    WaveJobs& out = jobs[c];
    for (std::size_t i = begin; i < end; ++i) {
      const Geometry& g = geometry[i];
      Found& f = found[i];
      const bool traced = rays[i].tnear <= rays[i].tfar;
      if (ctx.options.cage) f = caster.fromCage(g, samples[i].slot, &hits[i]);
      else if (!closest && traced) f = caster.frontFirst(g, &hits[i]);
      else if (closest && traced) caster.resolve(g, rays[i], hits[i], ctx.rear, 1.0f, f);
      results[i] = shade(ctx, g, f, samples[i], cc, true);
      if (!f.hit) continue;
      const vec3 normal = highNormal(ctx, *f.hit);
      const std::uint64_t seed = samples[i].seed;
      if (ctx.hemisphere) {
        work[i].ao = std::int32_t(out.hemisphere.size());
        out.hemisphere.push_back(aoJob(ctx, f, normal, seed));
        cc.aoRays += std::uint64_t(ctx.options.aoSamples);
      }
      if (thickness && cache && (cache->small[f.hit->triangle] & VertexCache::kThickness)) {
        claimVertices(*cache, cache->thickness, f.hit->triangle, out.thicknessVertices);
      } else if (thickness) {
        work[i].thickness = std::int32_t(out.hemisphere.size());
        out.hemisphere.push_back(
            thicknessJob(ctx, f.ray.at(f.hit->t), -outwardFacet(*f.hit, normal), normal, seed, ctx.options.aoSamples));
        cc.thicknessRays += std::uint64_t(ctx.options.aoSamples);
      }
      if (curvature && cache && (cache->small[f.hit->triangle] & VertexCache::kCurvature)) {
        claimVertices(*cache, cache->curvature, f.hit->triangle, out.curvatureVertices);
      } else if (curvature) {
        work[i].curvature = std::int32_t(out.curvature.size());
        out.curvature.push_back(curvatureJob(ctx, f.ray.at(f.hit->t), normal, seed));
      }
    }
  });

  // 4. The jobs in one list per kernel: the chunks' in order, then the vertices claimed.
  std::vector<HemisphereJob> hemisphere;
  std::vector<CurvatureJob> curvatureJobs;
  std::vector<std::size_t> hemisphereFirst(chunks), curvatureFirst(chunks);
  for (std::size_t c = 0; c < chunks; ++c) {
    hemisphereFirst[c] = hemisphere.size();
    curvatureFirst[c] = curvatureJobs.size();
    hemisphere.insert(hemisphere.end(), jobs[c].hemisphere.begin(), jobs[c].hemisphere.end());
    curvatureJobs.insert(curvatureJobs.end(), jobs[c].curvature.begin(), jobs[c].curvature.end());
  }
  const int vertexSamples = std::min(kVertexSampleFactor * ctx.options.aoSamples, int(BaseTurns::kCount));
  const std::size_t thicknessVertexFirst = hemisphere.size(), curvatureVertexFirst = curvatureJobs.size();
  std::vector<std::uint32_t> thicknessVertices, curvatureVertices;
  for (const WaveJobs& j : jobs) {
    thicknessVertices.insert(thicknessVertices.end(), j.thicknessVertices.begin(), j.thicknessVertices.end());
    curvatureVertices.insert(curvatureVertices.end(), j.curvatureVertices.begin(), j.curvatureVertices.end());
  }
  for (const std::uint32_t v : thicknessVertices) {  // (as interpolatedAtHit measures a vertex)
    const std::uint32_t corner = cache->cornerOfVertex[v];
    const vec3 normal = glm::normalize(ctx.highCornerNormals[corner]);
    hemisphere.push_back(thicknessJob(ctx, cache->position(corner), -normal, normal, mix(std::uint64_t(v) ^ kVertexStream),
                                      vertexSamples));
  }
  for (const std::uint32_t v : curvatureVertices) {
    const std::uint32_t corner = cache->cornerOfVertex[v];
    const vec3 normal = glm::normalize(ctx.highCornerNormals[corner]);
    curvatureJobs.push_back(curvatureJob(ctx, cache->position(corner), normal, mix(std::uint64_t(v) ^ kVertexStream)));
  }

  // 5. The hit work on the GPU.
  std::vector<HemisphereSum> hemisphereSums(hemisphere.size());
  std::vector<CurvatureSum> curvatureSums(curvatureJobs.size());
  ctx.gpu->hemisphere(hemisphere, hemisphereSums);
  ctx.gpu->curvature(curvatureJobs, ctx.epsilon, curvatureSums);

  // 6. The vertices' values, then every sample finished as shade() would have.
  const float thicknessScale = 1.0f / (float(vertexSamples) * ctx.thicknessDistance);
  for (std::size_t k = 0; k < thicknessVertices.size(); ++k) {
    cache->thickness.value[thicknessVertices[k]] = hemisphereSums[thicknessVertexFirst + k].value * thicknessScale;
    cache->thickness.state[thicknessVertices[k]].store(kMeasured, std::memory_order_relaxed);
    counters.thicknessRays += std::uint64_t(vertexSamples);
  }
  for (std::size_t k = 0; k < curvatureVertices.size(); ++k) {
    const CurvatureSum& sum = curvatureSums[curvatureVertexFirst + k];
    cache->curvature.value[curvatureVertices[k]] = sum.found ? sum.sum / float(sum.found) : 0.0f;
    cache->curvature.state[curvatureVertices[k]].store(kMeasured, std::memory_order_relaxed);
    counters.curvatureRays += sum.rays;
  }
  counters.vertexMeasurements += thicknessVertices.size() + curvatureVertices.size();
  forChunks([&](std::size_t c, std::size_t begin, std::size_t end, const Caster&) {
    Counters& cc = chunkCounters[c];
    for (std::size_t i = begin; i < end; ++i) {
      SampleResult& r = results[i];
      const Found& f = found[i];
      vec3 bent = geometry[i].dir;
      if (f.hit) {
        const vec3 normal = highNormal(ctx, *f.hit);
        if (work[i].ao >= 0) {
          const HemisphereSum& sum = hemisphereSums[hemisphereFirst[c] + std::size_t(work[i].ao)];
          const float len = glm::length(sum.directions);
          r.ao = sum.value / float(ctx.options.aoSamples);
          bent = sum.value > 0.0f && len > 0.0f ? sum.directions * (1.0f / len) : normal;
        }
        if (work[i].thickness >= 0) {
          r.thickness = hemisphereSums[hemisphereFirst[c] + std::size_t(work[i].thickness)].value /
                        (float(ctx.options.aoSamples) * ctx.thicknessDistance);
        } else if (thickness) {
          r.thickness = cachedAtHit(*cache, cache->thickness, *f.hit);
        }
        if (work[i].curvature >= 0) {
          const CurvatureSum& sum = curvatureSums[curvatureFirst[c] + std::size_t(work[i].curvature)];
          r.curvature = sum.found ? sum.sum / float(sum.found) : 0.0f;
          cc.curvatureRays += sum.rays;
        } else if (curvature) {
          r.curvature = cachedAtHit(*cache, cache->curvature, *f.hit);
        }
      }
      if (ctx.baking(Map::BentNormal)) r.bent = inSpace(ctx, geometry[i], bent);
    }
  });
  for (const Counters& c : chunkCounters) {
    counters.rays += c.rays;
    counters.aoRays += c.aoRays;
    counters.thicknessRays += c.thicknessRays;
    counters.curvatureRays += c.curvatureRays;
  }
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
