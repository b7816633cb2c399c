// The instrument machine's lights (render/pipedream/renderer.h): white point lights with
// a range, diffuse only, so that the share of a pixel's light one light gives is one number
// for all three channels — the dim factor is then exact in every channel.
const int kMaxLights = 4;
uniform int uLightCount;
uniform vec3 uLightPos[kMaxLights];
uniform float uLightRange[kMaxLights];
uniform float uLightIntensity[kMaxLights];
uniform float uAmbient;

// Light i's diffuse term at p: intensity × a window falling smoothly to 0 at the light's
// range (zero slope there: a caster leaving the range fades out, it does not pop) × N·L.
float lightTerm(int i, vec3 p, vec3 n) {
  vec3 d = uLightPos[i] - p;
  float dist = length(d);
  float x = clamp(dist / uLightRange[i], 0.0, 1.0);
  float window = (1.0 - x * x) * (1.0 - x * x);
  return uLightIntensity[i] * window * max(dot(n, d / max(dist, 1e-6)), 0.0);
}
