// Texture-coordinate generation of the 2001 fixed-function pipeline, in GLSL.
//   GL_REFLECTION_MAP: r = u − 2n(n·u), u = unit eye-space position, n = eye-space normal.
//   GL_SPHERE_MAP:     the same r, then (s, t) = r.xy / (2·|r + (0,0,1)|) + ½.
// Eye space is what texgen works in; uEyeToEnv rotates r into the environment's frame:
// the inverse view rotation for a world-space cube map (what the classic path loads
// into the texture matrix), or eye → the sphere map's frame (identity when the map was
// made for this view, which is all GL_SPHERE_MAP itself can do).
#include "env/envmap.glsl"

vec3 texgen(vec3 eyePos, vec3 eyeNormal, mat3 eyeToEnv) {
  vec3 r = eyeToEnv * reflect(normalize(eyePos), eyeNormal);
#ifdef SPHERE_MAP
  return vec3(sphereMapUv(r), 0.0);
#else
  return r;
#endif
}
