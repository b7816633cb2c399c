// The bake loop: UV-space tiles in parallel; in each, the low poly's triangles are
// rasterized at the sample positions, rays are cast for every covered sample and the
// results averaged per texel. Tiles are independent, so the output does not depend on
// the thread count.
#include "glint/bake/baker.h"

#include "glint/bake/dilate.h"
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"
#include "glint/mesh/tangents.h"
#include "glint/raytrace/raytracer.h"
#include "internal.h"
#include "parts_internal.h"
#include "scene_cache_internal.h"
#include "trace.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <functional>
#include <optional>
#include <ctime>
#include <span>
#include <utility>

namespace glint::bake {
namespace {

using detail::Context;
using detail::Counters;
using detail::Slot;
using detail::UvTriangle;

using Clock = std::chrono::steady_clock;

/// Denormal floats flushed to zero (FTZ) and read as zero (DAZ) for a scope, the mode
/// Embree asks its callers for: its kernels slow down when a denormal turns up in a box
/// or triangle test. The thread's own mode comes back at the end, so oneTBB workers that
/// run other work afterwards see no change.
/// (Elsewhere than x86, a no-op.)
class FlushDenormals {
public:
#if defined(__SSE__)
  FlushDenormals() : m_saved(_mm_getcsr()) { _mm_setcsr(m_saved | kFtz | kDaz); }
  ~FlushDenormals() { _mm_setcsr(m_saved); }
#else
  FlushDenormals() = default;
#endif
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

#if defined(__SSE__)
private:
  static constexpr unsigned kFtz = 0x8000, kDaz = 0x0040;
  unsigned m_saved;
#endif
};
double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }
/// CPU time of the whole process (every thread): throughput per CPU second does not
/// depend on what else the machine is running.
double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

constexpr int kTile = 32;  // texels per tile side: a few hundred rays per task at 1 spp

float edge(const vec2& p, const vec2& q, const vec2& s) { return (q.x - p.x) * (s.y - p.y) - (q.y - p.y) * (s.x - p.x); }

/// Barycentric weights of corners (b, c) at point s.
vec2 barycentric(const UvTriangle& t, const vec2& s) {
  return {edge(t.c, t.a, s) * t.invArea, edge(t.a, t.b, s) * t.invArea};
}

/// Closest point of the triangle to s, as barycentric weights of (b, c).
vec2 closestBarycentric(const UvTriangle& t, const vec2& s) {
  const vec2 w = barycentric(t, s);
  if (w.x >= 0.0f && w.y >= 0.0f && w.x + w.y <= 1.0f) return w;
  // Outside: the closest point is on an edge; try all three and keep the nearest.
  const auto onSegment = [&](const vec2& p, const vec2& q) {
    const vec2 d = q - p;
    const float len2 = glm::dot(d, d);
    const float k = len2 > 0.0f ? std::clamp(glm::dot(s - p, d) / len2, 0.0f, 1.0f) : 0.0f;
    return p + k * d;
  };
  const vec2 candidates[3] = {onSegment(t.a, t.b), onSegment(t.b, t.c), onSegment(t.c, t.a)};
  vec2 best = candidates[0];
  for (const vec2& p : candidates) {
    if (glm::distance(p, s) < glm::distance(best, s)) best = p;
  }
  return glm::clamp(barycentric(t, best), vec2(0.0f), vec2(1.0f));
}

/// Does the triangle overlap the open unit square at `texel` (separating axes)?
bool overlapsTexel(const UvTriangle& t, ivec2 texel) {
  const vec2 lo(texel), hi = lo + vec2(1.0f);
  const vec2 p[3] = {t.a, t.b, t.c};
  for (int axis = 0; axis < 2; ++axis) {
    const float mn = std::min({p[0][axis], p[1][axis], p[2][axis]});
    const float mx = std::max({p[0][axis], p[1][axis], p[2][axis]});
    if (mx <= lo[axis] || mn >= hi[axis]) return false;
  }
  const vec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  for (int e = 0; e < 3; ++e) {
    const vec2 &p0 = p[e], &p1 = p[(e + 1) % 3], &p2 = p[(e + 2) % 3];
    const vec2 n(p0.y - p1.y, p1.x - p0.x);  // edge normal
    const float side = glm::dot(n, p2 - p0);
    float best = -1e30f;
    for (const vec2& c : corners) best = std::max(best, side > 0.0f ? glm::dot(n, c - p0) : -glm::dot(n, c - p0));
    if (best <= 0.0f) return false;
  }
  return true;
}

/// A tile's sample slots (S per texel, row by row): the first triangle (lowest id) of the
/// tile's bin containing a sample owns it. Counts samples inside several triangles.
// (Forced inline here, in storeTexel and in texelInputs: both tile loops call them, and GCC
// otherwise keeps them out of line; measured on a 2048² normal map of the 262k-triangle
// torus, medians of 6 alternating runs: 0.265 s of tracing against 0.244 s inlined.)
[[gnu::always_inline]] inline void placeSamples(const Context& ctx, int x0, int y0, int tw, int th,
                                                const std::vector<int>& bin, std::span<Slot> slots, Counters& counters) {
  const int S = ctx.root * ctx.root;
  for (int id : bin) {
    const UvTriangle& t = ctx.tris[std::size_t(id)];
    const int bx0 = std::max(t.lo.x, x0), bx1 = std::min(t.hi.x, x0 + tw - 1);
    const int by0 = std::max(t.lo.y, y0), by1 = std::min(t.hi.y, y0 + th - 1);
    for (int y = by0; y <= by1; ++y) {
      for (int x = bx0; x <= bx1; ++x) {
        Slot* texelSlots = &slots[std::size_t(((y - y0) * tw + (x - x0)) * S)];
        for (int s = 0; s < S; ++s) {
          const vec2 p = vec2(float(x), float(y)) + ctx.sampleOffsets[std::size_t(s)];
          const vec2 w = barycentric(t, p);
          const float w0 = 1.0f - w.x - w.y;
          if (w.x < 0.0f || w.y < 0.0f || w0 < 0.0f) continue;
          if (texelSlots[s].tri < 0) texelSlots[s] = {id, w};
          else if (std::min({w.x, w.y, w0}) > 1e-4f) ++counters.overlaps;
        }
      }
    }
  }
}

/// Conservative coverage of a texel no sample landed in: a triangle touching the texel
/// gives one sample at its point closest to the texel centre (nearest such triangle; ties
/// to the lowest id), in `slot`. False when no triangle touches it.
bool conservativeSample(const Context& ctx, const std::vector<int>& bin, int x, int y, Slot& slot) {
  const vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
  float bestDistance = 1e30f;
  for (int id : bin) {
    const UvTriangle& t = ctx.tris[std::size_t(id)];
    if (x < t.lo.x || x > t.hi.x || y < t.lo.y || y > t.hi.y || !overlapsTexel(t, {x, y})) continue;
    const vec2 w = closestBarycentric(t, centre);
    const vec2 p = (1.0f - w.x - w.y) * t.a + w.x * t.b + w.y * t.c;
    const float d = glm::distance(p, centre);
    if (d < bestDistance) {
      bestDistance = d;
      slot = {id, w};
    }
  }
  return slot.tri >= 0;
}

/// A texel whose samples are waiting in a group: results [first, first + count).
struct Pending {
  std::size_t texel;
  std::size_t first, count;
  bool conservative;
};

/// The maps beyond normal, AO, height and miss mask for one texel (see baker.h, "Maps"):
/// bent normals averaged and normalized, thickness, curvature and position averaged over the hits.
void storeExtraMaps(const Context& ctx, const Pending& p, std::span<const detail::SampleResult> results,
                    std::size_t hits, float* out) {
  vec3 bent(0.0f), position(0.0f), positionAll(0.0f);
  float thickness = 0.0f, curvature = 0.0f;
  for (std::size_t i = p.first; i < p.first + p.count; ++i) {
    const detail::SampleResult& r = results[i];
    bent += r.bent;
    positionAll += r.position;
    if (r.hit) {
      position += r.position;
      thickness += r.thickness;
      curvature += r.curvature;
    }
  }
  if (ctx.baking(Map::BentNormal)) {
    const float len = glm::length(bent);
    const vec3 b = len > 0.0f ? bent * (1.0f / len) : vec3(0.0f, 0.0f, 1.0f);
    for (int k = 0; k < 3; ++k) out[ctx.channelOf(Map::BentNormal) + k] = b[k];
  }
  if (ctx.baking(Map::Thickness)) out[ctx.channelOf(Map::Thickness)] = hits ? thickness / float(hits) : 0.0f;
  if (ctx.baking(Map::Curvature)) out[ctx.channelOf(Map::Curvature)] = hits ? curvature / float(hits) : 0.0f;
  if (ctx.baking(Map::Position)) {
    const vec3 q = hits ? position / float(hits) : positionAll / float(p.count);
    for (int k = 0; k < 3; ++k) out[ctx.channelOf(Map::Position) + k] = q[k];
  }
  if (ctx.baking(Map::Opacity)) out[ctx.channelOf(Map::Opacity)] = float(hits) / float(ctx.root * ctx.root);
}

/// The texel's samples averaged into ctx.texels (the normal normalized), and counted.
[[gnu::always_inline]] inline void storeTexel(Context& ctx, const Pending& p, std::span<const detail::SampleResult> results,
                                              Counters& counters) {
  vec3 sum(0.0f);
  float ao = 0.0f, height = 0.0f;
  std::size_t missed = 0;
  for (std::size_t i = p.first; i < p.first + p.count; ++i) {
    const detail::SampleResult& r = results[i];
    sum += r.value;
    ao += r.ao;
    height += r.height;
    missed += r.hit ? 0 : 1;
    counters.inward += r.inward ? 1 : 0;
  }
  const std::size_t hits = p.count - missed;
  counters.samples += p.count;
  counters.hits += hits;
  counters.misses += missed;
  ++counters.covered;
  counters.conservative += p.conservative ? 1 : 0;
  float* out = &ctx.texels[p.texel * std::size_t(ctx.channels)];
  const float len = p.count == 1 ? 1.0f : glm::length(sum);  // one sample: already unit length
  const vec3 n = len == 1.0f ? sum : len > 0.0f ? sum * (1.0f / len) : vec3(0.0f, 0.0f, 1.0f);
  out[0] = n.x;
  out[1] = n.y;
  out[2] = n.z;
  const float count = float(p.count);
  if (ctx.baking(Map::Ao)) out[ctx.channelOf(Map::Ao)] = ao / count;
  if (ctx.baking(Map::Height)) out[ctx.channelOf(Map::Height)] = height / count;
  if (ctx.baking(Map::MissMask)) out[ctx.channelOf(Map::MissMask)] = float(missed) / count;
  if (ctx.extraMaps) storeExtraMaps(ctx, p, results, hits, out);
  if (ctx.parts) detail::storePartsMaps(ctx, p.texel, results.subspan(p.first, p.count), out);
  ctx.covered[p.texel] = 1;
}

/// A tile's covered texels, row by row: `texel(index, conservative, slots)` for each, its
/// samples' slots at `slots` (ctx.root² of them; tri < 0: not on the low poly).
template <typename Texel>
void forEachTexel(const Context& ctx, int tileIndex, Counters& counters, const Texel& texel) {
  const int W = ctx.options.width, H = ctx.options.height, k = ctx.root, S = k * k;
  const int x0 = (tileIndex % ctx.tilesX) * kTile, y0 = (tileIndex / ctx.tilesX) * kTile;
  const int tw = std::min(kTile, W - x0), th = std::min(kTile, H - y0);
  // Reused per thread: a fresh 32×32×36 buffer per tile would cost page faults and zeroing.
  thread_local std::vector<Slot> slots;
  slots.assign(std::size_t(tw * th * S), Slot{});
  const auto& bin = ctx.bins[std::size_t(tileIndex)];
  placeSamples(ctx, x0, y0, tw, th, bin, slots, counters);
  for (int y = y0; y < y0 + th; ++y) {
    for (int x = x0; x < x0 + tw; ++x) {
      Slot* texelSlots = &slots[std::size_t(((y - y0) * tw + (x - x0)) * S)];
      bool any = false;
      for (int s = 0; s < S && !any; ++s) any = texelSlots[s].tri >= 0;
      if (!any && !conservativeSample(ctx, bin, x, y, texelSlots[0])) continue;
      texel(std::size_t(y) * std::size_t(W) + std::size_t(x), !any, texelSlots);
    }
  }
}

/// A texel's samples as trace inputs, written at `out` (in place, field by field: see
/// traceGroup); returns how many.
[[gnu::always_inline]] inline std::size_t texelInputs(const Context& ctx, std::size_t texel, const Slot* texelSlots,
                                                      detail::SampleInput* out) {
  const int W = ctx.options.width, H = ctx.options.height, S = ctx.root * ctx.root;
  std::size_t count = 0;
  for (int s = 0; s < S; ++s) {
    if (texelSlots[s].tri < 0) continue;
    const UvTriangle& t = ctx.tris[std::size_t(texelSlots[s].tri)];
    const vec2 w = texelSlots[s].w;
    // The UV is only read for painted detail: skip the arithmetic otherwise.
    const vec2 p = ctx.options.detail ? (1.0f - w.x - w.y) * t.a + w.x * t.b + w.y * t.c : vec2(0.0f);
    detail::SampleInput& in = out[count++];
    in.slot = texelSlots[s];
    in.uv = vec2(p.x / float(W), p.y / float(H));
    in.seed = texel * 4096u + std::uint64_t(s);
  }
  return count;
}

void bakeTile(Context& ctx, int tileIndex, Counters& tileCounters, std::vector<raytrace::Ray>* rayLog) {
  // Counted on the stack, stored once: neighbouring tiles' counters share cache lines, and
  // two threads incrementing them per sample would pass those lines back and forth.
  Counters counters;
  int prediction = 0;  // which side of the low poly the hits are on (see traceGroup)
  // Texels are gathered until they hold at least kGroup samples, which are then traced
  // together (coherent groups for Embree's packets, whatever the sample count), and the
  // results averaged back per texel. One group's samples, results and texels are on the
  // stack: no heap, no thread-local lookups in the inner loops. A texel adds at most 64
  // samples (the most --samples allows), which bounds the capacity.
  constexpr std::size_t kGroup = 64, kCapacity = detail::kMaxGroup;
  static_assert(kCapacity >= kGroup + 64);
  std::array<Pending, kCapacity> pending;
  std::array<detail::SampleInput, kCapacity> inputs;
  std::array<detail::SampleResult, kCapacity> results;
  std::size_t pendingCount = 0, inputCount = 0;
  const auto flush = [&] {
    detail::traceGroup(ctx, std::span(inputs).first(inputCount), std::span(results).first(inputCount), counters, rayLog,
                       prediction);
    for (const Pending& p : std::span(pending).first(pendingCount)) storeTexel(ctx, p, results, counters);
    pendingCount = inputCount = 0;
  };
  forEachTexel(ctx, tileIndex, counters, [&](std::size_t texel, bool conservative, const Slot* texelSlots) {
    const std::size_t first = inputCount;
    inputCount += texelInputs(ctx, texel, texelSlots, &inputs[inputCount]);
    pending[pendingCount++] = {texel, first, inputCount - first, conservative};
    if (inputCount >= kGroup) flush();
  });
  if (inputCount > 0) flush();
  tileCounters = counters;
}

/// Channels [first, first + count) of the texels as an image of `type` (row 0 on top when
/// flipRows): `transform` writes a pixel's floats, integer types are quantized row by row.
Image channelImage(const Context& ctx, int first, int count, bool flipRows, PixelType type, const auto& transform) {
  const int W = ctx.options.width, H = ctx.options.height;
  Image image(W, H, count, type);
  const std::size_t rowValues = std::size_t(W) * std::size_t(count);
  const std::span<float> floats = type == PixelType::F32 ? image.pixels<float>() : std::span<float>();
  const std::span<std::uint8_t> bytes = type == PixelType::U8 ? image.pixels<std::uint8_t>() : std::span<std::uint8_t>();
  const std::span<std::uint16_t> words = type == PixelType::U16 ? image.pixels<std::uint16_t>() : std::span<std::uint16_t>();
  // In parallel bands of rows: this runs after the trace, on the critical path.
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 32), [&](const tbb::blocked_range<int>& rows) {
    std::vector<float> scratch(type == PixelType::F32 ? 0 : rowValues);
    for (int y = rows.begin(); y != rows.end(); ++y) {
      const std::size_t row = std::size_t(flipRows ? H - 1 - y : y);  // texels are stored v-up, images top-down
      float* out = type == PixelType::F32 ? &floats[row * rowValues] : scratch.data();
      for (int x = 0; x < W; ++x) {
        const std::size_t texel = std::size_t(y) * std::size_t(W) + std::size_t(x);
        transform(&ctx.texels[texel * std::size_t(ctx.channels) + std::size_t(first)], out + std::size_t(x * count),
                  ctx.covered[texel] != 0);
      }
      if (type == PixelType::U8) quantize(scratch, bytes.subspan(row * rowValues, rowValues));
      if (type == PixelType::U16) quantize(scratch, words.subspan(row * rowValues, rowValues));
    }
  });
  return image;
}

/// The tables the tiles share: sample offsets, ray distances, the high poly's corner
/// normals and the low poly's corners side by side, the channels and the texel storage.
void setUpContext(Context& ctx, BakeStats& stats) {
  const BakeOptions& options = ctx.options;
  const detail::Prepared& in = ctx.in;
  ctx.root = int(std::lround(std::sqrt(double(options.samples))));
  for (int s = 0; s < ctx.root * ctx.root; ++s) {  // stratified: the centres of a root × root grid
    ctx.sampleOffsets.emplace_back((float(s % ctx.root) + 0.5f) / float(ctx.root), (float(s / ctx.root) + 0.5f) / float(ctx.root));
  }
  ctx.front = options.maxFront.resolve(in.diagonal);
  ctx.rear = options.maxRear.resolve(in.diagonal);
  ctx.aoDistance = options.aoDistance.resolve(in.diagonal);
  ctx.thicknessDistance = options.thicknessDistance.resolve(in.diagonal);
  ctx.curvatureRadius = options.curvatureRadius.resolve(in.diagonal);
  ctx.epsilon = 1e-5f * std::max(in.diagonal, ctx.scene.bounds().diagonal());
  ctx.worldNormalMatrix = glm::transpose(glm::inverse(mat3(options.objectToWorld)));
  const std::vector<std::uint32_t>& highIndices = in.high->indices;
  bool identity = in.high->normals.size() == highIndices.size();
  for (std::size_t i = 0; identity && i < highIndices.size(); ++i) identity = highIndices[i] == i;
  if (identity) {
    ctx.highCornerNormals = in.high->normals.data();  // already corner by corner: no 9 MB copy per million triangles
  } else {
    ctx.highCornerNormalCopy.resize(highIndices.size());
    for (std::size_t i = 0; i < highIndices.size(); ++i) ctx.highCornerNormalCopy[i] = in.high->normals[highIndices[i]];
    ctx.highCornerNormals = ctx.highCornerNormalCopy.data();
  }
  ctx.lowCorners.resize(in.low.triangleCount());
  for (std::size_t t = 0; t < ctx.lowCorners.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = in.low.indices[3 * t + k];
      const vec3 &p = in.low.positions[v], &n = in.low.normals[v];
      const vec4& t4 = in.low.tangents[v];
      ctx.lowCorners[t].position[k] = Context::Float4{p.x, p.y, p.z, 0.0f};
      ctx.lowCorners[t].normal[k] = Context::Float4{n.x, n.y, n.z, 0.0f};
      ctx.lowCorners[t].tangent[k] = Context::Float4{t4.x, t4.y, t4.z, t4.w};
    }
  }
  stats.frontDistance = ctx.front;
  stats.rearDistance = ctx.rear;
  ctx.hemisphere = options.maps.needs(kHemisphereRays);
  stats.aoDistance = ctx.hemisphere ? ctx.aoDistance : 0.0f;
  stats.thicknessDistance = options.maps.has(Map::Thickness) ? ctx.thicknessDistance : 0.0f;
  stats.curvatureRadius = options.maps.has(Map::Curvature) ? ctx.curvatureRadius : 0.0f;
  if (options.maps.has(Map::Position)) stats.positionBounds = ctx.scene.bounds();
  // Each map asked for gets its floats in a texel, in the table's order (the normal first).
  for (const MapInfo& m : mapTable()) {
    if (m.map == Map::Normal || !options.maps.has(m.map) || m.texelChannels == 0) continue;
    ctx.channel[std::size_t(m.map)] = std::exchange(ctx.channels, ctx.channels + m.texelChannels);
  }
  // Maps with rays of their own, or that read the hit's triangle (which shade() records):
  // no lean path.
  ctx.hitWork = options.maps.needs(kHemisphereRays | kInwardRays | kCurvatureRays | kHitTriangle);
  ctx.extraMaps = options.maps.has(Map::BentNormal) || options.maps.has(Map::Thickness) ||
                  options.maps.has(Map::Curvature) || options.maps.has(Map::Position) || options.maps.has(Map::Opacity);
  stats.texels = std::uint64_t(options.width) * std::uint64_t(options.height);
  const std::size_t texelValues = std::size_t(stats.texels) * std::size_t(ctx.channels);
  ctx.texelStorage = std::make_unique_for_overwrite<float[]>(texelValues);
  ctx.texels = std::span<float>(ctx.texelStorage.get(), texelValues);
  ctx.covered.assign(std::size_t(stats.texels), 0);
  if (options.maps.has(Map::MaterialId)) ctx.texelMaterial.assign(std::size_t(stats.texels), 0);
}

/// The low poly's triangles in texel space, binned into tiles (in id order, so bins are
/// sorted). Triangles without UV area, or wholly outside 0..1, are in no bin.
void binTriangles(Context& ctx) {
  const int W = ctx.options.width, H = ctx.options.height;
  const Mesh& low = ctx.in.low;
  ctx.tilesX = (W + kTile - 1) / kTile;
  ctx.tilesY = (H + kTile - 1) / kTile;
  ctx.bins.resize(std::size_t(ctx.tilesX * ctx.tilesY));
  ctx.tris.resize(low.triangleCount());
  for (std::size_t i = 0; i < ctx.tris.size(); ++i) {
    UvTriangle& t = ctx.tris[i];
    const auto corner = [&](int k) { return low.uvs[low.indices[3 * i + std::size_t(k)]] * vec2(float(W), float(H)); };
    t.a = corner(0);
    t.b = corner(1);
    t.c = corner(2);
    const float area = edge(t.a, t.b, t.c);
    const vec2 uvA = low.uvs[low.indices[3 * i]], uvB = low.uvs[low.indices[3 * i + 1]], uvC = low.uvs[low.indices[3 * i + 2]];
    if (std::fabs((uvB.x - uvA.x) * (uvC.y - uvA.y) - (uvB.y - uvA.y) * (uvC.x - uvA.x)) <= 1e-12f || area == 0.0f) continue;
    t.invArea = 1.0f / area;
    const vec2 mn = glm::min(t.a, glm::min(t.b, t.c)), mx = glm::max(t.a, glm::max(t.b, t.c));
    t.lo = glm::clamp(ivec2(glm::floor(mn)), ivec2(0), ivec2(W - 1, H - 1));
    t.hi = glm::clamp(ivec2(glm::floor(mx)), ivec2(0), ivec2(W - 1, H - 1));
    if (mx.x < 0.0f || mx.y < 0.0f || mn.x > float(W) || mn.y > float(H)) continue;  // outside 0..1
    for (int ty = t.lo.y / kTile; ty <= t.hi.y / kTile; ++ty)
      for (int tx = t.lo.x / kTile; tx <= t.hi.x / kTile; ++tx) ctx.bins[std::size_t(ty * ctx.tilesX + tx)].push_back(int(i));
  }
}

/// The tiles on the GPU (ctx.gpu), in slabs of consecutive tiles a wave each (traceWave):
/// samples placed per tile in parallel, traced together, stored per tile. Progress and
/// Ctrl-C between slabs.
void bakeSlabs(Context& ctx, std::vector<Counters>& tileCounters, Progress* progress, std::atomic<bool>& cancelled) {
  const BakeOptions& options = ctx.options;
  const std::size_t tileCount = ctx.bins.size();
  const std::size_t perTile = std::size_t(kTile * kTile * ctx.root * ctx.root), most = detail::waveSamples(options);
  for (std::size_t t0 = 0; t0 < tileCount;) {
    if (options.cancel && options.cancel->load()) {
      cancelled = true;
      return;
    }
    std::size_t t1 = t0;
    for (std::size_t estimate = 0; t1 < tileCount && (t1 == t0 || estimate + perTile <= most); ++t1) {
      if (!ctx.bins[t1].empty()) estimate += perTile;
    }
    const std::size_t tiles = t1 - t0;
    std::vector<std::vector<detail::SampleInput>> inputs(tiles);
    std::vector<std::vector<Pending>> pending(tiles);
    tbb::parallel_for(std::size_t(0), tiles, [&](std::size_t k) {
      if (ctx.bins[t0 + k].empty()) return;
      std::vector<detail::SampleInput>& in = inputs[k];
      in.resize(perTile);
      std::size_t count = 0;
      forEachTexel(ctx, int(t0 + k), tileCounters[t0 + k], [&](std::size_t texel, bool conservative, const Slot* texelSlots) {
        const std::size_t first = count;
        count += texelInputs(ctx, texel, texelSlots, &in[count]);
        pending[k].push_back({texel, first, count - first, conservative});
      });
      in.resize(count);
    });
    std::vector<std::size_t> base(tiles + 1, 0);
    for (std::size_t k = 0; k < tiles; ++k) base[k + 1] = base[k] + inputs[k].size();
    std::vector<detail::SampleInput> all(base[tiles]);
    for (std::size_t k = 0; k < tiles; ++k) std::copy(inputs[k].begin(), inputs[k].end(), all.begin() + std::ptrdiff_t(base[k]));
    std::vector<detail::SampleResult> results(all.size());
    detail::traceWave(ctx, all, results, tileCounters[t0]);  // the wave's rays counted with its first tile
    tbb::parallel_for(std::size_t(0), tiles, [&](std::size_t k) {
      for (Pending p : pending[k]) {
        p.first += base[k];
        storeTexel(ctx, p, results, tileCounters[t0 + k]);
      }
    });
    if (progress) progress->advance(tiles);
    t0 = t1;
  }
}

/// Every tile with triangles, in parallel; their counters summed into `stats`, their rays
/// appended to options.rayLog in tile order. Error(Interrupted) when cancelled.
void bakeTiles(Context& ctx, BakeStats& stats) {
  const BakeOptions& options = ctx.options;
  const std::size_t tileCount = ctx.bins.size();
  std::vector<Counters> tileCounters(tileCount);
  std::vector<std::vector<raytrace::Ray>> tileRays(options.rayLog ? tileCount : 0);
  std::atomic<bool> cancelled{false};
  {
    Progress progress(options.progressLabel, tileCount);
    const bool showProgress = options.progress;
    if (ctx.gpu) bakeSlabs(ctx, tileCounters, showProgress ? &progress : nullptr, cancelled);
    else tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tileCount, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      const FlushDenormals flush;
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        if (cancelled.load(std::memory_order_relaxed) || (options.cancel && options.cancel->load())) {
          cancelled = true;
          return;
        }
        if (!ctx.bins[i].empty()) bakeTile(ctx, int(i), tileCounters[i], options.rayLog ? &tileRays[i] : nullptr);
        if (showProgress) progress.advance();
      }
    });
  }
  if (cancelled) fail(ErrorKind::Interrupted, "bake interrupted");
  for (const Counters& c : tileCounters) {
    stats.coveredTexels += c.covered;
    stats.conservativeTexels += c.conservative;
    stats.samples += c.samples;
    stats.hits += c.hits;
    stats.inwardHits += c.inward;
    stats.misses += c.misses;
    stats.rays += c.rays;
    stats.aoRays += c.aoRays;
    stats.thicknessRays += c.thicknessRays;
    stats.curvatureRays += c.curvatureRays;
    stats.vertexMeasurements += c.vertexMeasurements;
    stats.overlappingSamples += c.overlaps;
  }
  if (options.rayLog) {
    for (auto& rays : tileRays) options.rayLog->insert(options.rayLog->end(), rays.begin(), rays.end());
  }
}

/// Overlapping UVs, and samples that found nothing: logged and returned as warnings.
void warnAboutSamples(const Context& ctx, const BakeStats& stats, std::vector<std::string>& warnings) {
  if (stats.overlappingSamples) {
    const std::string message = fmt::format(
        "low-poly mesh: {} samples lie in more than one UV triangle (overlapping or mirrored-onto-itself UVs); "
        "each texel takes the lowest-numbered triangle", stats.overlappingSamples);
    log::warn("{}", message);
    warnings.push_back(message);
  }
  // An inside-out high poly (flipped winding or normals): its normals face into the low
  // poly at most hits, and the map points inward (what glint normalmap --check reports).
  if (stats.hits > 0 && stats.inwardHits * 2 > stats.hits) {
    const std::string message = fmt::format(
        "the high poly's normals face away from the low poly's at {:.0f}% of the hits: the high poly looks inside out "
        "(flipped normals or winding); the map points inward — fix the mesh and bake again",
        100.0 * double(stats.inwardHits) / double(stats.hits));
    log::warn("{}", message);
    warnings.push_back(message);
  }
  if (stats.samples > 0 && stats.misses * 10 > stats.samples) {
    const std::string message = fmt::format(
        "{:.0f}% of samples found no high-poly surface within {:.4g} in front / {:.4g} behind: raise --max-front/"
        "--max-rear or check that the meshes overlap", 100.0 * double(stats.misses) / double(stats.samples),
        ctx.front, ctx.rear);
    log::warn("{}", message);
    warnings.push_back(message);
  }
}

/// The baked texels as the result's images (row 0 on top), after `filled` (the covered
/// texels and those dilation filled) is known: maps, and the coverage image.
void makeImages(Context& ctx, const std::vector<std::uint8_t>& filled, BakeResult& result) {
  const BakeOptions& options = ctx.options;
  const int W = options.width, H = options.height;
  const vec3 background = options.space == NormalSpace::Tangent ? vec3(0.0f, 0.0f, 1.0f) : vec3(0.0f);
  std::vector<std::uint8_t> islands = ctx.covered;
  ctx.covered = filled;
  result.normal = channelImage(ctx, 0, 3, true, options.normalType, [&](const float* in, float* out, bool has) {
    const vec3 rgb = has ? encodeNormal(vec3(in[0], in[1], in[2]), options.directX) : background * 0.5f + 0.5f;
    out[0] = rgb.x;
    out[1] = rgb.y;
    out[2] = rgb.z;
  });
  // Each map asked for, as an image: its empty texels hold the map's neutral value (AO 1,
  // a bent normal the background direction, a position the bounds' minimum: 0 in 8/16-bit
  // files); the undilated maps (miss mask, opacity) see the islands only.
  const vec3 lowest = result.stats.positionBounds ? result.stats.positionBounds->min : vec3(0.0f);
  for (const MapInfo& m : mapTable()) {
    if (m.map == Map::Normal || !options.maps.has(m.map)) continue;
    ctx.covered = m.dilated ? filled : islands;
    Image& image = result.maps[std::size_t(m.map)];
    const int first = ctx.channelOf(m.map);
    switch (m.map) {
      case Map::MaterialId: image = detail::materialImage(ctx); break;
      case Map::BentNormal:  // dilation averaged the vectors: normalized again here
        image = channelImage(ctx, first, 3, true, PixelType::F32, [&](const float* in, float* out, bool has) {
          const vec3 b(in[0], in[1], in[2]);
          const float len = has ? glm::length(b) : 0.0f;
          const vec3 rgb = len > 0.0f ? encodeNormal(b * (1.0f / len), options.directX) : background * 0.5f + 0.5f;
          out[0] = rgb.x;
          out[1] = rgb.y;
          out[2] = rgb.z;
        });
        break;
      case Map::Position:
        image = channelImage(ctx, first, 3, true, PixelType::F32, [&](const float* in, float* out, bool has) {
          for (int k = 0; k < 3; ++k) out[k] = has ? in[k] : lowest[k];
        });
        break;
      default: {
        const float empty = m.map == Map::Ao ? 1.0f : 0.0f;
        const int channels = m.channels;
        image = channelImage(ctx, first, channels, true, PixelType::F32, [=](const float* in, float* out, bool has) {
          for (int k = 0; k < channels; ++k) out[k] = has ? in[k] : empty;
        });
      }
    }
  }
  ctx.covered = islands;
  result.coverage = Image(W, H, 1, PixelType::U8);
  auto cov = result.coverage.pixels<std::uint8_t>();
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 64), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      for (int x = 0; x < W; ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(W) + std::size_t(x);
        cov[std::size_t(H - 1 - y) * std::size_t(W) + std::size_t(x)] = islands[i] ? 255 : filled[i] ? 128 : 0;
      }
    }
  });
}

/// The rays a bake will trace: one per sample for the normal, plus AO's, thickness's and
/// curvature's per sample (what picks the BVH's build quality).
double expectedRaysOf(const BakeOptions& options) {
  const double raysPerSample = 1.0 + (options.maps.needs(kHemisphereRays) ? double(options.aoSamples) : 0.0) +
                               (options.maps.needs(kInwardRays) ? double(options.aoSamples) : 0.0) +
                               (options.maps.needs(kCurvatureRays) ? 8.0 : 0.0);
  return double(options.width) * double(options.height) * double(options.samples) * raysPerSample;
}

/// The BVH for `triangles` high-poly triangles traced by `expectedRays` rays. Not robust
/// (watertight) traversal: ~15 % faster; the rare ray that slips through a shared vertex is
/// retried (trace.cpp). Never Embree's high-quality (spatial split) BVH: a bake's short rays
/// along the low poly's normals trace no faster through it — 4.26 M rays of a 2048² bake
/// took 0.33 s either way — while it builds 4× slower (1 M triangles: 0.94 s against 0.22 s
/// on two cores). The low-quality (Morton) build is 2–3× quicker again than the medium one
/// (262k triangles: 0.03 s against 0.06–0.08 s; 1 M: 0.15 s against 0.30–0.45 s) and its rays
/// cost the same up to tens of rays per triangle; at 150 (2048², 36 per texel, 1 M
/// triangles) they took 4–8 % longer, more than the build saves: medium from 64 rays per
/// triangle on. The high poly is read in place (it outlives the scene): no copy of its
/// vertices.
raytrace::SceneOptions sceneOptionsFor(double expectedRays, std::size_t triangles) {
  return raytrace::SceneOptions{.quality = expectedRays < 64.0 * double(triangles) ? raytrace::SceneOptions::Quality::Fast
                                                                                   : raytrace::SceneOptions::Quality::Default,
                                .shareMeshes = true};
}

/// A group's surface offsets are those of the group baked alone: its low triangles' and its
/// BVH's sizes (BVH quality too), so that it bakes the same texels either way.
float groupEpsilon(const GroupMatch& match, const Mesh& low, const raytrace::Scene& scene, std::uint32_t g) {
  Bounds b{vec3(std::numeric_limits<float>::max()), vec3(-std::numeric_limits<float>::max())};
  for (std::size_t t = 0; t < match.lowTriangleGroup.size(); ++t) {
    if (match.lowTriangleGroup[t] != g) continue;
    for (int k = 0; k < 3; ++k) {
      const vec3& p = low.positions[low.indices[3 * t + std::size_t(k)]];
      b.min = glm::min(b.min, p);
      b.max = glm::max(b.max, p);
    }
  }
  return 1e-5f * std::max(b.diagonal(), scene.bounds().diagonal());
}

/// The high poly's scene on the GPU (--device gpu), one at a time (a bake group each);
/// what the scenes held and did is summed into the stats.
class GpuUpload {
public:
  GpuUpload(const BakeOptions& options, BakeStats& stats) : m_options(options), m_stats(stats) {}
  ~GpuUpload() { account(); }
  GpuUpload(const GpuUpload&) = delete;
  GpuUpload& operator=(const GpuUpload&) = delete;
  GpuScene* upload(const Mesh& mesh, const vec3* cornerNormals) {
    account();
    m_scene.reset();  // the last one's memory is free before the next is made
    m_scene = m_options.gpu->upload(mesh, cornerNormals);
    m_stats.gpuBytes = std::max(m_stats.gpuBytes, m_scene->bytes());
    return m_scene.get();
  }
  /// The current scene's dispatches into the stats (once).
  void account() {
    if (!m_scene) return;
    m_stats.gpuDispatches += m_scene->dispatches() - m_counted;
    m_counted = m_scene->dispatches();
    m_stats.gpuLongestDispatchMs = std::max(m_stats.gpuLongestDispatchMs, m_scene->longestDispatchMs());
  }

private:
  const BakeOptions& m_options;
  BakeStats& m_stats;
  std::unique_ptr<GpuScene> m_scene;
  std::size_t m_counted = 0;
};

/// Bake groups: each group's low triangles against its own high parts' BVH, built in turn
/// into `scene` (which `ctx` refers to; group 0's is built already, from `groupMesh`).
void bakeGroups(Context& ctx, BakeStats& stats, const GroupMatch& match, const Mesh& high, const Mesh& low,
                raytrace::Scene& scene, Mesh& groupMesh, std::vector<std::uint32_t>& groupIds,
                const std::function<raytrace::SceneOptions(const Mesh&)>& sceneOptions, GpuUpload& gpu) {
  const std::vector<std::vector<int>> allBins = ctx.bins;
  for (std::uint32_t g = 0; g < match.groups.size(); ++g) {
    if (g > 0) {
      std::vector<std::uint32_t> ids;
      Mesh next = detail::groupHighMesh(high, match.highTriangleGroup, g, ids);
      scene = raytrace::Scene(next, sceneOptions(next));  // (a moved vector keeps its buffer: the scene's view stays valid)
      groupMesh = std::move(next);
      groupIds = std::move(ids);
      ctx.highCornerNormals = groupMesh.normals.data();
      ctx.highTriangleIds = groupIds.data();
      ctx.epsilon = groupEpsilon(match, low, scene, g);
      ctx.vertexCache = detail::buildVertexCache(ctx, groupMesh);
      stats.bvhBytes = std::max(stats.bvhBytes, scene.memoryBytes());
      if (ctx.gpu) ctx.gpu = gpu.upload(groupMesh, ctx.highCornerNormals);
    }
    for (std::size_t i = 0; i < allBins.size(); ++i) {
      ctx.bins[i].clear();
      for (int tri : allBins[i])
        if (match.lowTriangleGroup[std::size_t(tri)] == g) ctx.bins[i].push_back(tri);
    }
    bakeTiles(ctx, stats);
  }
}

/// The covered texels grown over --padding texels (or every texel: --fill-all), the
/// material IDs with them: which texels are filled.
std::vector<std::uint8_t> dilateTexels(Context& ctx, BakeStats& stats) {
  const BakeOptions& options = ctx.options;
  std::vector<std::uint8_t> filled = ctx.covered;
  if (options.padding > 0 || options.fillAll) {
    stats.paddedTexels = dilate(ctx.texels, ctx.channels, options.width, options.height, filled,
                                {.passes = options.fillAll ? -1 : options.padding, .unitVectorChannels = 3});
  }
  if (!ctx.texelMaterial.empty() && (options.padding > 0 || options.fillAll))
    detail::dilateMaterials(ctx.texelMaterial, options.width, options.height, options.fillAll ? -1 : options.padding);
  return filled;
}

}  // namespace

std::size_t detail::waveSamples(const BakeOptions& options) {
  const double raysPerSample = 1.0 + (options.maps.needs(kHemisphereRays) ? double(options.aoSamples) : 0.0) +
                               (options.maps.needs(kInwardRays) ? double(options.aoSamples) : 0.0) +
                               (options.maps.needs(kCurvatureRays) ? 8.0 : 0.0);
  return std::clamp(std::size_t(double(std::size_t(1) << 26) / raysPerSample), std::size_t(1) << 16, std::size_t(1) << 18);
}

BakeResult bake(const Mesh& low, const Mesh& high, const BakeOptions& options) {
  return detail::bakeWith(low, high, options, nullptr);
}

BakeResult detail::bakeWith(const Mesh& low, const Mesh& high, const BakeOptions& options, const PartsInput* parts) {
  BakeResult result;
  BakeStats& stats = result.stats;
  stats.lowTriangles = low.triangleCount();
  stats.highTriangles = high.triangleCount();
  auto start = Clock::now();
  detail::Prepared in = detail::prepareInputs(low, high, options, stats, result.warnings);
  const double checkSeconds = secondsSince(start);  // (these split the phases in the debug log)
  const double expectedRays = expectedRaysOf(options);
  const bool fewRays = expectedRays < 64.0 * double(in.high->triangleCount());
  const auto sceneOptions = [&](std::size_t triangles) { return sceneOptionsFor(expectedRays, triangles); };
  // Bake groups (bake/groups.h): one BVH per group, built in turn; `scene` holds the current
  // one (Context refers to it), `groupMesh` its triangles, `groupIds` their high-poly ids.
  const GroupMatch* match = parts && parts->match && parts->match->grouped() ? parts->match : nullptr;
  Mesh groupMesh;
  std::vector<std::uint32_t> groupIds;
  if (match) groupMesh = detail::groupHighMesh(*in.high, match->highTriangleGroup, 0, groupIds);
  // A cached BVH (a batch's shared high poly) only for the input mesh itself: a copy with
  // generated normals, or a group's triangles, is this bake's own.
  std::shared_ptr<raytrace::Scene> cachedScene;
  std::optional<raytrace::Scene> ownScene;
  if (!match && options.sceneCache && in.high == &high) {
    cachedScene = options.sceneCache->impl().get(high, sceneOptions(high.triangleCount()), stats.bvhReused);
  } else {
    ownScene.emplace(match ? groupMesh : *in.high, sceneOptions(match ? groupMesh.triangleCount() : in.high->triangleCount()));
  }
  raytrace::Scene& scene = cachedScene ? *cachedScene : *ownScene;
  stats.bvhBytes = scene.memoryBytes();
  stats.lowQualityBvh = fewRays;
  const double bvhSeconds = secondsSince(start) - checkSeconds;
  const auto setupStart = Clock::now();
  Context ctx{options, in, scene};
  setUpContext(ctx, stats);
  detail::PartsTables partsTables;
  if (options.maps.needs(kHitTriangle)) {
    partsTables = detail::makePartsTables(options, *in.high, parts ? parts->high : nullptr, result.warnings);
    ctx.parts = &partsTables;
  }
  if (match) {  // position bounds are the whole high poly's, as without groups
    if (options.maps.has(Map::Position)) stats.positionBounds = in.high->bounds();
    ctx.epsilon = groupEpsilon(*match, in.low, scene, 0);
    ctx.highCornerNormals = groupMesh.normals.data();
    ctx.highTriangleIds = groupIds.data();
  }
  ctx.vertexCache = detail::buildVertexCache(ctx, match ? groupMesh : *in.high);
  const detail::DeviceChoice device = detail::chooseDevice(options, in.high->triangleCount());
  stats.device = device.gpu ? "gpu" : "cpu";
  stats.deviceReason = device.reason;
  stats.gpuRenderer = device.info.renderer;
  stats.gpuFreeBytes = device.info.freeBytes.value_or(0);
  GpuUpload gpu(options, stats);
  if (device.gpu) ctx.gpu = gpu.upload(match ? groupMesh : *in.high, ctx.highCornerNormals);
  log::debug("bake: rays on the {} ({})", stats.device, stats.deviceReason);
  const double setupSeconds = secondsSince(setupStart);
  stats.prepareSeconds = secondsSince(start);  // the phases cover the whole of bake()

  start = Clock::now();
  const double cpuStart = processCpuSeconds();
  binTriangles(ctx);
  if (!match) {
    bakeTiles(ctx, stats);
  } else {
    bakeGroups(ctx, stats, *match, *in.high, in.low, scene, groupMesh, groupIds,
               [&](const Mesh& mesh) { return sceneOptions(mesh.triangleCount()); }, gpu);
  }
  gpu.account();
  stats.traceSeconds = secondsSince(start);
  stats.traceCpuSeconds = processCpuSeconds() - cpuStart;
  warnAboutSamples(ctx, stats, result.warnings);

  // Dilation, then the maps as images (row 0 on top).
  start = Clock::now();
  const std::vector<std::uint8_t> filled = dilateTexels(ctx, stats);
  const double dilationSeconds = secondsSince(start);
  const auto imagesStart = Clock::now();
  makeImages(ctx, filled, result);
  result.low = std::move(in.low);
  stats.dilateSeconds = secondsSince(start);
  log::debug("bake: checks and tangents {:.0f} ms, BVH {:.0f} ms ({} quality), setup {:.0f} ms, trace {:.0f} ms, "
             "dilate {:.0f} ms, images {:.0f} ms", 1e3 * checkSeconds, 1e3 * bvhSeconds, fewRays ? "low" : "medium",
             1e3 * setupSeconds, 1e3 * stats.traceSeconds, 1e3 * dilationSeconds, 1e3 * secondsSince(imagesStart));
  return result;
}

}  // namespace glint::bake
