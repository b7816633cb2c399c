#version 450 core
// Planar projected shadows into a texture (the VGP353 lecture): the caster is flattened onto
// the ground along the light's rays (uShadowMatrix, render/shadows/planar.h), then
// mapped into the shadow texture, which sees the ground from straight above
// (uGroundClip: world x, z → clip x, y).
#include "common/attributes.glsl"

uniform mat4 uModel;
uniform mat4 uShadowMatrix;
uniform mat4 uGroundClip;

void main() {
  // The projected point is homogeneous (w = dot(plane, L) − dot(plane, p)); it is
  // divided out before the ground mapping, which ignores y.
  vec4 flat_ = uShadowMatrix * (uModel * vec4(aPosition, 1.0));
  gl_Position = uGroundClip * vec4(flat_.xyz / flat_.w, 1.0);
}
