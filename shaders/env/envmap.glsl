// Environment-map geometry shared by every shader under shaders/env/. The same
// formulas, in C++, are the CPU references of the tests (image/envmap.h): keep them
// in step.

#include "common/srgb.glsl"

const float kPi = 3.14159265358979;

// Direction through (s, t) of cube face `face` (GL order +X −X +Y −Y +Z −Z): the
// inverse of the OpenGL spec's major-axis table (§8.13).
vec3 cubeFaceDirection(int face, vec2 st) {
  float sc = 2.0 * st.x - 1.0;
  float tc = 2.0 * st.y - 1.0;
  if (face == 0) return vec3(1.0, -tc, -sc);
  if (face == 1) return vec3(-1.0, -tc, sc);
  if (face == 2) return vec3(sc, 1.0, tc);
  if (face == 3) return vec3(sc, -1.0, -tc);
  if (face == 4) return vec3(sc, -tc, 1.0);
  return vec3(-sc, -tc, -1.0);
}

// Lat-long (u, v) of a direction: u = 0.5 looks along −Z, 0.75 along +X; v = 0 is up.
vec2 equirectUv(vec3 d) {
  d = normalize(d);
  float u = 0.5 + atan(d.x, -d.z) / (2.0 * kPi);
  float v = acos(clamp(d.y, -1.0, 1.0)) / kPi;
  return vec2(fract(u), v);
}

// GL_SPHERE_MAP texgen on a reflection vector r given in the sphere map's frame
// (eye space of the view the map was made for): m = 2·|r + (0,0,1)|.
vec2 sphereMapUv(vec3 r) {
  r = normalize(r);
  float m = 2.0 * sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
  return m < 1e-6 ? vec2(1.0, 0.5) : r.xy / m + 0.5;
}

// What a sphere map shows at (s, t): the view ray (0,0,−1) reflected off a mirror ball's
// normal there. inside = false in the corners outside the ball (wasted texels).
vec3 sphereMapDirection(vec2 st, out bool inside) {
  vec2 p = 2.0 * st - 1.0;
  float rr = dot(p, p);
  inside = rr <= 1.0;
  vec3 n = vec3(p, sqrt(max(0.0, 1.0 - rr)));
  return reflect(vec3(0.0, 0.0, -1.0), n);
}

// HDR radiance → display colour: exposure, Narkowicz's ACES filmic fit, sRGB transfer.
// Environment textures store this, like the 8-bit maps of 2001, so the shader paths and
// the fixed-function path sample identical texels.
vec3 displayEncode(vec3 radiance, float exposure) {
  vec3 x = max(radiance * exposure, vec3(0.0));
  vec3 mapped = clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  return srgbEncode(mapped);
}
