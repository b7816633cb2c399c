#version 450 core
// A normal map shown as an image across the viewport (v up, like the mesh's UVs).
in vec2 vUv;
layout(binding = 0) uniform sampler2D uMap;
out vec4 fragColor;

void main() { fragColor = vec4(texture(uMap, vUv).rgb, 1.0); }
