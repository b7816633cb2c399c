#pragma once
// Private to glint_raytrace (and `glint bench bake`'s plain-Embree peer): the one seam between
// glint and Embree's two APIs. Debian 12 ships Embree 3, Debian 13 Embree 4 (CMake finds
// either and sets GLINT_EMBREE_MAJOR): the headers moved (embree3/ → embree4/), the
// intersect context became query arguments, and Embree 4 has no stream call (rtcIntersect1M).
#include "glint/raytrace/raytracer.h"

#if GLINT_EMBREE_MAJOR >= 4
#include <embree4/rtcore.h>
#else
#include <embree3/rtcore.h>
#endif

#include <cstddef>

namespace glint::raytrace::embree {

/// Whether Embree may be given the ray: origin and direction within its range (it asserts
/// on others, aborting the process), tnear and tfar not NaN.
inline bool traceable(const Ray& ray) {
  bool ok = !(ray.tnear != ray.tnear) && !(ray.tfar != ray.tfar);
  for (int k = 0; k < 3; ++k) {
    const float o = ray.origin[k] < 0.0f ? -ray.origin[k] : ray.origin[k];
    const float d = ray.direction[k] < 0.0f ? -ray.direction[k] : ray.direction[k];
    ok &= o <= kMaxCoordinate && d <= kMaxCoordinate;
  }
  return ok;
}

/// Fills `rh` in place for a query (building a temporary and copying it made the processor
/// wait on partial stores it could not forward: measurable in the baker's inner loop). A ray
/// Embree may not be given becomes an empty segment (tnear > tfar) at the origin, which hits nothing.
inline void fill(const Ray& ray, RTCRayHit& rh) {
  const bool ok = traceable(ray);
  rh.ray.org_x = ok ? ray.origin.x : 0.0f;
  rh.ray.org_y = ok ? ray.origin.y : 0.0f;
  rh.ray.org_z = ok ? ray.origin.z : 0.0f;
  rh.ray.dir_x = ok ? ray.direction.x : 0.0f;
  rh.ray.dir_y = ok ? ray.direction.y : 0.0f;
  rh.ray.dir_z = ok ? ray.direction.z : 1.0f;
  rh.ray.tnear = ok ? ray.tnear : 1.0f;
  rh.ray.tfar = ok ? ray.tfar : 0.0f;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

/// The closest hit of one ray, into rh.hit (geomID RTC_INVALID_GEOMETRY_ID: none). `coherent`
/// says neighbouring calls trace similar rays.
inline void intersect(RTCScene scene, RTCRayHit& rh, bool coherent = false) {
#if GLINT_EMBREE_MAJOR >= 4
  RTCIntersectArguments arguments;
  rtcInitIntersectArguments(&arguments);
  arguments.flags = coherent ? RTC_RAY_QUERY_FLAG_COHERENT : RTC_RAY_QUERY_FLAG_INCOHERENT;
  rtcIntersect1(scene, &rh, &arguments);
#else
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  if (coherent) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect1(scene, &context, &rh);
#endif
}

/// Whether anything lies on the ray's segment (Embree sets tfar to -inf when it does).
inline bool occluded(RTCScene scene, RTCRay& ray) {
#if GLINT_EMBREE_MAJOR >= 4
  RTCOccludedArguments arguments;
  rtcInitOccludedArguments(&arguments);
  rtcOccluded1(scene, &ray, &arguments);
#else
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(scene, &context, &ray);
#endif
  return ray.tfar < 0.0f;
}

/// The closest hits of a group of similar rays: Embree 3's stream call (it packetizes within
/// the call); Embree 4 has none, so one coherent query each.
inline void intersectGroup(RTCScene scene, RTCRayHit* rays, std::size_t count) {
#if GLINT_EMBREE_MAJOR >= 4
  for (std::size_t i = 0; i < count; ++i) intersect(scene, rays[i], true);
#else
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect1M(scene, &context, rays, unsigned(count), sizeof(RTCRayHit));
#endif
}

}  // namespace glint::raytrace::embree
