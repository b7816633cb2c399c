#version 450 core
// A frame into the FFT's buffer (render/post/fft.h): LANES 1 stores the luma as (L, 0);
// LANES 2 stores (R + iG, B + 0i). Row 0 of the buffer is texel row 0, the picture's top.
#include "post/common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#if !defined(LANES)
#define LANES 1  // the default lets the file compile on its own (the glslang check)
#endif
#if LANES == 1
#define T vec2
#else
#define T vec4
#endif
layout(std430, binding = 1) writeonly buffer Destination { T dst[]; };
uniform sampler2D uInput;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(uInput, 0);
  if (p.x >= size.x || p.y >= size.y) return;
  vec4 c = texelFetch(uInput, p, 0);
#if LANES == 1
  dst[p.y * size.x + p.x] = vec2(dot(c.rgb, kLuma), 0.0);
#else
  dst[p.y * size.x + p.x] = vec4(c.r, c.g, c.b, 0.0);
#endif
}
