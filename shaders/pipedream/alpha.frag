#version 450 core
// Destination alpha := light uLight's dim factor, before its quad. uRemoved: the earlier
// lights whose dynamic shadow already covers this pixel (the draw's stencil test picks the
// pixels with exactly those marker bits). What is left here is 1 − R of the pixel's light,
// R = Σ removed weights; taking light uLight away too leaves 1 − R − w, so the colour is
// multiplied by (1 − R − w) / (1 − R).
layout(binding = 0) uniform sampler2D uWeights;
uniform int uLight;
uniform int uRemoved;
in vec2 vUv;
layout(location = 0) out vec4 fragColor;

void main() {
  vec4 w = texelFetch(uWeights, ivec2(gl_FragCoord.xy), 0);
  float removed = 0.0;
  for (int i = 0; i < 4; ++i)
    if (((uRemoved >> i) & 1) != 0) removed += w[i];
  float left = 1.0 - removed;
  float factor = left > 1e-4 ? (left - w[uLight]) / left : 1.0;
  fragColor = vec4(0.0, 0.0, 0.0, clamp(factor, 0.0, 1.0));
}
