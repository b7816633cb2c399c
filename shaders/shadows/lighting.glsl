// Shared lighting for the shadow scenes: one positional light, Blinn-Phong.
uniform vec3 uLightPos;
uniform vec3 uEye;
uniform vec3 uColor;
uniform float uAmbient;  // fraction of the albedo a fully shadowed pixel keeps
uniform bool uGround;    // the ground gets a checker pattern so shadows read clearly
// 0 full, 1 ambient only, 2 direct only (diffuse + specular), 3 visibility as gray,
// 4 full colour with the destination-alpha dim factor ambient / full (WWDC 2003 session 212)
uniform int uTerms;

vec3 albedo(vec3 p) {
  if (!uGround) return uColor;
  vec2 cell = floor(p.xz * 2.0);  // 0.5-unit squares
  return uColor * (mod(cell.x + cell.y, 2.0) < 0.5 ? 1.0 : 0.82);
}

vec4 shade(vec3 p, vec3 normal, float visibility) {
  vec3 n = normalize(normal);
  vec3 v = normalize(uEye - p);
  // Light the side facing the viewer (the pinwheel's fins are seen from both sides).
  if (dot(n, v) < 0.0) n = -n;
  vec3 l = normalize(uLightPos - p);
  vec3 h = normalize(l + v);
  vec3 base = albedo(p);
  float diffuse = max(dot(n, l), 0.0);
  float specular = diffuse > 0.0 ? 0.35 * pow(max(dot(n, h), 0.0), 48.0) : 0.0;
  vec3 ambient = uAmbient * base;
  vec3 direct = (1.0 - uAmbient) * diffuse * base + vec3(specular);
  if (uTerms == 1) return vec4(ambient, 1.0);
  if (uTerms == 2) return vec4(direct * visibility, 1.0);
  if (uTerms == 3) return vec4(vec3(visibility), 1.0);
  vec3 full = ambient + direct * visibility;
  if (uTerms == 4) {
    // How much of this pixel a shadow keeps: multiply by it to go back to ambient.
    float keep = dot(ambient, vec3(0.2126, 0.7152, 0.0722)) / max(dot(full, vec3(0.2126, 0.7152, 0.0722)), 1e-4);
    return vec4(full, keep);
  }
  return vec4(full, 1.0);
}
