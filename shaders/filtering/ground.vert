#version 450 core
// The ground plane: world-space UVs repeat the texture every tile, so the far part of
// the plane packs hundreds of texels into each pixel — where filters differ. The plane
// follows the camera in whole tiles (uOffsetZ), which leaves the texture in place.
#include "common/attributes.glsl"
uniform mat4 uViewProj;
uniform float uOffsetZ = 0.0;
out vec2 vUv;

void main() {
  vUv = aUv;
  gl_Position = uViewProj * vec4(aPosition + vec3(0.0, 0.0, uOffsetZ), 1.0);
}
