#version 450 core
// WWDC 2003 session 212's motion-blurred ball (pipedream/motion_blur.h): a unit sphere whose
// seam lies across local +z, turned so that +z is the velocity (uFrame); the rear half
// (aRear = 1) is moved back by the distance travelled while the shutter is open, and the
// degenerate quads on the seam stretch into the pill's sides. stretchVertex() in
// motion_blur.cpp is this arithmetic on the CPU; the tests compare the two (CAPTURE: the
// world position is captured by transform feedback).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in float aRear;

uniform mat3 uFrame;
uniform vec3 uCentre;
uniform vec3 uVelocity;
uniform float uRadius;
uniform float uShutter;
uniform mat4 uViewProj;

#ifdef CAPTURE
layout(xfb_buffer = 0, xfb_offset = 0) out vec3 vWorld;
#else
out vec3 vWorld;
#endif
out vec3 vNormal;

void main() {
  vec3 n = uFrame * aPosition;
  vWorld = uCentre + uRadius * n - aRear * uShutter * uVelocity;
  vNormal = n;
  gl_Position = uViewProj * vec4(vWorld, 1.0);
}
