#version 450 core
// Samples the render-to-texture result with trilinear filtering: the faces are
// minified, so the mip chain glGenerateMipmap built is what is actually read.
in vec2 vUv;
in vec3 vNormal;
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform sampler2D uTexture;

void main() {
  float shade = 0.55 + 0.45 * max(dot(normalize(vNormal), normalize(vec3(0.4, 0.7, 0.6))), 0.0);
  fragColor = vec4(texture(uTexture, vUv).rgb * shade, 1.0);
}
