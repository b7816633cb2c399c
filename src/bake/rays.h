#pragma once
// Private to the baker: the pieces of a sample's rays that the CPU's groups (trace.cpp,
// traceGroup) and the GPU's waves (wave.cpp, traceWave) share — where the low poly is, the
// hit a sample settles on and the casts that settle it, the stratified hemisphere sets, the
// high poly's normal at a hit — so that both cast the same rays and shade the same way.
#include "glint/bake/gpu_backend.h"
#include "glint/core/hash.h"
#include "glint/raytrace/jobs.h"
#include "trace.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace glint::bake::detail {

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

// Not inlined (nor interpolatedHighNormal): inlined into traceGroup's loops they made the
// CPU bake's tracing 5 % slower (0.255 s against 0.243 s, the 2048² torus as in baker.cpp).
/// Written in place, field by field: see sweepInto.
[[gnu::noinline]] inline void geometryAt(const Context& ctx, const Slot& slot, Geometry& g) {
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
inline const BaseTurns& baseTurns() { return raytrace::hemisphereTurns(); }

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
inline vec3 outwardFacet(const raytrace::Hit& hit, const vec3& normal) {
  const vec3 g = hit.geometricNormal;
  return glm::dot(g, normal) < 0.0f ? -g : g;
}

/// The high poly's interpolated normal at a hit, not normalized; its facet normal where the
/// interpolation has no length (opposite corner normals).
[[gnu::noinline]] inline vec3 interpolatedHighNormal(const Context& ctx, const raytrace::Hit& hit) {
  const vec3* corner = &ctx.highCornerNormals[3 * std::size_t(hit.triangle)];
  const vec3 n = (1.0f - hit.u - hit.v) * corner[0] + hit.u * corner[1] + hit.v * corner[2];
  return n == vec3(0.0f) ? hit.geometricNormal : n;
}

/// The same, unit length.
inline vec3 highNormal(const Context& ctx, const raytrace::Hit& hit) {
  const vec3 n = interpolatedHighNormal(ctx, hit);
  const float len = glm::length(n);
  return len > 0.0f ? n * (1.0f / len) : n;
}

/// Points curvatureAt measures around a hit: evenly spaced, so opposite pairs cancel the
/// first-order error and the mean of the normal curvatures κ1 cos²θ + κ2 sin²θ is exactly
/// (κ1 + κ2) / 2 whatever the turn.
constexpr int kCurvaturePoints = 8;

/// The plane curvatureFrom measures in (t, b: unit, around `normal`) and its turn.
inline float curvatureFrame(const vec3& normal, std::uint64_t seed, vec3& t, vec3& b) {
  const vec3 a = std::fabs(normal.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
  t = glm::normalize(glm::cross(a, normal));
  b = glm::cross(normal, t);
  // A random turn per sample (its own stream): detail finer than the radius averages out
  // instead of printing the same 8 directions' pattern into every texel.
  return toUnit(mix(seed ^ kCurvatureStream)) * (2.0f * kPi / float(kCurvaturePoints));
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

/// An object-space unit vector in the output space (no painted detail).
vec3 inSpace(const Context& ctx, const Geometry& g, const vec3& v);

/// A sample's result from its settled hit: the normal (and painted detail) in the output
/// space, height, position and the hit itself, and the hit's own rays (AO, bent normal,
/// thickness, curvature) unless `deferred`: then the GPU's wave (traceWave) casts those
/// and stores the bent normal.
SampleResult shade(const Context& ctx, const Geometry& g, const Found& f, const SampleInput& in, Counters& counters,
                   bool deferred = false);

}  // namespace glint::bake::detail
