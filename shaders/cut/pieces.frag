#version 450 core
// uMode 0: the piece's colour, gently shaded by the facet's angle to the viewer's light
//          (only to tell faces apart; lit/shadowed is the colour itself).
// uMode 1: the piece's colour as it is (the destination-alpha dim factor, a grey level).
// uMode 2: uColor (wireframe, light markers).
// uMode 3: lit as a renderer would with the cut: N·L for the pieces the light reaches,
//          ambient only for the ones it does not (vColor.a: 1 lit, 0 shadowed).
uniform int uMode;
uniform vec4 uColor;
uniform vec3 uLight;
in vec4 vColor;
in vec3 vWorld;
in vec3 vNormal;
layout(location = 0) out vec4 fragColor;

void main() {
  vec3 n = normalize(cross(dFdx(vWorld), dFdy(vWorld)));
  float facing = abs(dot(n, normalize(uLight - vWorld)));
  if (uMode == 0) {
    fragColor = vec4(vColor.rgb * (0.55 + 0.45 * facing), 1.0);
  } else if (uMode == 1) {
    fragColor = vec4(vColor.rgb, 1.0);
  } else if (uMode == 2) {
    fragColor = uColor;
  } else {
    vec3 albedo = vec3(0.78, 0.74, 0.68);
    float diffuse = vColor.a * max(dot(normalize(vNormal), normalize(uLight - vWorld)), 0.0);
    fragColor = vec4(albedo * (0.18 + 0.82 * diffuse), 1.0);
  }
}
