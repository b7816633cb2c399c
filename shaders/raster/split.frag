#version 450 core
// basics/reference: OpenGL's picture left of uSplitX, glint::raster's (uploaded from the
// CPU) right of it, pixel for pixel (texelFetch: both are rendered at the target's size),
// with a thin divider. uDepth: both textures hold depth; shown as gray, white = far.
in vec2 vUv;
layout(location = 0) out vec4 fragColor;

layout(binding = 0) uniform sampler2D uGl;   // colour, or the GL depth buffer itself
layout(binding = 1) uniform sampler2D uCpu;  // colour (RGBA8), or depth (R32F)
uniform int uSplitX;                          // first pixel column of the CPU half
uniform bool uDepth;

const vec3 kDivider = vec3(0.95, 0.95, 0.95);

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (p.x == uSplitX - 1 || p.x == uSplitX) {
    fragColor = vec4(kDivider, 1.0);
    return;
  }
  vec4 c = p.x < uSplitX ? texelFetch(uGl, p, 0) : texelFetch(uCpu, p, 0);
  fragColor = uDepth ? vec4(c.rrr, 1.0) : vec4(c.rgb, 1.0);
}
