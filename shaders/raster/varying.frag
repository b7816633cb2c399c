#version 450 core
// raster::drawTriangles' default fragment shader: output the interpolated varying 0.
in vec4 vVarying0;
layout(location = 0) out vec4 fragColor;

void main() { fragColor = vVarying0; }
