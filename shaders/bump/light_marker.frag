#version 450 core
// A bright core with a soft rim, so the marker reads as a light, not as geometry.
uniform vec3 uColor;
layout(location = 0) out vec4 fragColor;

void main() {
  float r = length(gl_PointCoord * 2.0 - 1.0);
  if (r > 1.0) discard;
  float core = smoothstep(0.55, 0.35, r);
  fragColor = vec4(mix(uColor, vec3(1.0), core), smoothstep(1.0, 0.6, r));
}
