#version 450 core
// The cheaper shader for pieces no light reaches (WWDC 2003 session 212: "those polygons that we know
// are in shadow we can draw with a simpler shader"): ambient only, dim factor 1 (a
// dynamic shadow has nothing left to take away), no weights.
uniform float uAmbient;
uniform float uColorScale;  // as in scene.frag
in vec3 vAlbedo;
layout(location = 0) out vec4 fragColor;
layout(location = 1) out vec4 fragWeights;

void main() {
  fragColor = vec4(vAlbedo * uAmbient * uColorScale, 1.0);
  fragWeights = vec4(0.0);
}
