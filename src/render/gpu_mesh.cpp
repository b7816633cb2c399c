#include "glint/render/gpu_mesh.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace glint::render {

GpuMesh::GpuMesh(const Mesh& mesh, std::span<const vec4> colors, std::string_view name) {
  mesh.validate(std::string(name));
  const std::size_t n = mesh.vertexCount();
  if (!colors.empty() && colors.size() != n) fail(ErrorKind::Internal, "{}: one colour per vertex expected", name);
  // One buffer, attributes one after another (non-interleaved): simple to fill and
  // to skip missing attributes.
  struct Region {
    const void* data;
    std::size_t bytes;
    GLuint location;
    GLint components;
  };
  const Region regions[] = {
      {mesh.positions.data(), n * sizeof(vec3), attrib::kPosition, 3},
      {mesh.normals.data(), mesh.normals.size() * sizeof(vec3), attrib::kNormal, 3},
      {mesh.uvs.data(), mesh.uvs.size() * sizeof(vec2), attrib::kUv, 2},
      {mesh.tangents.data(), mesh.tangents.size() * sizeof(vec4), attrib::kTangent, 4},
      {colors.data(), colors.size() * sizeof(vec4), attrib::kColor, 4},
  };
  std::size_t total = 0;
  for (const auto& r : regions) total += r.bytes;
  std::vector<std::byte> data(total);
  m_vao = gl::VertexArray::create(name);
  std::size_t offset = 0;
  for (const auto& r : regions) {
    if (r.bytes) std::memcpy(data.data() + offset, r.data, r.bytes);
    offset += r.bytes;
  }
  m_vertices = gl::Buffer(total, data.data(), 0, std::string(name) + "-vertices");
  offset = 0;
  for (const auto& r : regions) {
    if (r.bytes) {
      m_vao.attribute(r.location, r.location, r.components, 0);
      m_vao.vertexBuffer(r.location, m_vertices, GLintptr(offset), GLsizei(std::size_t(r.components) * sizeof(float)));
    }
    offset += r.bytes;
  }
  m_indices = gl::Buffer(std::span<const std::uint32_t>(mesh.indices), 0, std::string(name) + "-indices");
  m_vao.indexBuffer(m_indices);
  m_indexCount = GLsizei(mesh.indices.size());
}

void GpuMesh::draw(GLenum mode) const {
  m_vao.bind();
  glDrawElements(mode, m_indexCount, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

FullscreenPass::FullscreenPass(std::string_view fragment, const std::vector<std::string>& defines)
    : m_program(gl::Program::fromFiles({"common/fullscreen.vert", fragment}, defines)),
      m_vao(gl::VertexArray::create("fullscreen")) {}

void FullscreenPass::draw() const {
  PipelineState{.depthTest = false, .depthWrite = false}.apply();
  drawWithCurrentState();
}

void FullscreenPass::drawWithCurrentState() const {
  m_program.use();
  m_vao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

}  // namespace glint::render
