#include "glint/sim/water.h"

#include "glint/core/error.h"
#include "glint/core/hash.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace glint::sim {

float WaveParams::dampingFactor() const { return std::exp(-damping * timeStep); }

float stabilityLimit(const WaveParams& p) {
  const float stiffness = 8.0f * p.springConstant + p.restoringConstant;
  return stiffness > 0.0f ? 2.0f * std::sqrt(p.mass / stiffness) : std::numeric_limits<float>::infinity();
}

void WaveParams::validate() const {
  auto finite = [](float v) { return std::isfinite(v); };
  if (!finite(mass) || mass <= 0.0f) fail(ErrorKind::Usage, "wave mass must be > 0, got {}", mass);
  if (!finite(springConstant) || springConstant < 0.0f)
    fail(ErrorKind::Usage, "wave spring constant must be ≥ 0, got {}", springConstant);
  if (!finite(restoringConstant) || restoringConstant < 0.0f)
    fail(ErrorKind::Usage, "wave restoring constant must be ≥ 0, got {}", restoringConstant);
  if (!finite(damping) || damping < 0.0f) fail(ErrorKind::Usage, "wave damping must be ≥ 0, got {}", damping);
  if (!finite(timeStep) || timeStep <= 0.0f) fail(ErrorKind::Usage, "wave time step must be > 0, got {}", timeStep);
  const float limit = stabilityLimit(*this);
  if (timeStep > limit) {
    fail(ErrorKind::Usage,
         "wave time step {:.5f} s is unstable for mass {} and spring constants {}, {}: the limit is 2·sqrt(m/(8k + "
         "k_rest)) = {:.5f} s",
         timeStep, mass, springConstant, restoringConstant, limit);
  }
}

namespace {
float hash01(std::uint32_t a, std::uint32_t salt) { return float(hash32(a * 2654435761U ^ hash32(salt)) & 0xFFFFFFU) / float(0xFFFFFF); }
}  // namespace

std::optional<Drop> rainDrop(long step, const WaveParams& params, const RainOptions& rain, ivec2 size) {
  if (rain.interval <= 0.0f || step < 0) return std::nullopt;
  // Drop i falls at the first step s with s·Δt ≥ i·interval: find the newest i with
  // i·interval ≤ s·Δt and check that step s − 1 was still before it. Doubles: exact enough
  // for days of simulated time.
  const double dt = params.timeStep, interval = rain.interval;
  const long i = long(std::floor(double(step) * dt / interval + 1e-9));
  const double dropTime = double(i) * interval;
  if (double(step - 1) * dt >= dropTime - 1e-9 * interval && step > 0) return std::nullopt;
  const auto u = std::uint32_t(i);
  const float scale = float(std::min(size.x, size.y)) / 256.0f;
  const float radius = rain.radius * std::max(scale, 0.25f) * (0.7f + 0.6f * hash01(u, rain.seed + 2));
  const float margin = std::min(3.0f * radius, 0.25f * float(std::min(size.x, size.y)));
  Drop d;
  d.centre = {margin + hash01(u, rain.seed) * (float(size.x) - 2 * margin),
              margin + hash01(u, rain.seed + 1) * (float(size.y) - 2 * margin)};
  d.radius = radius;
  d.amplitude = rain.amplitude * (0.6f + 0.8f * hash01(u, rain.seed + 3)) * ((u % 3 == 2) ? -1.0f : 1.0f);
  if (i == 0 && rain.centreFirst) {
    d.centre = vec2(size) * 0.5f;
    d.radius = rain.radius * std::max(scale, 0.25f);
    d.amplitude = rain.amplitude;
  }
  return d;
}

WaveField::WaveField(ivec2 size) : m_size(size) {
  if (size.x < 1 || size.y < 1) fail(ErrorKind::Usage, "wave grid must be at least 1x1, got {}x{}", size.x, size.y);
  m_state.assign(std::size_t(size.x) * std::size_t(size.y), vec2(0.0f));
}

void WaveField::step(const WaveParams& p) {
  const int w = m_size.x, h = m_size.y;
  m_next.resize(m_state.size());
  const float damp = p.dampingFactor();
  const float dtOverMass = p.timeStep / p.mass;
  auto height = [&](int x, int y, float self) {
    if (p.wrap) return m_state[index((x + w) % w, (y + h) % h)].x;
    return (x < 0 || y < 0 || x >= w || y >= h) ? self : m_state[index(x, y)].x;
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const vec2 me = m_state[index(x, y)];
      // Same order of operations as shaders/water/step.frag, so float results match closely.
      const float neighbours = height(x, y + 1, me.x) + height(x, y - 1, me.x) + height(x + 1, y, me.x) + height(x - 1, y, me.x);
      const float force = p.springConstant * (neighbours - 4.0f * me.x) + p.restoringConstant * (0.0f - me.x);
      const float v = (me.y + dtOverMass * force) * damp;
      m_next[index(x, y)] = {me.x + p.timeStep * v, v};
    }
  }
  m_state.swap(m_next);
}

void WaveField::addDrop(const Drop& d) {
  const float reach = 3.0f * d.radius;
  const int x0 = std::max(0, int(std::floor(d.centre.x - reach))), x1 = std::min(m_size.x - 1, int(std::ceil(d.centre.x + reach)));
  const int y0 = std::max(0, int(std::floor(d.centre.y - reach))), y1 = std::min(m_size.y - 1, int(std::ceil(d.centre.y + reach)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const vec2 offset = vec2(float(x) + 0.5f, float(y) + 0.5f) - d.centre;
      const float d2 = glm::dot(offset, offset);
      if (d2 < reach * reach) m_state[index(x, y)].x += d.amplitude * std::exp(-d2 / (d.radius * d.radius));
    }
  }
}

double WaveField::energy(const WaveParams& p) const {
  const int w = m_size.x, h = m_size.y;
  double kinetic = 0, potential = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const vec2 me = m_state[index(x, y)];
      kinetic += 0.5 * double(p.mass) * double(me.y) * double(me.y);
      potential += 0.5 * double(p.restoringConstant) * double(me.x) * double(me.x);
      // Springs to the east and north neighbours count every spring once.
      const bool east = p.wrap || x + 1 < w, north = p.wrap || y + 1 < h;
      if (east && w > 1) {
        const double d = double(me.x) - double(m_state[index((x + 1) % w, y)].x);
        potential += 0.5 * double(p.springConstant) * d * d;
      }
      if (north && h > 1) {
        const double d = double(me.x) - double(m_state[index(x, (y + 1) % h)].x);
        potential += 0.5 * double(p.springConstant) * d * d;
      }
    }
  }
  return kinetic + potential;
}

void simulate(WaveField& field, long firstStep, long count, const WaveParams& params, const RainOptions& rain) {
  for (long s = firstStep; s < firstStep + count; ++s) {
    if (auto drop = rainDrop(s, params, rain, field.size())) field.addDrop(*drop);
    field.step(params);
  }
}

}  // namespace glint::sim
