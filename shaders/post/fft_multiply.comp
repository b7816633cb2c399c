#version 450 core
// Frequency-domain filtering: every frequency of the (two-lane) transform times H(u, v).
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Data { vec4 data[]; };
layout(std430, binding = 2) readonly buffer Transfer { vec2 transfer[]; };
uniform int uCount;

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= uCount) return;
  vec2 h = transfer[i];
  vec4 d = data[i];
  data[i] = vec4(cmul(d.xy, h), cmul(d.zw, h));
}
