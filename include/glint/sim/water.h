#pragma once
// glint/sim/water.h — the VGP353 lecture's wave simulation as a spring network, on the CPU: the
// reference the GPU simulation (render/water/wave_simulation.h) is tested against, and
// the place its physics is documented. No GL.
//
// Contents
//   WaveParams      mass, spring constants, damping, time step, edges
//   Drop            a Gaussian splash added to the heights ("draw new waves into texture")
//   RainOptions / rainDrop   the deterministic schedule of drops the scenes use
//   WaveField       a grid of (height, velocity); step(), addDrop(), energy()
//   stabilityLimit  the largest stable time step
//
// The model. Every texel is a column of water of mass m with height h and velocity v,
// tied to its four neighbours by springs of constant k and to the rest level 0 by a
// weak spring k_rest ("a force pulling the waves towards rest ... to stabilize"). One
// step (semi-implicit Euler: velocity first, then position with the new velocity):
//     F  = k · (h_n + h_s + h_e + h_w − 4h) + k_rest · (0 − h)
//     v' = (v + Δt · F / m) · exp(−damping · Δt)
//     h' = h + Δt · v'
// This is the slide's shader with its constants made explicit:
//     vec2 f_vec = vec2(-4.0*me.x + n + s + e + w, 0.5 - me.x);   F = dot(spring_constant, f_vec)
//     V = mass * F + (me.w - 0.5);    H = time * V + me.x * damping;
// where the slide's "mass" is really Δt/m, its velocity update has no Δt of its own, heights
// and velocities are biased by 0.5 to fit 8-bit texture channels, and its damping multiplies
// the biased height — which also drags the rest level from 0.5 towards 0. glint stores
// (h, v) unbiased in a float texture (RG32F: R = height, G = velocity) and damps the
// velocity, so the rest state stays at rest; an oscillation's energy decays by about
// exp(−damping·t) (its amplitude by exp(−damping·t/2)).
//
// Edges: Clamp reads a missing neighbour as the texel itself (no spring across the edge: a
// reflecting wall, like a pool); Wrap joins opposite edges (an endless tiling sea).
//
// Stability. The stiffest mode (neighbours alternating) has ω² = (8k + k_rest)/m. The
// scheme is stable (energy bounded, with damping ≥ 0) iff Δt² · ω² ≤ 4, i.e.
//     Δt ≤ stabilityLimit(params) = 2 · sqrt(m / (8k + k_rest)).
// Waves travel at sqrt(k/m) texels per second. The defaults: 60 texels/s, Δt = 1/120 s,
// Δt·ω = 1.41 (limit 2). tests/water/wave_cpu_test.cpp and wave_gpu_test.cpp checks GPU = CPU, the energy decay, and
// that steps just inside the limit stay bounded while steps just beyond it blow up.

#include "glint/core/math.h"

#include <optional>
#include <vector>

namespace glint::sim {

struct WaveParams {
  float mass = 1.0f;                ///< m of one water column (> 0)
  float springConstant = 3600.0f;   ///< k between neighbours (≥ 0); wave speed sqrt(k/m) texels/s
  float restoringConstant = 4.0f;   ///< k_rest towards height 0 (≥ 0)
  float damping = 0.25f;            ///< velocity decay rate per second (≥ 0); 0 keeps the energy
  float timeStep = 1.0f / 120.0f;   ///< Δt of one step, seconds (> 0, ≤ stabilityLimit)
  bool wrap = false;                ///< true: periodic edges; false: reflecting walls

  /// Per-step velocity factor exp(−damping · Δt), computed once so CPU and GPU use the same float.
  float dampingFactor() const;
  /// Error(Usage) naming the parameter when one is out of range (including an unstable Δt).
  void validate() const;
};

/// The largest stable time step: 2 · sqrt(m / (8k + k_rest)) (infinite when both constants are 0).
float stabilityLimit(const WaveParams& params);

/// A Gaussian splash: height += amplitude · exp(−d² / radius²) for texels whose centre lies
/// within 3 · radius of `centre` (d in texels; texel (x, y) has its centre at (x + ½, y + ½),
/// y counted from the bottom row, as in a texture).
struct Drop {
  vec2 centre{0.0f};
  float radius = 3.0f;
  float amplitude = 0.5f;
};

/// When and how drops fall ("waves will eventually die: draw new waves periodically").
struct RainOptions {
  float interval = 0.5f;     ///< seconds between drops (≤ 0: no rain)
  float radius = 5.0f;       ///< texels (scaled with the grid: this is for 256 texels)
  float amplitude = 1.0f;    ///< height units
  unsigned seed = 1;
  bool centreFirst = false;  ///< drop 0 falls in the middle of the grid (a clean single ring)
};
/// The drop that falls at the start of step `step` (0-based), if one does: drop i falls at
/// the first step with step · Δt ≥ i · interval, at a hashed position on a grid of `size`.
std::optional<Drop> rainDrop(long step, const WaveParams& params, const RainOptions& rain, ivec2 size);

class WaveField {
public:
  WaveField() = default;
  /// A field at rest: all heights and velocities 0.
  explicit WaveField(ivec2 size);

  ivec2 size() const { return m_size; }
  /// (height, velocity) of texel (x, y), y from the bottom row. No bounds check.
  vec2& at(int x, int y) { return m_state[index(x, y)]; }
  vec2 at(int x, int y) const { return m_state[index(x, y)]; }
  /// Row-major from the bottom row: exactly the layout of the GPU's RG32F texture.
  std::vector<vec2>& data() { return m_state; }
  const std::vector<vec2>& data() const { return m_state; }

  /// One step of the model above (params assumed valid).
  void step(const WaveParams& params);
  /// Adds a drop to the heights (velocities unchanged).
  void addDrop(const Drop& drop);
  /// Total energy: Σ ½ m v² + ½ k_rest h² over texels + Σ ½ k (h_i − h_j)² over springs.
  double energy(const WaveParams& params) const;

private:
  std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(m_size.x) + std::size_t(x); }
  ivec2 m_size{0};
  std::vector<vec2> m_state;
  std::vector<vec2> m_next;
};

/// Runs steps firstStep … firstStep + count − 1 of a rainy simulation: each step adds its
/// scheduled drop (rainDrop), then steps. WaveSimulation::step does the same on the GPU.
void simulate(WaveField& field, long firstStep, long count, const WaveParams& params, const RainOptions& rain);

}  // namespace glint::sim
