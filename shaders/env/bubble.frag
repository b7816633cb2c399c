#version 450 core
// A soap bubble reflecting its surroundings from a dynamic cube map. The film is thin,
// so what it does not reflect it transmits: the colour is premultiplied by the Fresnel
// reflectance F (Schlick: F0 + (1 − F0)(1 − cosθ)^5) and blended with (ONE,
// ONE_MINUS_SRC_ALPHA), alpha = F — faint face-on, a bright mirror at grazing angles.
// Thin-film interference is suggested by a hue that shifts with cosθ. MIRROR sets F = 1
// (an opaque chrome ball), to see the cube map's content plainly.
in vec3 vWorldPos;
in vec3 vNormal;
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform samplerCube uEnvironment;
uniform vec3 uEye;
uniform float uF0 = 0.04;  // water/soap film at normal incidence
uniform float uTime;

void main() {
  vec3 v = normalize(vWorldPos - uEye);
  vec3 n = normalize(vNormal);
  if (dot(n, v) > 0.0) n = -n;  // wobble can tilt a normal away near the silhouette
  vec3 reflected = texture(uEnvironment, reflect(v, n)).rgb;
  float cosTheta = clamp(dot(-v, n), 0.0, 1.0);
#ifdef MIRROR
  float f = 1.0;
  vec3 film = vec3(1.0);
#else
  float f = uF0 + (1.0 - uF0) * pow(1.0 - cosTheta, 5.0);
  vec3 film = 0.5 + 0.5 * cos(6.28318 * (vec3(0.0, 0.33, 0.67) + 1.6 * cosTheta + 0.05 * uTime));
  film = mix(vec3(1.0), film, 0.6);
#endif
  fragColor = vec4(reflected * film * f, f);
}
