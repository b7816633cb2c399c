#version 450 core
// The VGP353 lecture, "Normal Map Generation": draw one full-screen quad; for every texel read its
// four neighbours n, s, e, w from the height map and write the normal, encoded (n + 1) / 2.
// Identical arithmetic to image/normalmap.cpp's heightNormal (the CPU reference).

in vec2 vUv;
layout(location = 0) out vec4 fragColor;

uniform sampler2D uHeight;  // heights in .r
uniform float uScale;       // height of the full 0..1 range in texel widths
uniform bool uWrap;         // tileable: neighbours wrap around the edges
uniform bool uSlide;        // the slide's formula as written (mirrored x, z = 1 − |d|)

// texelFetch at integer coordinates: exact neighbours for any texture size and filtering.
float heightAt(ivec2 p, ivec2 size) {
  // p is at most one texel outside; GLSL's % is undefined for negative operands, so add first.
  p = uWrap ? (p + size) % size : clamp(p, ivec2(0), size - 1);
  return texelFetch(uHeight, p, 0).r;
}

void main() {
  ivec2 size = textureSize(uHeight, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);  // the framebuffer is exactly the texture's size
  // Texture rows grow upwards (t), so north is +y here; image/normalmap.h's north is the
  // row above in the picture — the same texel once uploaded bottom row first.
  float n = heightAt(p + ivec2(0, 1), size);
  float s = heightAt(p - ivec2(0, 1), size);
  float e = heightAt(p + ivec2(1, 0), size);
  float w = heightAt(p - ivec2(1, 0), size);
  vec3 d;
  if (uSlide) {
    // d = vec3(e.x - w.x, s.y - n.y, 0.0); d.z = 1.0 - sqrt(dot(d, d)); d = normalize(d);
    d = vec3(e - w, s - n, 0.0) * (0.5 * uScale);
    d.z = 1.0 - sqrt(d.x * d.x + d.y * d.y);
  } else {
    // The height field's true normal (−∂h/∂x, −∂h/∂y, 1) from central differences.
    d = vec3(0.5 * uScale * (w - e), 0.5 * uScale * (s - n), 1.0);
  }
  fragColor = vec4(normalize(d) * 0.5 + 0.5, 1.0);
}
