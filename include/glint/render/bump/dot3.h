#pragma once
// glint/render/bump/dot3.h — DOT3 bump mapping as the WWDC 2001 talk shows it: the
// light vector per vertex in the polygon's local space, encoded in the vertex colour; the
// normal map in texture unit 0; combiner stage 1 = GL_DOT3_RGB(primary colour, normal map);
// stage 2 = GL_MODULATE(previous, base texture in unit 1).
//
// Contents
//   Dot3Stage       how far down the combiner chain to go (what the demo toggled between)
//   Dot3Polygon     the flat polygon, its placement (a quaternion, as in the WWDC 2001 talk) and the
//                   per-vertex light colours
//   Dot3Classic     the 2001 path: glTexEnv(GL_COMBINE), glBegin/glColor3ub/glMultiTexCoord2f
//                   in a compatibility-profile context
//   Dot3Shader      the same arithmetic in GLSL on a 4.5 core context, plus the fix for the
//                   interpolation artifact (per-pixel normalization)
//
// Both paths receive the same unsigned-byte colours and textures, and the shader computes
// exactly what the OpenGL spec says the combiners compute (image/dot3.h):
//     stage 1: 4·((c_r − ½)(t_r − ½) + (c_g − ½)(t_g − ½) + (c_b − ½)(t_b − ½)), clamped, in r, g, b
//     stage 2: stage1 · base
// tests/bump/dot3_gl_test.cpp checks both against that formula computed by hand and against
// each other. The interpolation artifact: the colours are interpolated linearly across the
// polygon, and the average of two unit vectors is shorter than 1 — when the light is near
// the polygon its vectors at the corners point in very different directions, their
// interpolation in between is short, and the dot product darkens exactly where the light is
// closest. Normalizing per pixel (Dot3ShaderOptions::normalizePerPixel; a normalization
// cube map in 2001) removes it.
//
// Texture units: the normal map must be in unit 0 and the base texture in unit 1 (the
// 2001 talk's layout); both classes bind them and reset sampler objects on those units.

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/image/dot3.h"
#include "glint/core/camera.h"

#include <cstdint>
#include <span>
#include <vector>

namespace glint::render::bump {

enum class Dot3Stage {
  LightVectors,  ///< only the primary colour: the encoded local light vectors
  DotProduct,    ///< stage 1 only: the grayscale N·L "light map"
  Modulated      ///< stages 1 and 2: N·L times the base texture, the final image
};

struct Dot3PolygonOptions {
  float halfSize = 1.0f;      ///< the polygon spans [−halfSize, halfSize]² in its local XY plane
  int subdivisions = 1;       ///< cells per side: 1 = the WWDC 2001 talk's single four-vertex polygon
  float uvScale = 1.0f;       ///< texture repeats across the polygon
};

/// A flat square in its local XY plane (normal +Z, u along +X, v along +Y: its local frame
/// IS its tangent space), placed in the world by rotation then translation.
class Dot3Polygon {
public:
  explicit Dot3Polygon(const Dot3PolygonOptions& options = {});

  /// Places the polygon: world = rotation · local + translation (rotation a unit quaternion).
  void place(const quat& rotation, vec3 translation) {
    m_rotation = rotation;
    m_translation = translation;
  }
  const quat& rotation() const { return m_rotation; }
  vec3 translation() const { return m_translation; }
  /// Local → world matrix of the placement.
  mat4 model() const;
  const std::vector<vec3>& positions() const { return m_positions; }  ///< local space
  const std::vector<vec2>& uvs() const { return m_uvs; }
  const std::vector<std::uint32_t>& indices() const { return m_indices; }  ///< triangles, CCW
  /// The WWDC 2001 talk's per-vertex step: the light vector from each vertex, rotated by the inverse of
  /// the polygon's rotation, encoded (v + 1)/2 · 255 (image/dot3.h).
  std::vector<u8vec3> lightColors(vec3 lightWorld) const;

private:
  quat m_rotation{1.0f, 0.0f, 0.0f, 0.0f};
  vec3 m_translation{0.0f};
  std::vector<vec3> m_positions;
  std::vector<vec2> m_uvs;
  std::vector<std::uint32_t> m_indices;
};

/// The fixed-function path. Error(NoGpu) on construction unless the current context has the
/// compatibility profile. draw() sets the texture-environment, matrix and enable state it
/// needs and returns them to GL's defaults afterwards (program 0 while drawing).
class Dot3Classic {
public:
  Dot3Classic();
  /// Immediate mode, one vertex at a time, as on the WWDC 2001 talk's slide: glColor3ub(light vector),
  /// glMultiTexCoord2f for units 0 and 1, glVertex3f. `colors` from polygon.lightColors().
  void draw(const Dot3Polygon& polygon, std::span<const u8vec3> colors, const Camera& camera,
            const gl::Texture& normalMap, const gl::Texture& base, Dot3Stage stage) const;
};

struct Dot3ShaderOptions {
  bool normalizePerPixel = false;  ///< decode, normalize and re-encode the interpolated light vector
};

/// The programmable path: a vertex buffer of positions and uvs, a dynamic buffer of
/// unsigned-byte colours (normalized attribute 4, as glColor3ub), and a fragment shader with
/// the combiner arithmetic.
class Dot3Shader {
public:
  explicit Dot3Shader(const Dot3Polygon& polygon, const Dot3ShaderOptions& options = {});
  /// Uploads `colors` and draws. Sets the state it uses (depth test on, no blending, no culling).
  void draw(std::span<const u8vec3> colors, const mat4& model, const Camera& camera, const gl::Texture& normalMap,
            const gl::Texture& base, Dot3Stage stage);

private:
  Dot3ShaderOptions m_options;
  gl::Program m_programs[3];  // one per Dot3Stage
  gl::Buffer m_vertices;      // vec3 position, vec2 uv (interleaved, static)
  gl::Buffer m_colors;        // u8vec4 per vertex (dynamic)
  gl::Buffer m_indices;
  gl::VertexArray m_vao;
  GLsizei m_indexCount = 0;
  std::size_t m_vertexCount = 0;
};

}  // namespace glint::render::bump
