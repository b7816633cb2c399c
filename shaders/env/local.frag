#version 450 core
// Lambert from one directional light plus ambient, and optional stripes from the UVs so
// the objects' motion reads in the reflections.
in vec3 vNormal;
in vec2 vUv;
layout(location = 0) out vec4 fragColor;
uniform vec3 uColor;
uniform vec3 uLightDir = vec3(0.4, 0.8, 0.45);  // towards the light
uniform float uStripes = 0.0;                    // stripes per unit of u (0 = none)

void main() {
  float diffuse = max(dot(normalize(vNormal), normalize(uLightDir)), 0.0);
  float stripe = uStripes > 0.0 ? 0.75 + 0.25 * step(0.5, fract(vUv.x * uStripes)) : 1.0;
  fragColor = vec4(uColor * stripe * (0.25 + 0.75 * diffuse), 1.0);
}
