#version 450 core
// The environment behind everything: each pixel looks up the direction of its view ray.
// uInvViewProj inverts projection × (view rotation only), so the sky sits at infinity
// and does not move when the camera translates.
in vec2 vUv;
layout(location = 0) out vec4 fragColor;
layout(binding = 0) uniform samplerCube uEnvironment;
uniform mat4 uInvViewProj;

void main() {
  vec4 p = uInvViewProj * vec4(2.0 * vUv - 1.0, 1.0, 1.0);
  fragColor = vec4(texture(uEnvironment, p.xyz / p.w).rgb, 1.0);
}
