#pragma once
// glint/image/dot3.h — the arithmetic of DOT3 bump mapping (the WWDC 2001 talk), without GL: the
// CPU reference both GPU paths of render/bump/dot3.h are tested against.
//
// Contents
//   localLightVector   the light vector in a polygon's local (tangent) space
//   encodeLightVector  a vector → unsigned-byte vertex colour, (v + 1) / 2 · 255
//   combineDot3Rgb     GL_DOT3_RGB of two colours, exactly as the OpenGL spec defines it
//   combineModulate    GL_MODULATE
//
// The WWDC 2001 talk's recipe: "the dot product operation requires that the light vector be in local
// coordinate space. So we must rotate this light by the inverse rotation of the polygon."
// The light vector is then encoded into the vertex colour; texture unit 0 holds the normal
// map encoded the same way; combiner stage 1 = DOT3_RGB(primary colour, normal map), stage
// 2 = MODULATE(previous, base texture in unit 1).
//
// The OpenGL 1.3 spec (table 3.20; 4.5 compatibility §16.2) defines DOT3_RGB as
//     4 · ((a_r − ½)(b_r − ½) + (a_g − ½)(b_g − ½) + (a_b − ½)(b_b − ½))
// placed in r, g and b, then clamped to [0, 1]. With a = (l + 1)/2 and b = (n + 1)/2 every
// (x − ½) is half a vector component, so the sum is exactly l · n: the diffuse term, with
// back-facing light clamped to black.

#include "glint/core/math.h"

#include <glm/gtc/quaternion.hpp>

#include <cstdint>

namespace glint {

using glm::quat;
using u8vec3 = glm::u8vec3;

/// Unit vector from `localVertex` to the light, in the polygon's local frame. The polygon is
/// placed in the world by `rotation` then `translation` (world = rotation · local + translation);
/// the world light vector is rotated back by the inverse (conjugate) quaternion, as the WWDC 2001 talk does.
/// A light exactly at the vertex gives (0, 0, 1).
vec3 localLightVector(const quat& rotation, vec3 translation, vec3 localVertex, vec3 lightWorld);

/// (v + 1) / 2 · 255 per component, rounded to the nearest byte: −1 → 0, 0 → 128, +1 → 255.
/// Components outside [−1, 1] are clamped.
u8vec3 encodeLightVector(vec3 v);
/// The inverse: byte / 255 · 2 − 1 (not normalized).
vec3 decodeLightVector(u8vec3 c);

/// GL_DOT3_RGB of colours a and b in [0, 1]³ (one value, replicated to r, g, b by GL):
/// clamp(4 · Σ (a − ½)(b − ½), 0, 1).
float combineDot3Rgb(vec3 a, vec3 b);
/// GL_MODULATE: a · b per component.
inline vec3 combineModulate(vec3 a, vec3 b) { return a * b; }

}  // namespace glint
