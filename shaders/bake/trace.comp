#version 450 core
// The GPU bake's rays (scenes/bake_tracer.h): one invocation a ray through the BVH
// (bake/bvh.glsl), closest or any hit.
layout(local_size_x = 64) in;

#include "bake/bvh.glsl"

layout(std430, binding = 3) readonly buffer Rays { RayIn rays[]; };
layout(std430, binding = 4) writeonly buffer Hits { HitOut hits[]; };

uniform uint uCount;   // rays in the batch
uniform bool uAnyHit;  // stop at the first hit found (occlusion)

void main() {
  uint r = gl_GlobalInvocationID.x;
  if (r >= uCount) return;
  RayIn ray = rays[r];
  uint slot;
  hits[r] = traceRay(ray.origin, ray.direction, ray.tnear, ray.tfar, uAnyHit, slot);
}
