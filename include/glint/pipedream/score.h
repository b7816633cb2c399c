#pragma once
// glint/pipedream/score.h — what the instrument machine plays: the score as data,
// and where every moving part is at a given time (no GL).
//
// Contents
//   BallFlight, MalletStroke, Score   the score: which launcher fires at whom, when; mallet strokes
//   makeScore                         the machine's score (deterministic, looping)
//   BallState, MachinePose, poseAt    every ball's position and velocity, every skin, cymbal
//                                     and mallet's transform at a time
//
// A flight: a ball leaves a launcher (from inside its mouth, so it is never seen to
// appear), flies a ballistic arc to an instrument (a drum skin, a cymbal, a xylophone bar),
// strikes it at `hit`, rebounds on a second arc onto a collector's mouth at `land` and drops
// straight down its tube (it is removed once it is inside, at `end`). Both arcs are exact
// parabolas under gravity through their end points, so velocity is known exactly (the
// motion blur uses it).
// Strikes make drum skins bounce and cymbals wobble (damped sines); mallets swing down
// onto their drums on the beat. Everything is a function of time: the score loops with
// `period`, and flights that cross the end of the loop carry over into the next.
//
/// ```cpp run
/// #include <algorithm>
/// const glint::InstrumentMachine machine = glint::makeInstrumentMachine({.detail = 1});
/// const glint::pipedream::Score score = glint::pipedream::makeScore(machine);
/// const glint::pipedream::MachinePose pose = glint::pipedream::poseAt(machine, score, 3.25);
/// float fastest = 0.0f;
/// for (const glint::pipedream::BallState& ball : pose.balls)
///   fastest = std::max(fastest, glm::length(ball.velocity));  // ball.position: where to draw it
/// ```

#include "glint/core/math.h"
#include "glint/pipedream/machine_room.h"

#include <cstdint>
#include <vector>

namespace glint::pipedream {

constexpr float kGravity = 9.81f;  ///< m/s², along −y

/// What a ball strikes.
enum class TargetKind {
  Drum,    ///< a drum's skin (MachineDrum)
  Cymbal,  ///< a cymbal's top (MachineCymbal)
  Bar      ///< a xylophone bar (MachineBar)
};

struct BallFlight {
  int launcher = 0;
  TargetKind kind = TargetKind::Drum;
  int target = 0;     ///< index into the machine's drums, cymbals or bars
  int collector = 0;  ///< where it ends
  double launch = 0.0, hit = 0.0, land = 0.0, end = 0.0;  ///< seconds within the loop (end may pass it)
  vec3 start{0.0f}, strike{0.0f}, finish{0.0f};  ///< ball centre at launch, hit and land
  vec3 launchVelocity{0.0f}, reboundVelocity{0.0f};
};

struct MalletStroke {
  int mallet = 0;
  double time = 0.0;  ///< the head meets the skin
};

struct Score {
  double period = 16.0;  ///< seconds; the score repeats
  std::vector<BallFlight> flights;
  std::vector<MalletStroke> strokes;
};

/// The machine's score: a launch every `interval` seconds, launchers in turn, targets
/// mostly in other modules (balls cross the stage and the lights' ranges), mallets on a
/// four-beat pattern. Deterministic for a seed.
Score makeScore(const InstrumentMachine& machine, std::uint32_t seed = 1, double interval = 0.4);

/// A ball in flight.
struct BallState {
  vec3 position{0.0f};
  vec3 velocity{0.0f};  ///< m/s
  int flight = 0;       ///< index into Score::flights
};

/// Everything that moves, at one time.
struct MachinePose {
  std::vector<BallState> balls;  ///< in flight, by launch time
  std::vector<mat4> skins;       ///< per drum: InstrumentMachine::skin → world
  std::vector<mat4> cymbals;     ///< per cymbal: InstrumentMachine::cymbal → world
  std::vector<mat4> mallets;     ///< per mallet: InstrumentMachine::mallet → world
};

/// Where everything is at `time` seconds (any value: the score loops).
MachinePose poseAt(const InstrumentMachine& machine, const Score& score, double time);

/// A ball's state `t` seconds after its launch (t in [0, end − launch]).
BallState ballAt(const BallFlight& flight, double t);

}  // namespace glint::pipedream
