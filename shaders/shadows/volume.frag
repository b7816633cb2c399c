#version 450 core
// Flat colour for shadow volumes: unseen in the stencil pass (colour writes off),
// the WWDC 2001 talk's green/blue faces in the debug view, the shadow tint when the volume is
// drawn again into colour with alpha (the WWDC 2001 talk's 85% / 50%).
uniform vec4 uColor;
layout(location = 0) out vec4 fragColor;

void main() { fragColor = uColor; }
