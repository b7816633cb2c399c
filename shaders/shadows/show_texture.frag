#version 450 core
// Shows a texture over the whole viewport (the planar shadow texture).
in vec2 vUv;
layout(binding = 0) uniform sampler2D uTexture;
layout(location = 0) out vec4 fragColor;

void main() { fragColor = vec4(texture(uTexture, vUv).rgb, 1.0); }
