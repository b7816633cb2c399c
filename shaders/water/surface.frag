#version 450 core
// Water shaded with the normal map made from the simulated heights: Fresnel-weighted mix
// of the cube-map reflection and the refracted pool floor, plus the sun's glints.

in vec3 vWorld;
in vec2 vUv;
layout(location = 0) out vec4 fragColor;

layout(binding = 1) uniform sampler2D uNormalMap;     // (n + 1)/2, tangent space of the grid
layout(binding = 2) uniform samplerCube uEnvironment; // world space, display-encoded
layout(binding = 3) uniform sampler2D uFloor;         // pool tiles
uniform vec3 uEye;
uniform float uHalfSize;
uniform float uDepth;
uniform float uF0;
uniform vec3 uAbsorption;
uniform vec3 uSunDirection;
uniform vec3 uSunColor;
uniform float uSunShininess;

void main() {
  // Tangent space of the grid: u along +X, v along −Z, normal +Y (mesh/mesh.h's makeGrid).
  vec3 m = texture(uNormalMap, vUv).xyz * 2.0 - 1.0;
  vec3 n = normalize(vec3(m.x, m.z, -m.y));
  vec3 v = normalize(uEye - vWorld);
  float nDotV = max(dot(n, v), 1e-3);

  // Reflection: the sky. Schlick's approximation of Fresnel for the mix.
  vec3 r = reflect(-v, n);
  r.y = abs(r.y);  // a wave can tilt r below the horizon; the pool's rim would hide that sky anyway
  vec3 reflected = texture(uEnvironment, r).rgb;
  float fresnel = uF0 + (1.0 - uF0) * pow(1.0 - nDotV, 5.0);

  // Refraction: follow the bent ray down to the floor at y = −depth and look at the tiles
  // there; light fades along the path, red first, which makes water blue-green.
  vec3 t = refract(-v, n, 1.0 / 1.33);
  float along = uDepth / max(-t.y, 0.05);
  vec3 floorPoint = vWorld + t * along;
  vec2 floorUv = floorPoint.xz / (2.0 * uHalfSize) + 0.5;
  vec3 floorColor = texture(uFloor, floorUv * 2.0).rgb;
  vec3 transmittance = exp(-uAbsorption * along);
  vec3 deepWater = vec3(0.02, 0.12, 0.16);
  vec3 refracted = floorColor * transmittance + deepWater * (1.0 - transmittance);

  // The sun's glints: a tight highlight around the mirror direction.
  vec3 sun = uSunColor * pow(max(dot(r, normalize(uSunDirection)), 0.0), uSunShininess) * 4.0;

  fragColor = vec4(mix(refracted, reflected, fresnel) + sun * fresnel * 10.0, 1.0);
}
