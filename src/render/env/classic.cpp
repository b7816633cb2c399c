// The fixed-function calls here are the point of this file: they are what the WWDC 2001 talk
// shows on its slides (ARB suffixes dropped, as in GL 1.3+).
#include "glint/render/env/classic.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint::render::env {
namespace {

void loadMatrix(GLenum mode, const mat4& m) {
  glMatrixMode(mode);
  glLoadMatrixf(&m[0][0]);
}

// Back to GL's initial fixed-function state so the next pass starts clean.
void resetFixedFunction() {
  for (GLenum coord : {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R}) glDisable(coord);
  glDisable(GL_TEXTURE_CUBE_MAP);
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_NORMALIZE);
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glColor4f(1.0f, 1.0f, 1.0f, 1.0f);
  for (GLenum mode : {GL_TEXTURE, GL_PROJECTION, GL_MODELVIEW}) {
    glMatrixMode(mode);
    glLoadIdentity();
  }
}

/// `cubeMap`: the mirror samples a cube map (filtered seamlessly across its faces).
void beginMirror(const mat4& model, const Camera& camera, vec3 tint, bool cubeMap) {
  glUseProgram(0);  // fixed function: no program bound
  PipelineState{.depthTest = true, .cull = true, .seamlessCubeMap = cubeMap}.apply();
  loadMatrix(GL_PROJECTION, camera.projection);
  loadMatrix(GL_MODELVIEW, camera.view * model);
  glEnable(GL_NORMALIZE);  // texgen needs unit eye-space normals, whatever the model scale
  glActiveTexture(GL_TEXTURE0);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glColor4f(tint.r, tint.g, tint.b, 1.0f);
}
}  // namespace

ClassicMesh::ClassicMesh(const Mesh& mesh, std::string_view label) {
  mesh.validate(std::string(label));
  if (!mesh.hasNormals()) fail(ErrorKind::Input, "{}: reflection mapping needs normals", label);
  std::vector<float> interleaved;
  interleaved.reserve(mesh.vertexCount() * 6);
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    const vec3 p = mesh.positions[i], n = mesh.normals[i];
    interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
  }
  m_vertices = gl::Buffer(std::span<const float>(interleaved), 0, std::string(label) + "-vertices");
  m_indices = gl::Buffer(std::span<const std::uint32_t>(mesh.indices), 0, std::string(label) + "-indices");
  m_indexCount = GLsizei(mesh.indices.size());
}

void ClassicMesh::draw() const {
  constexpr GLsizei kStride = 6 * sizeof(float);
  glBindVertexArray(0);  // client-state arrays live in the default vertex array object
  m_vertices.bind(GL_ARRAY_BUFFER);
  m_indices.bind(GL_ELEMENT_ARRAY_BUFFER);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, kStride, nullptr);
  glNormalPointer(GL_FLOAT, kStride, reinterpret_cast<const void*>(3 * sizeof(float)));
  glDrawElements(GL_TRIANGLES, m_indexCount, GL_UNSIGNED_INT, nullptr);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

ClassicEnvironment::ClassicEnvironment() {
  GLint mask = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
  if (!(mask & GL_CONTEXT_COMPATIBILITY_PROFILE_BIT)) {
    fail(ErrorKind::NoGpu, "the classic fixed-function path needs a compatibility-profile context");
  }
}

void ClassicEnvironment::drawSkybox(const gl::Texture& cube, const Camera& camera) const {
  glUseProgram(0);
  PipelineState{.depthTest = false, .depthWrite = false, .seamlessCubeMap = true}.apply();
  loadMatrix(GL_PROJECTION, camera.projection);
  loadMatrix(GL_MODELVIEW, mat4(camera.rotation()));  // rotation only: the sky is at infinity
  glActiveTexture(GL_TEXTURE0);
  cube.bindToActiveUnit();
  glEnable(GL_TEXTURE_CUBE_MAP);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  // Each corner's texture coordinate is its own direction; perspective-correct
  // interpolation across a face then gives every pixel its exact view direction.
  static constexpr int kQuads[6][4] = {{1, 5, 7, 3}, {4, 0, 2, 6}, {2, 3, 7, 6}, {4, 5, 1, 0}, {5, 4, 6, 7}, {0, 1, 3, 2}};
  glBegin(GL_QUADS);
  for (const auto& quad : kQuads) {
    for (int corner : quad) {
      const float x = (corner & 1) ? 1.0f : -1.0f, y = (corner & 2) ? 1.0f : -1.0f, z = (corner & 4) ? 1.0f : -1.0f;
      glTexCoord3f(x, y, z);
      glVertex3f(x, y, z);
    }
  }
  glEnd();
  resetFixedFunction();
}

void ClassicEnvironment::drawCubeMapped(const ClassicMesh& mesh, const mat4& model, const Camera& camera,
                                        const gl::Texture& cube, vec3 tint) const {
  beginMirror(model, camera, tint, true);
  cube.bindToActiveUnit();
  glEnable(GL_TEXTURE_CUBE_MAP);
  // The WWDC 2001 talk: "set the texture generation to Reflection Map mode ... three dimensions".
  for (GLenum coord : {GL_S, GL_T, GL_R}) glTexGeni(coord, GL_TEXTURE_GEN_MODE, GL_REFLECTION_MAP);
  for (GLenum coord : {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R}) glEnable(coord);
  // Texgen's r is in eye space; the cube map is in world space.
  loadMatrix(GL_TEXTURE, mat4(glm::transpose(camera.rotation())));
  mesh.draw();
  resetFixedFunction();
}

void ClassicEnvironment::drawSphereMapped(const ClassicMesh& mesh, const mat4& model, const Camera& camera,
                                          const gl::Texture& sphereMap, vec3 tint) const {
  beginMirror(model, camera, tint, false);
  sphereMap.bindToActiveUnit();
  glEnable(GL_TEXTURE_2D);
  // "...while spherical map mode uses two dimensions."
  for (GLenum coord : {GL_S, GL_T}) glTexGeni(coord, GL_TEXTURE_GEN_MODE, GL_SPHERE_MAP);
  for (GLenum coord : {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T}) glEnable(coord);
  mesh.draw();
  resetFixedFunction();
}

}  // namespace glint::render::env
