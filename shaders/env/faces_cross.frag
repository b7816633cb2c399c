#version 450 core
// The six faces of a cube map unfolded as a cross, as the viewer inside the cube sees
// them turning around (the WWDC 2001 talk: "a contiguous panorama of the scene as viewed from the
// rendered object"):
//              [+Y]
//   [−X] [−Z] [+X] [+Z]     front (−Z) is second; left, right and back follow around
//              [−Y]
// Each cell looks along its face's axis with a right/up frame continuous with its
// neighbours, so edges line up. Lookups use level 0 (the faces as stored).
in vec2 vUv;
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform samplerCube uEnvironment;
uniform float uAspect;  // viewport width / height
uniform vec3 uBackground = vec3(0.12, 0.13, 0.15);

void main() {
  // Fit a 4:3 area into the viewport, centred.
  vec2 p = vUv;
  if (uAspect > 4.0 / 3.0) p.x = (p.x - 0.5) * uAspect / (4.0 / 3.0) + 0.5;
  else p.y = (p.y - 0.5) * (4.0 / 3.0) / uAspect + 0.5;
  vec2 cell = p * vec2(4.0, 3.0);
  ivec2 c = ivec2(floor(cell));
  vec2 ab = 2.0 * fract(cell) - 1.0;  // −1..1 inside the cell, +y up
  vec3 forward, right, up;
  if (c.y == 1 && c.x >= 0 && c.x < 4) {
    const vec3 fwd[4] = vec3[](vec3(-1, 0, 0), vec3(0, 0, -1), vec3(1, 0, 0), vec3(0, 0, 1));
    forward = fwd[c.x];
    up = vec3(0, 1, 0);
    right = cross(forward, up);
  } else if (c.x == 1 && c.y == 2) {
    forward = vec3(0, 1, 0), right = vec3(1, 0, 0), up = vec3(0, 0, 1);
  } else if (c.x == 1 && c.y == 0) {
    forward = vec3(0, -1, 0), right = vec3(1, 0, 0), up = vec3(0, 0, -1);
  } else {
    fragColor = vec4(uBackground, 1.0);
    return;
  }
  vec3 dir = forward + ab.x * right + ab.y * up;
  // A thin dark line on each face's border shows where one face ends.
  float edge = max(abs(ab.x), abs(ab.y)) > 0.992 ? 0.35 : 1.0;
  fragColor = vec4(textureLod(uEnvironment, dir, 0.0).rgb * edge, 1.0);
}
