#version 450 core
// The reference pipeline's input as a vertex shader: positions are already in clip
// space (what raster::Vertex::position holds) and varying 0 is passed through, so GL
// and glint::raster draw exactly the same primitives (tests/raster_gl, basics/reference).
layout(location = 0) in vec4 aClipPosition;
layout(location = 1) in vec4 aVarying0;

out vec4 vVarying0;

void main() {
  vVarying0 = aVarying0;
  gl_Position = aClipPosition;
}
