#pragma once
// glint/core/hash.h — a small integer hash for deterministic procedural noise.
//
// Procedural textures and simulated rain must be identical on every machine and
// thread count, so they hash integer coordinates instead of using a random engine.

#include <cstdint>

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

}  // namespace glint
