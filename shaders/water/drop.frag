#version 450 core
// "Waves will eventually die. Draw new waves into texture periodically." A Gaussian splash
// added to the heights by additive blending (ONE, ONE); velocities get 0 added.
in vec2 vTexel;
layout(location = 0) out vec2 fragAdd;

uniform vec2 uCentre;
uniform float uRadius;
uniform float uAmplitude;

void main() {
  // gl_FragCoord.xy is the texel centre: the same points sim::WaveField::addDrop evaluates.
  vec2 offset = gl_FragCoord.xy - uCentre;
  float d2 = dot(offset, offset);
  float reach = 3.0 * uRadius;
  if (d2 >= reach * reach) discard;
  fragAdd = vec2(uAmplitude * exp(-d2 / (uRadius * uRadius)), 0.0);
}
