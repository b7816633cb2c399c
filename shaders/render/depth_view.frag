#version 450 core
// Shows a depth texture as gray: white = 1.0 (far), black = 0.0 (near), like the
// lecture's "depth buffer visualized". LINEARIZE maps perspective depth back to
// eye distance between uNear and uFar first, for perspective scenes.
in vec2 vUv;
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform sampler2D uDepth;
uniform float uNear = 0.1;
uniform float uFar = 100.0;

void main() {
  float d = texture(uDepth, vUv).r;
#ifdef LINEARIZE
  float ndc = 2.0 * d - 1.0;
  float eye = 2.0 * uNear * uFar / (uFar + uNear - ndc * (uFar - uNear));
  d = (eye - uNear) / (uFar - uNear);
#endif
  fragColor = vec4(vec3(d), 1.0);
}
