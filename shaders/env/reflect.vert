#version 450 core
// A mirror object lit only by its environment. Eye-space position and normal go to the
// fragment shader, which generates the lookup per pixel; with PER_VERTEX the lookup is
// generated here and interpolated, exactly what glTexGen does (for comparison with the
// classic path; per pixel is better near silhouettes, where r changes fastest).
#include "common/attributes.glsl"
#include "env/texgen.glsl"

uniform mat4 uModel;
uniform mat3 uNormalMatrix;  // inverse transpose of uModel's 3×3
uniform mat4 uView;
uniform mat4 uProj;
uniform mat3 uEyeToEnv;

out vec3 vEyePos;
out vec3 vEyeNormal;
#ifdef PER_VERTEX
out vec3 vTexCoord;
#endif

void main() {
  vec4 eye = uView * (uModel * vec4(aPosition, 1.0));
  vEyePos = eye.xyz;
  vEyeNormal = mat3(uView) * (uNormalMatrix * aNormal);  // rigid view: no inverse transpose needed
#ifdef PER_VERTEX
  vTexCoord = texgen(vEyePos, normalize(vEyeNormal), uEyeToEnv);
#endif
  gl_Position = uProj * eye;
}
