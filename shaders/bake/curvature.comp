#version 450 core
// One invocation a sample's curvature (scenes/bake_tracer.h, bake/gpu_backend.h's
// CurvatureJob): the CPU's curvatureFrom — 8 points around the hit dropped onto the high
// poly, the first surface facing the hit's way (up to 3 crossings), the radius halved up to
// 3 times where nothing is found — each giving the normal curvature towards it.
layout(local_size_x = 64) in;

#include "bake/bvh.glsl"

struct Job {
  vec3 point;
  float radius;
  vec3 normal;
  float turn;
  vec3 tangent;
  float unused0;
  vec3 bitangent;
  float unused1;
};
struct Sum {
  float sum;
  uint found, rays;
  float unused;
};

layout(std430, binding = 3) readonly buffer Jobs { Job jobs[]; };
layout(std430, binding = 4) writeonly buffer Sums { Sum sums[]; };
layout(std430, binding = 6) readonly buffer CornerNormals { float cornerNormals[]; };  // 9 a mesh triangle

uniform uint uCount;     // jobs in the batch
uniform float uEpsilon;  // past a skipped surface

// The high poly's interpolated normal at a hit (not normalized); its facet normal where that
// has no length.
vec3 interpolatedNormal(HitOut hit, uint slot) {
  uint base = 9u * hit.triangle;
  vec3 c0 = vec3(cornerNormals[base], cornerNormals[base + 1u], cornerNormals[base + 2u]);
  vec3 c1 = vec3(cornerNormals[base + 3u], cornerNormals[base + 4u], cornerNormals[base + 5u]);
  vec3 c2 = vec3(cornerNormals[base + 6u], cornerNormals[base + 7u], cornerNormals[base + 8u]);
  vec3 n = (1.0 - hit.u - hit.v) * c0 + hit.u * c1 + hit.v * c2;
  if (n != vec3(0.0)) return n;
  vec3 a = triangles[slot].a.xyz;
  return normalize(cross(triangles[slot].b.xyz - a, triangles[slot].c.xyz - a));
}

void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= uCount) return;
  Job job = jobs[j];
  const float step = 2.0 * 3.14159265358979 / 8.0;
  float sum = 0.0;
  uint found = 0u, rays = 0u;
  for (int i = 0; i < 8; ++i) {
    float angle = job.turn + step * float(i);
    vec3 dir = cos(angle) * job.tangent + sin(angle) * job.bitangent;
    float r = job.radius;
    for (int attempt = 0; attempt < 4; ++attempt, r *= 0.5) {
      vec3 origin = job.point + r * dir + r * job.normal;
      float tnear = 0.0;
      bool any = false;
      HitOut hit;
      uint slot;
      for (int crossing = 0; crossing < 3; ++crossing) {
        ++rays;
        hit = traceRay(origin, -job.normal, tnear, 2.0 * r, false, slot);
        if (hit.triangle == 0xFFFFFFFFu) break;
        if (dot(interpolatedNormal(hit, slot), job.normal) > 0.0) {
          any = true;
          break;
        }
        tnear = hit.t + uEpsilon;
      }
      if (!any) continue;
      vec3 e = origin - hit.t * job.normal - job.point;
      float length2 = dot(e, e);
      if (length2 > 0.0) {
        vec3 n = interpolatedNormal(hit, slot);
        float len = length(n);
        sum += dot((len > 0.0 ? n / len : n) - job.normal, e) / length2;
        ++found;
      }
      break;
    }
  }
  sums[j] = Sum(sum, found, rays, 0.0);
}
