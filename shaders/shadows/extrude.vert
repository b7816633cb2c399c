#version 450 core
// GPU shadow-volume extrusion (WWDC 2003 session 212, ATI's Pipe Dream demo): every face has its
// own three vertices carrying the face normal, and a degenerate quad sits on every
// edge. A face turned away from the light is shot back to infinity — all three of its
// vertices agree, because n·(L − p) is the same for every point p of the face's plane
// — so each face either stays (near cap) or moves whole (far cap), and the quads on
// edges between a staying and a moving face stretch into the volume's sides.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aFaceNormal;

uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProj;
uniform vec3 uLightPos;  // world space
// 0: faces turned away go to infinity. Else the distance from the light they go to instead:
// a bounded volume, which the caller picks far enough that the difference lies wholly
// outside everything the eye can see (render/pipedream/renderer.h, "bounded volumes").
uniform float uExtrudeTo;

void main() {
  vec3 p = (uModel * vec4(aPosition, 1.0)).xyz;
  vec3 n = uNormalMatrix * aFaceNormal;
  // w = 0: the direction away from the light, a point at infinity (see volume.vert).
  vec4 away = uExtrudeTo > 0.0 ? vec4(uLightPos + uExtrudeTo * normalize(p - uLightPos), 1.0) : vec4(p - uLightPos, 0.0);
  vec4 world = dot(n, uLightPos - p) > 0.0 ? vec4(p, 1.0) : away;
  gl_Position = uViewProj * world;
}
