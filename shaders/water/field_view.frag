#version 450 core
// A simulation texture as a picture: heights as gray levels, or a normal map's colours.
in vec2 vUv;
layout(location = 0) out vec4 fragColor;

uniform sampler2D uField;
uniform bool uHeight;  // true: .r is a height around 0; false: .rgb are colours already
uniform float uGain;   // gray levels per unit of height

void main() {
  // texelFetch: exact texels whatever the texture's filtering (the state is NEAREST, the
  // normal map mipmapped); the square viewport is resampled nearest-neighbour.
  ivec2 size = textureSize(uField, 0);
  ivec2 texel = min(ivec2(vUv * vec2(size)), size - 1);
  vec4 v = texelFetch(uField, texel, 0);
  fragColor = uHeight ? vec4(vec3(clamp(0.5 + uGain * v.r, 0.0, 1.0)), 1.0) : vec4(v.rgb, 1.0);
}
