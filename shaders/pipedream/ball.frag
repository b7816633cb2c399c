#version 450 core
// A chrome ball reflecting the room (a cube map rendered from the stage), blurrier and
// more see-through the faster it moves (WWDC 2003 session 212: "we lower the mip level bias ... we also
// change the opacity"): uLodBias and uOpacity come from blurOf().
layout(binding = 0) uniform samplerCube uEnvironment;
uniform vec3 uEye;
uniform float uLodBias;
uniform float uOpacity;
uniform float uColorScale;  // as in scene.frag (the cube map holds plain linear light)
in vec3 vWorld;
in vec3 vNormal;
layout(location = 0) out vec4 fragColor;
layout(location = 1) out vec4 fragWeights;

void main() {
  vec3 n = normalize(vNormal);
  vec3 v = normalize(vWorld - uEye);
  vec3 r = reflect(v, n);
  vec3 environment = texture(uEnvironment, r, uLodBias).rgb;
  float fresnel = 0.55 + 0.45 * pow(1.0 - max(dot(-v, n), 0.0), 4.0);
  fragColor = vec4((vec3(0.015) + vec3(0.95, 0.97, 1.0) * environment * fresnel) * uColorScale, uOpacity);
  fragWeights = vec4(0.0);  // reflections are not lit by the lights: a dynamic shadow leaves them
}
