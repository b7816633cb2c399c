#version 450 core
// A full-screen quad of one colour: WWDC 2003 session 212's shadow-coloured overlay under the
// stencil test, and the dim-factor pass of WWDC 2003 session 212 (its colour is unused there:
// the blend multiplies the destination by its own alpha).
uniform vec4 uColor;
in vec2 vUv;
layout(location = 0) out vec4 fragColor;

void main() { fragColor = uColor; }
