#pragma once
// glint/core/hash.h — the project's hashes and its one seeded generator, each written once.
//
//   hash32        an integer hash for deterministic procedural noise (textures, simulated
//                 rain): identical on every machine and thread count, unlike a random engine.
//   hash64        SplitMix64's mix: a 64-bit integer hash, for counter-based random streams
//                 (the baker's per-texel rays: the value for (texel, sample) does not depend
//                 on which thread asks) and as unitFloat's input.
//   hashKey       three integers → one 64-bit key, for hash tables keyed by a small integer
//                 tuple (grid cells, welded positions, plane names).
//   HashSequence  the seeded generator: a deterministic sequence of uniform numbers built on
//                 hash32 (the Pipe Dream stage and score, the painted detail map).
//   Fnv1a         64-bit FNV-1a over bytes: a stable content hash for cache keys, input
//                 fingerprints and names (a material's colour). Not cryptographic.
//
/// ```cpp run
/// #include <vector>
/// const std::vector<float> positions{0.0f, 1.0f, 2.0f};
/// const int lightCount = 2;
/// glint::Fnv1a h;
/// h.add(positions).add(lightCount);  // ranges of trivially copyable values, or values
/// const std::uint64_t key = h.value();
/// const std::uint32_t noise = glint::hash32(7);  // the same on every machine
/// const float u = glint::unitFloat(glint::hash64(42));  // texel 42's first random number
/// glint::HashSequence rng{12345u};
/// const float r = rng.range(-1.0f, 1.0f);
/// ```

#include <cstddef>
#include <cstdint>
#include <ranges>
#include <span>
#include <type_traits>

namespace glint {

/// lowbias32: a 32-bit integer hash with good avalanche; identical everywhere.
constexpr std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

/// SplitMix64's output function of state `x` (the state advanced by the golden ratio first):
/// a 64-bit hash with full avalanche, identical everywhere.
constexpr std::uint64_t hash64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// The top 24 bits of `x` as a float in [0, 1): a uniform number from a hash64 value.
constexpr float unitFloat(std::uint64_t x) { return float(x >> 40) * (1.0f / float(1ull << 24)); }

/// Three integers (a cell's coordinates, a position's bits) as one 64-bit key for a hash
/// table: each multiplied by a large odd constant and folded in with shifts.
constexpr std::uint64_t hashKey(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  std::uint64_t h = a * 0x9E3779B97F4A7C15ull;
  h ^= (h >> 29) + b * 0xBF58476D1CE4E5B9ull;
  h ^= (h >> 31) + c * 0x94D049BB133111EBull;
  return h ^ (h >> 32);
}

/// A deterministic sequence of uniform numbers built on hash32: the same numbers on every
/// machine and standard library (std::uniform_real_distribution's are not), for procedural
/// content such as the Pipe Dream stage and its score. Not for statistics.
struct HashSequence {
  std::uint32_t state = 0;
  /// The next number in [0, 1), with 24 bits of resolution.
  float next() {
    state = hash32(state + 0x9E3779B9u);
    return float(state >> 8) * (1.0f / 16777216.0f);
  }
  /// Uniform in [lo, hi).
  float range(float lo, float hi) { return lo + (hi - lo) * next(); }
  /// Uniform integer in [0, n), n > 0.
  int below(int n) {
    const int k = int(next() * float(n));
    return k < n - 1 ? k : n - 1;
  }
};

/// 64-bit FNV-1a, fed byte by byte. Values are hashed by their object representation,
/// so callers that need +0 and -0 (or other equal values with different bits) to hash
/// alike canonicalise first.
class Fnv1a {
 public:
  static constexpr std::uint64_t kOffsetBasis = 0xcbf29ce484222325ull;
  static constexpr std::uint64_t kPrime = 0x100000001b3ull;

  constexpr Fnv1a() = default;
  constexpr explicit Fnv1a(std::uint64_t seed) : m_h(seed) {}

  /// Hashes `size` bytes at `data`.
  Fnv1a& addBytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) m_h = (m_h ^ p[i]) * kPrime;
    return *this;
  }
  /// Hashes a contiguous range of trivially copyable values (a span, vector or array):
  /// their bytes, in order. The size is not hashed; add it too where lengths vary.
  template <std::ranges::contiguous_range R>
    requires std::ranges::sized_range<R> && std::is_trivially_copyable_v<std::ranges::range_value_t<R>>
  Fnv1a& add(const R& values) {
    return addBytes(std::ranges::data(values), std::ranges::size(values) * sizeof(std::ranges::range_value_t<R>));
  }
  /// Hashes one trivially copyable value that is not a range.
  template <class T>
    requires std::is_trivially_copyable_v<T> && (!std::ranges::contiguous_range<T>)
  Fnv1a& add(const T& value) {
    return addBytes(&value, sizeof(T));
  }

  constexpr std::uint64_t value() const { return m_h; }

 private:
  std::uint64_t m_h = kOffsetBasis;
};

/// FNV-1a of a byte span in one call.
inline std::uint64_t fnv1a(std::span<const std::byte> bytes) { return Fnv1a().add(bytes).value(); }

}  // namespace glint
