#version 450 core
// Where a flattened caster lands, the ground is in shadow: black on the white texture.
layout(location = 0) out vec4 fragColor;

void main() { fragColor = vec4(0.0, 0.0, 0.0, 1.0); }
