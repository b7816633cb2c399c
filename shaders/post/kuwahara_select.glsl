// Kuwahara pass 2 (WWDC 2003 session 212): fetch the four overlapping quadrants' statistics — four
// texel fetches — and keep the mean of the one with the least variance. Quadrants share
// the pixel as a corner (image/post.h's numbering: 0 upper-left, 1 upper-right,
// 2 lower-left, 3 lower-right; "upper" is towards texel row 0, the picture's top). Exact
// ties go to the lowest number, as in the reference.
// One texel; kuwahara_select.frag calls it (the fragment version of kuwahara.comp).
uniform sampler2D uInput;
uniform sampler2D uStatistics;
uniform int uSize;
uniform bool uShowQuadrant;

vec4 kuwaharaSelect(ivec2 p) {
  int o = uSize - 1;
  // Statistics texel of the block with top-left pixel c is c + (s − 1).
  vec4 q0 = texelFetch(uStatistics, p, 0);
  vec4 q1 = texelFetch(uStatistics, p + ivec2(o, 0), 0);
  vec4 q2 = texelFetch(uStatistics, p + ivec2(0, o), 0);
  vec4 q3 = texelFetch(uStatistics, p + ivec2(o, o), 0);
  vec4 best = q0;
  int chosen = 0;
  if (q1.a < best.a) { best = q1; chosen = 1; }
  if (q2.a < best.a) { best = q2; chosen = 2; }
  if (q3.a < best.a) { best = q3; chosen = 3; }
  float alpha = texelFetch(uInput, p, 0).a;
  if (uShowQuadrant) return vec4(vec3(float(chosen) / 255.0), alpha);
  return vec4(best.rgb / (float(uSize * uSize) * 255.0), alpha);
}
