#version 450 core
// Mirror reflection: cube map lookup by the reflection vector (GL_REFLECTION_MAP +
// GL_TEXTURE_CUBE_MAP) or, with SPHERE_MAP, sphere-map lookup (GL_SPHERE_MAP).
#include "env/texgen.glsl"

in vec3 vEyePos;
in vec3 vEyeNormal;
#ifdef PER_VERTEX
in vec3 vTexCoord;
#endif
layout(location = 0) out vec4 fragColor;

#ifdef SPHERE_MAP
layout(binding = 0) uniform sampler2D uEnvironment;
#else
layout(binding = 0) uniform samplerCube uEnvironment;
#endif
uniform mat3 uEyeToEnv;
uniform vec3 uTint = vec3(1.0);  // a mirror's colour (1 = perfect chrome)

void main() {
#ifdef PER_VERTEX
  vec3 coord = vTexCoord;
#else
  vec3 coord = texgen(vEyePos, normalize(vEyeNormal), uEyeToEnv);
#endif
#ifdef SPHERE_MAP
  vec3 c = texture(uEnvironment, coord.xy).rgb;
#else
  vec3 c = texture(uEnvironment, coord).rgb;
#endif
  fragColor = vec4(c * uTint, 1.0);
}
