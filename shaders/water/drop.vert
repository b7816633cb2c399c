#version 450 core
// A drop is drawn as one quad around its centre (two triangles from gl_VertexID, no
// buffers), in texel coordinates of the state texture.
uniform vec2 uCentre;     // texels, texel (x, y) has its centre at (x + ½, y + ½)
uniform float uReach;     // 3 · radius, plus a texel so no covered texel is missed
uniform vec2 uStateSize;  // texels

out vec2 vTexel;  // position in texels

void main() {
  const vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vTexel = uCentre + corners[gl_VertexID] * uReach;
  gl_Position = vec4(vTexel / uStateSize * 2.0 - 1.0, 0.0, 1.0);
}
