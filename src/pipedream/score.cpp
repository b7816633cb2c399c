// The instrument machine's score and poses (pipedream/score.h).
#include "glint/pipedream/score.h"

#include "glint/core/hash.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace glint::pipedream {

namespace {

constexpr double kBeat = 0.5;           // seconds between possible mallet strokes
constexpr float kMalletRaise = 0.65f;   // radians the mallet rests above its stroke
constexpr double kStrokeDown = 0.16, kStrokeUp = 0.4;
constexpr float kMalletHead = 0.075f;   // head radius of the unit mallet (InstrumentMachine::mallet)

const vec3 kUp{0.0f, 1.0f, 0.0f};

/// A parabola from `from` through an apex `apex` metres above the higher end to `to`:
/// its launch velocity and duration.
void arcThrough(vec3 from, vec3 to, float apex, vec3& velocity, double& duration) {
  const float top = std::max(from.y, to.y) + apex;
  const float up = std::sqrt(2.0f * kGravity * (top - from.y));
  const float down = std::sqrt(2.0f * kGravity * (top - to.y));
  const float t = (up + down) / kGravity;
  velocity = vec3((to.x - from.x) / t, up, (to.z - from.z) / t);
  duration = double(t);
}

vec3 along(vec3 start, vec3 velocity, float t) { return start + velocity * t - vec3(0.0f, 0.5f * kGravity * t * t, 0.0f); }

/// Module of an instrument (2 drums, 1 cymbal, 8 bars, 1 launcher per module).
int moduleOf(TargetKind kind, int index) {
  switch (kind) {
    case TargetKind::Drum: return index / 2;
    case TargetKind::Cymbal: return index;
    case TargetKind::Bar: return index / 8;
  }
  return 0;
}

/// Mallet length (pivot to head centre) so that the head rests on the skin at the stroke.
float malletLength(const InstrumentMachine& m, const MachineMallet& mallet) {
  const MachineDrum& drum = m.drums[std::size_t(mallet.drum)];
  float length = glm::length(mallet.pivot - drum.top);
  for (int i = 0; i < 4; ++i) length = glm::length(mallet.pivot - (drum.top + vec3(0.0f, 0.022f + kMalletHead * length, 0.0f)));
  return length;
}

/// Damped ringing after each time in `hits` (seconds before `time`, within `window`).
float ring(const std::vector<double>& hits, double time, double decay, double frequency, double window) {
  float sum = 0.0f;
  for (const double h : hits) {
    const double tau = time - h;
    if (tau < 0.0 || tau > window) continue;
    sum += float(std::exp(-tau / decay) * std::sin(2.0 * kPi * frequency * tau));
  }
  return sum;
}

}  // namespace

BallState ballAt(const BallFlight& f, double t) {
  BallState s;
  const double toHit = f.hit - f.launch, toLand = f.land - f.launch;
  if (t < toHit) {
    s.position = along(f.start, f.launchVelocity, float(t));
    s.velocity = f.launchVelocity - vec3(0.0f, kGravity * float(t), 0.0f);
  } else if (t >= toLand) {
    // Into the collector: straight down its tube (the tube's wall takes the sideways motion).
    const float u = float(t - toLand);
    const float vy = f.reboundVelocity.y - kGravity * float(f.land - f.hit);
    s.position = along(f.finish, vec3(0.0f, vy, 0.0f), u);
    s.velocity = vec3(0.0f, vy - kGravity * u, 0.0f);
  } else {
    const float u = float(t - toHit);
    s.position = along(f.strike, f.reboundVelocity, u);
    s.velocity = f.reboundVelocity - vec3(0.0f, kGravity * u, 0.0f);
  }
  return s;
}

Score makeScore(const InstrumentMachine& m, std::uint32_t seed, double interval) {
  Score score;
  HashSequence rng{seed * 2654435761u + 7u};
  const float r = m.ballRadius;
  const int launches = int(std::floor(score.period / interval + 1e-9));
  for (int k = 0; k < launches; ++k) {
    BallFlight f;
    f.launcher = k % int(m.launchers.size());
    const float pick = rng.next();
    f.kind = pick < 0.4f ? TargetKind::Drum : pick < 0.6f ? TargetKind::Cymbal : TargetKind::Bar;
    const int count = int(f.kind == TargetKind::Drum ? m.drums.size() : f.kind == TargetKind::Cymbal ? m.cymbals.size() : m.bars.size());
    // Mostly another module's instrument: balls cross the stage.
    for (int tries = 0; tries < 8; ++tries) {
      f.target = rng.below(count);
      if (moduleOf(f.kind, f.target) != f.launcher || rng.next() < 0.25f) break;
    }
    const MachineLauncher& launcher = m.launchers[std::size_t(f.launcher)];
    // From just inside the mouth, so a ball is never seen to appear.
    f.start = launcher.mouth - vec3(0.0f, r + 0.01f, 0.0f);
    switch (f.kind) {
      case TargetKind::Drum: {
        const MachineDrum& d = m.drums[std::size_t(f.target)];
        const float a = rng.range(0.0f, 2.0f * kPi), o = rng.range(0.0f, 0.4f) * d.radius;
        f.strike = d.top + vec3(o * std::cos(a), 0.022f + r, o * std::sin(a));
        break;
      }
      case TargetKind::Cymbal: {
        const MachineCymbal& c = m.cymbals[std::size_t(f.target)];
        const float a = rng.range(0.0f, 2.0f * kPi), o = rng.range(0.3f, 0.6f);
        f.strike = c.pivot + vec3(o * c.radius * std::cos(a), 0.09f * (1.0f - o) * c.radius + r, o * c.radius * std::sin(a));
        break;
      }
      case TargetKind::Bar: {
        const MachineBar& b = m.bars[std::size_t(f.target)];
        f.strike = b.top + vec3(0.0f, r, rng.range(-0.25f, 0.25f) * b.size.z);
        break;
      }
    }
    // High arcs (over the overhead pipes), then a lower rebound into the nearest collector.
    double toHit = 0.0, toLand = 0.0;
    arcThrough(f.start, f.strike, rng.range(2.3f, 3.0f), f.launchVelocity, toHit);
    float best = 1e30f;
    for (std::size_t c = 0; c < m.collectors.size(); ++c) {
      const float d = glm::length(vec2(m.collectors[c].top.x - f.strike.x, m.collectors[c].top.z - f.strike.z));
      if (d < best) best = d, f.collector = int(c);
    }
    const MachineCollector& collector = m.collectors[std::size_t(f.collector)];
    f.finish = collector.top + vec3(0.0f, r, 0.0f);
    arcThrough(f.strike, f.finish, rng.range(0.9f, 1.5f), f.reboundVelocity, toLand);
    f.launch = double(k) * interval;
    f.hit = f.launch + toHit;
    f.land = f.hit + toLand;
    // Then straight down the tube until the ball is wholly below the collector's top.
    const float vy = f.reboundVelocity.y - kGravity * float(toLand);  // negative
    const float depth = 2.2f * r;
    const float extra = (vy + std::sqrt(vy * vy + 2.0f * kGravity * depth)) / kGravity;
    f.end = f.land + double(extra);
    score.flights.push_back(f);
  }
  const int beats = int(std::floor(score.period / kBeat + 1e-9));
  for (int b = 0; b < beats; ++b)
    for (int mallet = 0; mallet < int(m.mallets.size()); ++mallet)
      if (hash32(std::uint32_t(b * 131 + mallet * 7919) + seed) % 6 == 0)
        score.strokes.push_back({mallet, double(b) * kBeat + 0.25});
  return score;
}

MachinePose poseAt(const InstrumentMachine& m, const Score& score, double time) {
  MachinePose pose;
  const double period = score.period;
  const double cycle = std::floor(time / period);
  const double local = time - cycle * period;  // in [0, period)
  // Events of this loop and the previous one (flights and ringing carry over the seam).
  std::vector<std::vector<double>> drumHits(m.drums.size()), cymbalHits(m.cymbals.size());
  std::vector<vec3> cymbalPush(m.cymbals.size(), vec3(1.0f, 0.0f, 0.0f));
  for (const double shift : {-period, 0.0}) {
    for (std::size_t i = 0; i < score.flights.size(); ++i) {
      const BallFlight& f = score.flights[i];
      const double t = local - (f.launch + shift);
      if (t >= 0.0 && t < f.end - f.launch) {
        BallState s = ballAt(f, t);
        s.flight = int(i);
        pose.balls.push_back(s);
      }
      if (f.kind == TargetKind::Drum) drumHits[std::size_t(f.target)].push_back(f.hit + shift);
      if (f.kind == TargetKind::Cymbal) {
        cymbalHits[std::size_t(f.target)].push_back(f.hit + shift);
        if (local >= f.hit + shift) cymbalPush[std::size_t(f.target)] = f.launchVelocity;
      }
    }
    for (const MalletStroke& s : score.strokes)
      drumHits[std::size_t(m.mallets[std::size_t(s.mallet)].drum)].push_back(s.time + shift);
  }
  std::sort(pose.balls.begin(), pose.balls.end(), [&](const BallState& a, const BallState& b) { return a.flight < b.flight; });

  for (std::size_t d = 0; d < m.drums.size(); ++d) {
    const MachineDrum& drum = m.drums[d];
    const float bounce = 0.012f * ring(drumHits[d], local, 0.12, 9.0, 1.0);
    mat4 t = glm::translate(mat4(1.0f), drum.top + vec3(0.0f, 0.0015f + bounce, 0.0f));
    pose.skins.push_back(glm::scale(t, vec3(0.97f * drum.radius, 1.0f, 0.97f * drum.radius)));
  }
  for (std::size_t c = 0; c < m.cymbals.size(); ++c) {
    const MachineCymbal& cymbal = m.cymbals[c];
    // Tilted a little towards the front at rest; a strike rocks it about the axis across
    // the ball's path.
    vec3 push(cymbalPush[c].x, 0.0f, cymbalPush[c].z);
    if (glm::length(push) < 1e-4f) push = vec3(1.0f, 0.0f, 0.0f);
    const vec3 axis = glm::normalize(glm::cross(kUp, push));
    const float wobble = 0.22f * ring(cymbalHits[c], local, 0.7, 2.1, 4.0);
    mat4 t = glm::translate(mat4(1.0f), cymbal.pivot);
    t = glm::rotate(t, 0.12f, vec3(1.0f, 0.0f, 0.0f));
    t = glm::rotate(t, wobble, axis);
    pose.cymbals.push_back(glm::scale(t, vec3(cymbal.radius)));
  }
  for (std::size_t k = 0; k < m.mallets.size(); ++k) {
    const MachineMallet& mallet = m.mallets[k];
    const MachineDrum& drum = m.drums[std::size_t(mallet.drum)];
    const float length = malletLength(m, mallet);
    const vec3 head = drum.top + vec3(0.0f, 0.022f + kMalletHead * length, 0.0f);
    const vec3 toward = head - mallet.pivot;
    const float yaw = std::atan2(toward.z, -toward.x);
    const float strike = std::asin(std::clamp(-toward.y / length, -1.0f, 1.0f));  // below the horizontal
    float raise = kMalletRaise;
    for (const double shift : {-period, 0.0, period})
      for (const MalletStroke& s : score.strokes) {
        if (s.mallet != int(k)) continue;
        const double tau = local - (s.time + shift);
        if (tau >= -kStrokeDown && tau <= 0.0) raise = std::min(raise, kMalletRaise * float((tau / kStrokeDown) * (tau / kStrokeDown)));
        if (tau > 0.0 && tau <= kStrokeUp) {
          const float u = float(tau / kStrokeUp);
          raise = std::min(raise, kMalletRaise * u * u * (3.0f - 2.0f * u));
        }
      }
    mat4 t = glm::translate(mat4(1.0f), mallet.pivot);
    t = glm::rotate(t, yaw, kUp);
    t = glm::rotate(t, strike - raise, vec3(0.0f, 0.0f, 1.0f));
    pose.mallets.push_back(glm::scale(t, vec3(length)));
  }
  return pose;
}

}  // namespace glint::pipedream
