#pragma once
// glint/raytrace/jobs.h — the ray work a GPU bake hands over per sample, as plain data both
// sides share: the baker (bake/, which fills the jobs exactly as its CPU path casts the rays)
// and the compute shaders (scenes/bake_tracer.h; shaders/bake/hemisphere.comp and
// curvature.comp, whose std430 structs these are). Also the table of turns the hemisphere
// sets are made from, so the CPU and the GPU turn the same directions.
//
/// ```cpp run
/// const glint::raytrace::HemisphereTurns& turns = glint::raytrace::hemisphereTurns();
/// // turns.cosine[1] == -1: radicalInverse(1) = 1/2, half a turn
/// ```

#include "glint/core/math.h"

#include <array>
#include <cstdint>

namespace glint::raytrace {

/// One sample's hemisphere rays: `count` directions r·cos φ_i·tangent + r·sin φ_i·bitangent +
/// √(1 − u_i)·axis with u_i = (i + ½)/count + r1 (mod 1), r = √u_i and φ_i = 2π·radicalInverse(i)
/// (the CPU's CosineSet, its turn already in tangent and bitangent); a direction below
/// `mirror`'s plane (dot < 0) is mirrored above it. Each ray runs from `origin` over
/// [0, distance]. 80 bytes, the shader's std430 layout.
struct HemisphereJob {
  vec3 origin{0.0f};
  float r1 = 0.0f;
  vec3 tangent{1, 0, 0};
  float distance = 0.0f;
  vec3 bitangent{0, 1, 0};
  std::uint32_t count = 0;
  vec3 axis{0, 0, 1};
  std::uint32_t closest = 0;  ///< 0: any hit (AO); 1: closest hit (thickness)
  vec3 mirror{0, 0, 1};
  float unused = 0.0f;
};
static_assert(sizeof(HemisphereJob) == 80, "HemisphereJob is the shader's std430 struct");

/// Its answer: any hit — `escaped` rays and the sum of their directions; closest — `value`
/// the sum over the rays of min(t, distance) (a miss counts `distance`).
struct HemisphereSum {
  vec3 directions{0.0f};
  float value = 0.0f;
};
static_assert(sizeof(HemisphereSum) == 16, "HemisphereSum is the shader's std430 struct");

/// One sample's curvature points (the CPU's curvatureFrom): 8 points at angles
/// turn + i·2π/8 in the plane (tangent, bitangent) around `point`, each dropped from
/// radius above that plane along −normal onto the first surface facing the normal's way
/// (up to 3 crossings, the radius halved up to 3 times where nothing is found). 64 bytes.
struct CurvatureJob {
  vec3 point{0.0f};
  float radius = 0.0f;
  vec3 normal{0, 0, 1};
  float turn = 0.0f;
  vec3 tangent{1, 0, 0};
  float unused0 = 0.0f;
  vec3 bitangent{0, 1, 0};
  float unused1 = 0.0f;
};
static_assert(sizeof(CurvatureJob) == 64, "CurvatureJob is the shader's std430 struct");

/// Its answer: the sum of the normal curvatures found, how many points found a surface, and
/// the rays cast.
struct CurvatureSum {
  float sum = 0.0f;
  std::uint32_t found = 0, rays = 0;
  float unused = 0.0f;
};
static_assert(sizeof(CurvatureSum) == 16, "CurvatureSum is the shader's std430 struct");

/// cos and sin of 2π·radicalInverse(i) for the first kCount i (the most rays a hemisphere
/// job casts): the turns of a Hammersley set's second coordinate, computed once.
struct HemisphereTurns {
  static constexpr std::uint32_t kCount = 4096;
  std::array<float, kCount> cosine, sine;
};
const HemisphereTurns& hemisphereTurns();

/// The van der Corput radical inverse in base 2 of i: its bits mirrored behind the point.
float radicalInverse(std::uint32_t i);

}  // namespace glint::raytrace
