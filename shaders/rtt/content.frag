#version 450 core
// Normal-coloured objects with a little diffuse shading; the floor is checkered in world
// space so the texture has fine detail for its mipmaps to filter.
in vec3 vNormal;
in vec3 vWorld;
layout(location = 0) out vec4 fragColor;
uniform bool uFloor = false;

void main() {
  vec3 n = normalize(vNormal);
  if (uFloor) {
    float check = mod(floor(vWorld.x * 2.0) + floor(vWorld.z * 2.0), 2.0);
    fragColor = vec4(mix(vec3(0.2, 0.22, 0.3), vec3(0.8, 0.82, 0.9), check), 1.0);
    return;
  }
  float diffuse = 0.35 + 0.65 * max(dot(n, normalize(vec3(0.3, 0.9, 0.4))), 0.0);
  fragColor = vec4((0.5 + 0.5 * n) * diffuse, 1.0);
}
