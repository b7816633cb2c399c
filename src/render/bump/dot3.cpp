// The fixed-function calls in Dot3Classic are the point of this file: they are what the
// WWDC 2001 talk shows on its slides (ARB suffixes dropped, as in GL 1.3+).
#include "glint/render/bump/dot3.h"

#include "glint/core/error.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/state.h"

#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <span>
#include <string>

namespace glint::render::bump {

// ---------------------------------------------------------------------------
Dot3Polygon::Dot3Polygon(const Dot3PolygonOptions& o) {
  if (o.subdivisions < 1 || o.subdivisions > 256) fail(ErrorKind::Usage, "polygon subdivisions must be 1..256");
  const int n = o.subdivisions;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float fx = float(i) / float(n), fy = float(j) / float(n);
      m_positions.emplace_back((2 * fx - 1) * o.halfSize, (2 * fy - 1) * o.halfSize, 0.0f);
      m_uvs.emplace_back(fx * o.uvScale, fy * o.uvScale);
    }
  }
  const auto at = [&](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      // The same diagonal in both paths: colour interpolation depends on it.
      m_indices.insert(m_indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
}

mat4 Dot3Polygon::model() const { return glm::translate(mat4(1.0f), m_translation) * glm::mat4_cast(m_rotation); }

std::vector<u8vec3> Dot3Polygon::lightColors(vec3 lightWorld) const {
  std::vector<u8vec3> colors;
  colors.reserve(m_positions.size());
  for (const vec3& p : m_positions) colors.push_back(encodeLightVector(localLightVector(m_rotation, m_translation, p, lightWorld)));
  return colors;
}

// ---------------------------------------------------------------------------
namespace {
void loadMatrix(GLenum mode, const mat4& m) {
  glMatrixMode(mode);
  glLoadMatrixf(&m[0][0]);
}

void resetUnit(GLenum unit) {
  glActiveTexture(unit);
  glDisable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, 0);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
}

/// One fixed-function texture stage of texture unit `unit`: `texture` bound and enabled, the
/// combiner computing `combine` of operand 0 (`source0`: the vertex colour or the previous
/// stage) and the texture, RGB from their colours, alpha passed on from `source0`.
void combinerStage(GLuint unit, const gl::Texture& texture, GLenum combine, GLenum source0) {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindSampler(unit, 0);
  texture.bindToActiveUnit();
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_COMBINE);
  glTexEnvi(GL_TEXTURE_ENV, GL_COMBINE_RGB, combine);
  glTexEnvi(GL_TEXTURE_ENV, GL_SOURCE0_RGB, source0);
  glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND0_RGB, GL_SRC_COLOR);
  glTexEnvi(GL_TEXTURE_ENV, GL_SOURCE1_RGB, GL_TEXTURE);
  glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND1_RGB, GL_SRC_COLOR);
  glTexEnvf(GL_TEXTURE_ENV, GL_RGB_SCALE, 1.0f);  // the "scale the output" the WWDC 2001 talk mentions
  glTexEnvi(GL_TEXTURE_ENV, GL_COMBINE_ALPHA, GL_REPLACE);
  glTexEnvi(GL_TEXTURE_ENV, GL_SOURCE0_ALPHA, source0);
  glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND0_ALPHA, GL_SRC_ALPHA);
}
}  // namespace

Dot3Classic::Dot3Classic() {
  GLint mask = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
  if (!(mask & GL_CONTEXT_COMPATIBILITY_PROFILE_BIT)) {
    fail(ErrorKind::NoGpu, "the classic DOT3 path needs a compatibility-profile context");
  }
}

void Dot3Classic::draw(const Dot3Polygon& polygon, std::span<const u8vec3> colors, const Camera& camera,
                       const gl::Texture& normalMap, const gl::Texture& base, Dot3Stage stage) const {
  if (colors.size() != polygon.positions().size()) fail(ErrorKind::Internal, "one light colour per vertex expected");
  glUseProgram(0);
  glBindVertexArray(0);
  PipelineState{.depthTest = true}.apply();
  glShadeModel(GL_SMOOTH);
  loadMatrix(GL_PROJECTION, camera.projection);
  loadMatrix(GL_MODELVIEW, camera.view * polygon.model());

  if (stage != Dot3Stage::LightVectors) {
    // Stage 1 (unit 0): "we bind the normal map to the first texture unit ... set the texture
    // combine operation to DOT3 ... set the output to be an RGB value ... set the two operands".
    combinerStage(0, normalMap, GL_DOT3_RGB, GL_PRIMARY_COLOR);
  }
  if (stage == Dot3Stage::Modulated) {
    // Stage 2 (unit 1): "set the combiner operation to modulate ... the first operand to be
    // the previous output ... second operand will be the base texture".
    combinerStage(1, base, GL_MODULATE, GL_PREVIOUS);
  }

  // "First I issued the local light vector, which is an unsigned byte vector. Then I simply
  // issue the two sets of texture coordinates." Triangles rather than the slide's polygon so
  // the diagonal (and with it the colour interpolation) is the shader path's.
  const auto& positions = polygon.positions();
  const auto& uvs = polygon.uvs();
  glBegin(GL_TRIANGLES);
  for (std::uint32_t i : polygon.indices()) {
    glColor3ub(colors[i].x, colors[i].y, colors[i].z);
    glMultiTexCoord2f(GL_TEXTURE0, uvs[i].x, uvs[i].y);
    glMultiTexCoord2f(GL_TEXTURE1, uvs[i].x, uvs[i].y);
    glVertex3f(positions[i].x, positions[i].y, positions[i].z);
  }
  glEnd();

  // Back to GL's initial fixed-function state.
  resetUnit(GL_TEXTURE1);
  resetUnit(GL_TEXTURE0);
  glColor4f(1.0f, 1.0f, 1.0f, 1.0f);
  for (GLenum mode : {GL_TEXTURE, GL_PROJECTION, GL_MODELVIEW}) {
    glMatrixMode(mode);
    glLoadIdentity();
  }
}

// ---------------------------------------------------------------------------
Dot3Shader::Dot3Shader(const Dot3Polygon& polygon, const Dot3ShaderOptions& options) : m_options(options) {
  for (int stage = 0; stage < 3; ++stage) {
    std::vector<std::string> defines;
    if (stage == int(Dot3Stage::LightVectors)) defines.emplace_back("STAGE_LIGHT_VECTORS");
    if (stage == int(Dot3Stage::DotProduct)) defines.emplace_back("STAGE_DOT_PRODUCT");
    if (options.normalizePerPixel) defines.push_back("NORMALIZE_PER_PIXEL");
    m_programs[stage] = gl::Program::fromFiles({"bump/dot3.vert", "bump/dot3.frag"}, defines);
  }
  struct Vertex {
    vec3 position;
    vec2 uv;
  };
  std::vector<Vertex> vertices;
  for (std::size_t i = 0; i < polygon.positions().size(); ++i) vertices.push_back({polygon.positions()[i], polygon.uvs()[i]});
  m_vertexCount = vertices.size();
  m_vertices = gl::Buffer(std::span<const Vertex>(vertices), 0, "dot3-vertices");
  m_colors = gl::Buffer(m_vertexCount * sizeof(glm::u8vec4), nullptr, GL_DYNAMIC_STORAGE_BIT, "dot3-light-colors");
  m_indices = gl::Buffer(std::span<const std::uint32_t>(polygon.indices()), 0, "dot3-indices");
  m_indexCount = GLsizei(polygon.indices().size());
  m_vao = gl::VertexArray::create("dot3");
  m_vao.attribute(attrib::kPosition, 0, 3, offsetof(Vertex, position));
  m_vao.attribute(attrib::kUv, 0, 2, offsetof(Vertex, uv));
  m_vao.vertexBuffer(0, m_vertices, 0, sizeof(Vertex));
  // Unsigned bytes, normalized: 0..255 → 0..1, exactly what glColor3ub hands the pipeline.
  m_vao.attribute(attrib::kColor, 1, 4, 0, GL_UNSIGNED_BYTE, true);
  m_vao.vertexBuffer(1, m_colors, 0, sizeof(glm::u8vec4));
  m_vao.indexBuffer(m_indices);
}

void Dot3Shader::draw(std::span<const u8vec3> colors, const mat4& model, const Camera& camera,
                      const gl::Texture& normalMap, const gl::Texture& base, Dot3Stage stage) {
  if (colors.size() != m_vertexCount) fail(ErrorKind::Internal, "one light colour per vertex expected");
  std::vector<glm::u8vec4> rgba;
  rgba.reserve(colors.size());
  for (const u8vec3& c : colors) rgba.emplace_back(c, 255);
  m_colors.update(0, rgba.size() * sizeof(glm::u8vec4), rgba.data());

  const gl::Program& program = m_programs[int(stage)];
  program.set("uModelViewProjection", camera.viewProjection() * model);
  normalMap.bind(0);
  base.bind(1);
  gl::Sampler::unbind(0);
  gl::Sampler::unbind(1);
  PipelineState{.depthTest = true}.apply();
  program.use();
  m_vao.bind();
  glDrawElements(GL_TRIANGLES, m_indexCount, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

}  // namespace glint::render::bump
