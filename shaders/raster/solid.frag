#version 450 core
// One colour everywhere the current state lets fragments through: basics/reference
// shows GL's stencil counts by drawing this once per count under glStencilFunc(GL_EQUAL, k).
in vec2 vUv;
layout(location = 0) out vec4 fragColor;
uniform vec4 uColor;

void main() { fragColor = uColor; }
