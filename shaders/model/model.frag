#version 450 core
// A model file lit by glint view's studio rig (scenes/model.h): three directional lights
// that follow the camera (key, fill, rim) and the environment cube for ambient light and
// reflections, with the material's maps toggled by the viewer's options. uShow draws one
// map's stored values as a colour instead; uMisses tints the texels a bake's rays missed.
#include "common/srgb.glsl"
in vec3 vWorld;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv;
in vec4 vColor;

layout(binding = 0) uniform sampler2D uNormalMap;
layout(binding = 1) uniform sampler2D uOcclusionMap;
layout(binding = 2) uniform sampler2D uBaseColorMap;
layout(binding = 3) uniform sampler2D uShowMap;
layout(binding = 4) uniform sampler2D uMissMask;
layout(binding = 5) uniform samplerCube uEnvironment;
uniform bool uUseNormalMap, uUseOcclusion, uUseBaseColorMap, uUseVertexColor, uShow, uMisses;
uniform vec4 uBaseColor;
uniform float uRoughness;
uniform vec3 uEye;
uniform vec3 uLightDirection[3];
uniform vec3 uLightColor[3];
uniform float uEnvironmentLevels;  // mip levels of uEnvironment

out vec4 fragColor;

vec3 srgbDecode(vec3 c) { return mix(pow((c + 0.055) / 1.055, vec3(2.4)), c / 12.92, lessThanEqual(c, vec3(0.04045))); }

void main() {
  if (uShow) {
    fragColor = vec4(texture(uShowMap, vUv).rgb, 1.0);  // the stored values, as an image viewer shows them
    if (textureSize(uShowMap, 0).x == 1) fragColor.rgb = vec3(0.5, 0.0, 0.5);  // a part without this map
    return;
  }
  vec3 normal = normalize(vNormal);
  vec3 n = normal;
  if (uUseNormalMap) {
    // MikkTSpace per pixel, as the baker encoded: interpolated, unnormalized n and t.
    vec3 m = texture(uNormalMap, vUv).xyz * 2.0 - 1.0;
    vec3 b = (vTangent.w < 0.0 ? -1.0 : 1.0) * cross(vNormal, vTangent.xyz);
    n = normalize(m.x * vTangent.xyz + m.y * b + m.z * vNormal);
  }
  vec3 v = normalize(uEye - vWorld);
  if (!gl_FrontFacing) n = -n;  // back faces (an open mesh seen from inside) lit as seen
  vec3 albedo = uBaseColor.rgb;
  if (uUseBaseColorMap) albedo *= srgbDecode(texture(uBaseColorMap, vUv).rgb);
  if (uUseVertexColor) albedo *= vColor.rgb;
  float occlusion = uUseOcclusion ? texture(uOcclusionMap, vUv).r : 1.0;

  float shininess = 2.0 / max(uRoughness * uRoughness * uRoughness * uRoughness, 1e-3) - 2.0;
  vec3 colour = vec3(0.0);
  for (int i = 0; i < 3; ++i) {
    vec3 l = uLightDirection[i];
    float diffuse = max(dot(n, l), 0.0);
    float highlight = diffuse > 0.0 ? pow(max(dot(n, normalize(l + v)), 0.0), shininess) * (shininess + 8.0) / 25.0 : 0.0;
    colour += uLightColor[i] * (albedo * diffuse + 0.04 * highlight);
  }
  // The environment: its most blurred levels as the light from all around (diffuse), a
  // level by roughness for the reflection, both shadowed by the occlusion.
  vec3 ambient = srgbDecode(textureLod(uEnvironment, n, uEnvironmentLevels - 1.5).rgb);
  vec3 reflected = srgbDecode(textureLod(uEnvironment, reflect(-v, n), uRoughness * (uEnvironmentLevels - 2.0)).rgb);
  float fresnel = 0.04 + 0.96 * pow(1.0 - max(dot(n, v), 0.0), 5.0);
  colour += occlusion * (0.6 * albedo * ambient + 0.35 * fresnel * reflected);
  fragColor = vec4(srgbEncode(colour), 1.0);
  if (uMisses && texture(uMissMask, vUv).r > 0.002) fragColor.rgb = mix(fragColor.rgb, vec3(1.0, 0.08, 0.05), 0.75);
}
