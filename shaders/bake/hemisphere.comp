#version 450 core
// One invocation a sample's hemisphere rays (scenes/bake_tracer.h, bake/gpu_backend.h's
// HemisphereJob): the CPU's CosineSet generated here from the same table of turns, so a
// sample's 16–1,024 rays never cross the bus. Any hit (AO, bent normals): the rays that
// escape and the sum of their directions; closest hit (thickness): the sum of the distances.
layout(local_size_x = 64) in;

#include "bake/bvh.glsl"

struct Job {
  vec3 origin;
  float r1;
  vec3 tangent;
  float distance;
  vec3 bitangent;
  uint count;
  vec3 axis;
  uint closest;
  vec3 mirror;
  float unused;
};
struct Sum {
  vec3 directions;
  float value;
};

layout(std430, binding = 3) readonly buffer Jobs { Job jobs[]; };
layout(std430, binding = 4) writeonly buffer Sums { Sum sums[]; };
layout(std430, binding = 5) readonly buffer Turns { vec2 turns[]; };  // cos, sin of 2π·radicalInverse(i)

uniform uint uCount;  // jobs in the batch

void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= uCount) return;
  Job job = jobs[j];
  vec3 directions = vec3(0.0);
  float value = 0.0;
  for (uint i = 0u; i < job.count; ++i) {
    // precise: the CPU's rounding, no fused multiply-add (trace.cpp, CosineSet).
    precise float u1 = (float(i) + 0.5) / float(job.count) + job.r1;
    if (u1 >= 1.0) u1 -= 1.0;
    precise float r = sqrt(u1);
    precise vec3 d = (r * turns[i].x) * job.tangent + (r * turns[i].y) * job.bitangent + sqrt(max(0.0, 1.0 - u1)) * job.axis;
    precise float below = dot(d, job.mirror);
    if (below < 0.0) d -= (2.0 * below) * job.mirror;
    uint slot;
    HitOut hit = traceRay(job.origin, d, 0.0, job.distance, job.closest == 0u, slot);
    if (job.closest != 0u) {
      value += hit.triangle != 0xFFFFFFFFu ? min(hit.t, job.distance) : job.distance;
    } else if (hit.triangle == 0xFFFFFFFFu) {
      value += 1.0;
      directions += d;
    }
  }
  sums[j] = Sum(directions, value);
}
