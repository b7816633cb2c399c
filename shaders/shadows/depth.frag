#version 450 core
// The shadow map pass writes depth only (the FBO has no colour attachment).
void main() {}
