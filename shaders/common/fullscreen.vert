#version 450 core
// One triangle that covers the whole viewport, from gl_VertexID alone (no buffers):
// vertices (-1,-1), (3,-1), (-1,3). vUv is 0..1 across the viewport.
out vec2 vUv;

void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  vUv = 0.5 * p + 0.5;
  gl_Position = vec4(p, 0.0, 1.0);
}
