#version 450 core
// The filtered frame back into a texture: (R + iG, B) of the inverse transform, plus the
// filter's offset, clamped to 0..1 for an RGBA8 target (FLOAT_OUTPUT: an RGBA32F one, whose
// encoded HDR values pass through unclamped); alpha from the input frame.
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Source { vec4 src[]; };
#ifdef FLOAT_OUTPUT
layout(rgba32f, binding = 0) writeonly uniform image2D uOutput;
#else
layout(rgba8, binding = 0) writeonly uniform image2D uOutput;
#endif
uniform sampler2D uInput;
uniform float uOffset;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(uOutput);
  if (p.x >= size.x || p.y >= size.y) return;
  vec4 d = src[p.y * size.x + p.x];
#ifdef FLOAT_OUTPUT
  vec3 rgb = d.xyz + uOffset;
#else
  vec3 rgb = clamp(d.xyz + uOffset, 0.0, 1.0);
#endif
  imageStore(uOutput, p, vec4(rgb, texelFetch(uInput, p, 0).a));
}
