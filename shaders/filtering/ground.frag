#version 450 core
// One plain texture() call: all filtering (minification filter, mip selection,
// anisotropy, LOD bias) comes from the sampler object bound to unit 0, so the variants
// differ only in sampler state. FLAT draws the distant ground beyond the textured part
// in the texture's mean colour (what any correct filter converges to out there).
in vec2 vUv;
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform sampler2D uTexture;
uniform bool uFlat = false;
uniform vec3 uMeanColor;

void main() {
  fragColor = vec4(uFlat ? uMeanColor : texture(uTexture, vUv).rgb, 1.0);
}
