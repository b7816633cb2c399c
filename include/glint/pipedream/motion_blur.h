#pragma once
// glint/pipedream/motion_blur.h — WWDC 2003 session 212's motion-blurred balls (the end of
// its "Pipe Dream" part): a ball split at a seam, stretched in the vertex shader (no GL:
// the mesh, the blur amounts and the shader's arithmetic on the CPU).
//
// Contents
//   BlurBallMesh      a unit sphere cut at its equator, the two halves joined by degenerate
//                     quads along the seam (the same trick as GPU shadow volumes)
//   buildBlurBall     makes one
//   BallBlur, blurOf  how much one ball is stretched, and how see-through and blurry it is
//   ballFrame         the rotation that turns the seam across the velocity
//   stretchVertex     the vertex shader's arithmetic on the CPU (the tests' reference)
//
// "we take our ball and split it at one of those seams ... it looks like a pill": the
// ball's mesh has its seam across its local +z axis. Each frame a ball is turned so that +z
// is its velocity (ballFrame); the vertex shader (shaders/pipedream/ball.vert) moves the
// rear half (rear = 1) back along the velocity by the distance the ball travels while the
// shutter is open, and the quads on the seam, of zero area at rest, stretch into the
// pill's sides — the mesh stays closed at any speed. Then, as WWDC 2003 session 212 says, the faster the
// ball the blurrier its environment map (a higher LOD bias) and the lower its opacity, so
// that fast balls read as see-through streaks and not as "hot dogs":
//
//   stretch = |v| · shutter
//   opacity = max(minOpacity, d / (d + stretch))    d = the ball's diameter: the share of
//                                                   the streak's length the ball covers
//   lodBias = log2(1 + stretch / d) · lodScale       one mip level per doubling of length
//
/// ```cpp run
/// const glint::vec3 velocity(4.0f, 1.0f, 0.0f);  // metres per second
/// const glint::pipedream::BlurBallMesh mesh = glint::pipedream::buildBlurBall(32, 16);
/// const glint::pipedream::BallBlur blur = glint::pipedream::blurOf(velocity, 0.12f, 1.0f / 30.0f);
/// ```

#include "glint/core/math.h"

#include <cstdint>
#include <vector>

namespace glint::pipedream {

struct BlurBallMesh {
  std::vector<vec3> positions;        ///< on the unit sphere; the seam is the circle z = 0
  std::vector<float> rear;            ///< 1 for the rear half's vertices (z ≤ 0, its own seam copy), 0 for the front
  std::vector<std::uint32_t> indices; ///< counter-clockwise from outside; seam quads last
  std::size_t seamTriangles = 0;      ///< the degenerate quads' triangles (2 per seam segment)
  /// Normals are the positions (a unit sphere); the seam copies share theirs, so the
  /// stretched quads shade as the pill's cylindrical side.
  std::size_t triangleCount() const { return indices.size() / 3; }
};

/// A sphere of `segments` around the z axis and `rings` (even) from pole to pole, cut at
/// the equator. Error(Usage) for segments < 3 or an odd or too small ring count.
BlurBallMesh buildBlurBall(int segments, int rings);

struct BallBlur {
  float stretch = 0.0f;  ///< metres the rear half moves back
  float opacity = 1.0f;
  float lodBias = 0.0f;  ///< added to the environment map's level of detail
};

/// The blur of a ball of `radius` moving at `velocity` while the shutter is open `shutter`
/// seconds.
BallBlur blurOf(vec3 velocity, float radius, float shutter, float minOpacity = 0.25f, float lodScale = 1.5f);

/// The rotation taking the mesh's +z to the direction of `velocity` (identity when it is zero).
mat3 ballFrame(vec3 velocity);

/// Where the vertex shader puts a mesh vertex: centre + frame · (radius · position), and
/// for the rear half minus velocity · shutter.
vec3 stretchVertex(vec3 position, float rear, vec3 centre, vec3 velocity, float radius, float shutter);

}  // namespace glint::pipedream
