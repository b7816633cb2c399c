// The GPU bake's traversal (scenes/bake_tracer.h), shared by its kernels: the flat BVH of
// raytrace/bvh.h walked with the same arithmetic as its CPU traverse(): the slab test widened
// by 2γ(3), the nearer child first, and the watertight triangle test (Woop, Benthin and Wald
// 2013) with the edge functions redone in double where float gives zero. Bindings 0–2.

struct Node {
  vec3 lower;
  uint first;  // inner: first child; leaf: first triangle
  vec3 upper;
  uint count;  // 0: inner
};
struct Triangle {
  vec4 a, b, c;
};
struct RayIn {
  vec3 origin;
  float tnear;
  vec3 direction;
  float tfar;
};
struct HitOut {
  float t;
  uint triangle;  // the mesh's triangle; 0xFFFFFFFF: no hit
  float u, v;     // weights of corners 1 and 2
};

layout(std430, binding = 0) readonly buffer Nodes { Node nodes[]; };
layout(std430, binding = 1) readonly buffer Triangles { Triangle triangles[]; };
layout(std430, binding = 2) readonly buffer Ids { uint ids[]; };

const float kWiden = 1.0 + 2.0 * (3.0 * 0.5 * 1.1920929e-7) / (1.0 - 3.0 * 0.5 * 1.1920929e-7);

bool hitsBox(uint i, vec3 origin, vec3 inverse, float tnear, float tfar, out float entry) {
  vec3 t0 = (nodes[i].lower - origin) * inverse, t1 = (nodes[i].upper - origin) * inverse;
  vec3 lo = min(t0, t1), hi = max(t0, t1);
  // NaN (0 · ∞ on a slab's plane) does not decide: the ray's own limits stand in.
  float enter = max(max(tnear, isnan(lo.x) ? tnear : lo.x), max(isnan(lo.y) ? tnear : lo.y, isnan(lo.z) ? tnear : lo.z));
  float leave = min(min(tfar, isnan(hi.x) ? tfar : hi.x), min(isnan(hi.y) ? tfar : hi.y, isnan(hi.z) ? tfar : hi.z)) * kWiden;
  entry = enter;
  return enter <= leave;
}

bool hitsTriangle(uint k, vec3 origin, ivec3 axes, vec3 shear, float tnear, float tfar, out float t, out float u,
                  out float v) {
  vec3 A = triangles[k].a.xyz - origin, B = triangles[k].b.xyz - origin, C = triangles[k].c.xyz - origin;
  float ax = A[axes.x] - shear.x * A[axes.z], ay = A[axes.y] - shear.y * A[axes.z];
  float bx = B[axes.x] - shear.x * B[axes.z], by = B[axes.y] - shear.y * B[axes.z];
  float cx = C[axes.x] - shear.x * C[axes.z], cy = C[axes.y] - shear.y * C[axes.z];
  // precise: no fused multiply-add, the CPU's rounding (traverse() in bvh.cpp).
  precise float U = cx * by - cy * bx;
  precise float V = ax * cy - ay * cx;
  precise float W = bx * ay - by * ax;
  if (U == 0.0 || V == 0.0 || W == 0.0) {
    U = float(double(cx) * double(by) - double(cy) * double(bx));
    V = float(double(ax) * double(cy) - double(ay) * double(cx));
    W = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  t = 0.0;
  u = 0.0;
  v = 0.0;
  if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
  float det = U + V + W;
  if (det == 0.0) return false;
  precise float T = U * (shear.z * A[axes.z]) + V * (shear.z * B[axes.z]) + W * (shear.z * C[axes.z]);
  float inv = 1.0 / det;
  t = T * inv;
  if (!(t >= tnear && t <= tfar)) return false;
  u = V * inv;
  v = W * inv;
  return true;
}

// The closest hit on [tnear, tfar] (anyHit: the first found), its BVH slot in `slot`.
HitOut traceRay(vec3 origin, vec3 d, float tnear, float tfar, bool anyHit, out uint slot) {
  HitOut hit = HitOut(0.0, 0xFFFFFFFFu, 0.0, 0.0);
  slot = 0u;
  vec3 a = abs(d);
  int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (d[kz] < 0.0) {
    int s = kx;
    kx = ky;
    ky = s;
  }
  ivec3 axes = ivec3(kx, ky, kz);
  vec3 shear = vec3(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
  if (nodes.length() == 0 || !(tnear <= tfar) || isinf(shear.z) || isnan(shear.z)) return hit;
  vec3 inverse = 1.0 / d;
  float best = tfar;
  uint stack[64];
  int top = 0;
  stack[top++] = 0u;
  while (top > 0) {
    uint i = stack[--top];
    float entry;
    if (!hitsBox(i, origin, inverse, tnear, best, entry)) continue;
    if (nodes[i].count == 0u) {
      uint f = nodes[i].first;
      float e0, e1;
      bool h0 = hitsBox(f, origin, inverse, tnear, best, e0);
      bool h1 = hitsBox(f + 1u, origin, inverse, tnear, best, e1);
      if (h0 && h1) {
        stack[top++] = e0 <= e1 ? f + 1u : f;
        stack[top++] = e0 <= e1 ? f : f + 1u;
      } else if (h0 || h1) {
        stack[top++] = h0 ? f : f + 1u;
      }
      continue;
    }
    for (uint k = nodes[i].first; k < nodes[i].first + nodes[i].count; ++k) {
      float t, u, v;
      if (!hitsTriangle(k, origin, axes, shear, tnear, best, t, u, v)) continue;
      best = t;
      hit = HitOut(t, ids[k], u, v);
      slot = k;
      if (anyHit) return hit;
    }
  }
  return hit;
}
