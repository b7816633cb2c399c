#pragma once
// glint/render/gpu_mesh.h — a Mesh uploaded to the GPU, and a full-screen pass.
//
// GpuMesh stores each attribute in its own region of one buffer, at fixed
// attribute locations every glint shader uses (shaders/common/attributes.glsl):
//   0 position (vec3)  1 normal (vec3)  2 uv (vec2)  3 tangent (vec4)  4 color (vec4)
// Missing attributes are disabled and read as GL's default (0,0,0,1).
//
// FullscreenPass draws one triangle covering the viewport, generated from
// gl_VertexID (shaders/common/fullscreen.vert), with any fragment shader.

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/mesh/mesh.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint::render {

namespace attrib {
constexpr GLuint kPosition = 0;
constexpr GLuint kNormal = 1;
constexpr GLuint kUv = 2;
constexpr GLuint kTangent = 3;
constexpr GLuint kColor = 4;
}  // namespace attrib

class GpuMesh {
public:
  GpuMesh() = default;
  /// Uploads `mesh`; `colors` (optional, one per vertex) feed attribute 4.
  explicit GpuMesh(const Mesh& mesh, std::span<const vec4> colors = {}, std::string_view name = "mesh");

  /// glDrawElements of every triangle with the VAO bound (the program must be in use).
  void draw(GLenum mode = GL_TRIANGLES) const;
  std::size_t triangleCount() const { return m_indexCount / 3; }
  const gl::VertexArray& vertexArray() const { return m_vao; }

private:
  gl::Buffer m_vertices;
  gl::Buffer m_indices;
  gl::VertexArray m_vao;
  GLsizei m_indexCount = 0;
};

class FullscreenPass {
public:
  FullscreenPass() = default;
  /// `fragment`: path of a fragment shader under shaders/ reading `in vec2 vUv`.
  explicit FullscreenPass(std::string_view fragment, const std::vector<std::string>& defines = {});
  const gl::Program& program() const { return m_program; }
  /// Draws with depth test and writes off (a pass that wants depth sets its own state first
  /// and calls drawWithCurrentState()).
  void draw() const;
  void drawWithCurrentState() const;

private:
  gl::Program m_program;
  gl::VertexArray m_vao;
};

}  // namespace glint::render
