#version 450 core
// Normal mapping, fragment stage. NORMAL_SOURCE: 0 vertex normal, 1 tangent-space map
// (MikkTSpace per-pixel rule), 2 object-space map. DIRECTX: the map's green points down.
// OUTPUT_NORMAL: write the shading normal as (n + 1) / 2 instead of lighting.
in vec3 vWorldPos;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv;

layout(binding = 0) uniform sampler2D uNormalMap;
uniform mat3 uNormalMatrix;
uniform float uMirror;  // sign(det(model)): a mirroring model flips the bitangent
uniform vec3 uEye;
uniform int uLightCount;
uniform vec3 uLightDirection[4];
uniform vec3 uLightColor[4];
uniform int uPointCount;         // point lights: direction and falloff per pixel
uniform vec3 uPointPosition[4];
uniform vec3 uPointColor[4];
uniform float uPointRange[4];     // 1 / (1 + (d / range)²); 0: no falloff
layout(binding = 1) uniform sampler2D uAlbedoMap;
uniform bool uHasAlbedoMap;
uniform vec3 uAlbedo;
uniform vec3 uAmbient;
uniform float uSpecular;
uniform float uShininess;

out vec4 fragColor;

// Lambert diffuse + Blinn-Phong highlight for one light arriving from unit direction l.
vec3 shade(vec3 n, vec3 v, vec3 l, vec3 lightColor, vec3 albedo) {
  float diffuse = max(dot(n, l), 0.0);
  float highlight = diffuse > 0.0 ? pow(max(dot(n, normalize(l + v)), 0.0), uShininess) : 0.0;
  return lightColor * (albedo * diffuse + uSpecular * highlight);
}

vec3 mapTexel() {
  vec3 m = texture(uNormalMap, vUv).xyz * 2.0 - 1.0;
#ifdef DIRECTX
  m.y = -m.y;
#endif
  return m;
}

void main() {
#if NORMAL_SOURCE == 1
  vec3 m = mapTexel();
  float sgn = (vTangent.w < 0.0 ? -1.0 : 1.0) * uMirror;
  vec3 b = sgn * cross(vNormal, vTangent.xyz);
  vec3 n = normalize(m.x * vTangent.xyz + m.y * b + m.z * vNormal);
#elif NORMAL_SOURCE == 2
  vec3 n = normalize(uNormalMatrix * mapTexel());
#else
  vec3 n = normalize(vNormal);
#endif

#ifdef OUTPUT_NORMAL
  fragColor = vec4(n * 0.5 + 0.5, 1.0);
#else
  vec3 v = normalize(uEye - vWorldPos);
  vec3 albedo = uHasAlbedoMap ? uAlbedo * texture(uAlbedoMap, vUv).rgb : uAlbedo;
  vec3 color = uAmbient * albedo;
  for (int i = 0; i < uLightCount; ++i) color += shade(n, v, uLightDirection[i], uLightColor[i], albedo);
  for (int i = 0; i < uPointCount; ++i) {
    vec3 toLight = uPointPosition[i] - vWorldPos;
    float d = length(toLight);
    float falloff = uPointRange[i] > 0.0 ? 1.0 / (1.0 + (d / uPointRange[i]) * (d / uPointRange[i])) : 1.0;
    color += shade(n, v, toLight / max(d, 1e-6), uPointColor[i] * falloff, albedo);
  }
  fragColor = vec4(color, 1.0);
#endif
}
