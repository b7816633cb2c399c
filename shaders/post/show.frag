#version 450 core
// A processed frame drawn upright (frames are stored with the picture's top row at texel
// row 0), optionally split: the original left of uSplit, the result right of it, a thin
// white divider between — WWDC 2003 session 212's before/after demo.
in vec2 vUv;
uniform sampler2D uAfter;
uniform sampler2D uBefore;
uniform float uSplit;         // 0: the result only
uniform float uDividerWidth;  // in vUv.x units
out vec4 fragColor;

void main() {
  vec2 uv = vec2(vUv.x, 1.0 - vUv.y);
  if (uSplit > 0.0 && abs(vUv.x - uSplit) < 0.5 * uDividerWidth) {
    fragColor = vec4(1.0);
    return;
  }
  vec3 rgb = (vUv.x < uSplit ? texture(uBefore, uv) : texture(uAfter, uv)).rgb;
  fragColor = vec4(rgb, 1.0);
}
