#version 450 core
// A CPU-built shadow volume (shadows/volume.h): homogeneous object-space
// vertices, w = 1 on the caster and w = 0 for points extruded to infinity. A w = 0
// vertex is a direction; uModel maps it as one (no translation) and the projection
// sends it to its vanishing point, so the volume reaches infinity without a length.
layout(location = 0) in vec4 aPosition;

uniform mat4 uModel;
uniform mat4 uViewProj;

void main() { gl_Position = uViewProj * (uModel * aPosition); }
