#pragma once
// glint/render/raster_gl.h — the reference pipeline's inputs, drawn by OpenGL.
//
// The reference rasterizer (glint/raster) takes plain data: clip-space vertices with
// varyings, and a raster::State with GL's initial values. This header draws the same
// data with OpenGL, so a test or a side-by-side scene states its geometry and its
// operations once and both pipelines are guaranteed to run the same ones:
//
/// ```cpp
/// #include <glint/gl/render_target.h>
/// namespace raster = glint::raster;
/// const std::vector<raster::Vertex> vertices = {
///     {{-0.8f, -0.8f, 0.5f, 1}, {{1, 0, 0, 1}}}, {{0.8f, -0.8f, 0.5f, 1}, {{0, 1, 0, 1}}},
///     {{0.0f, 0.8f, -0.5f, 1}, {{0, 0, 1, 1}}}};
/// const raster::State state{.depthTest = true, .depthFunc = raster::CompareFunc::LessEqual};
/// const glint::gl::RenderTarget target({500, 500});  // with a current GL context
/// target.target().bind();
/// const glint::render::RasterTriangles gpu(vertices);          // upload once
/// glint::render::applyRasterState(state, target.size());       // GL state
/// gpu.draw();                                                  // GL draw
/// raster::Framebuffer fb(500, 500);
/// raster::drawTriangles(fb, state, vertices);                  // the same draw on the CPU
/// ```
//
// Everything in raster::State is mapped: viewport (unset = the whole framebuffer),
// depth range, depth test/func/mask, two-sided stencil, culling and front face, colour
// mask, blending with separate RGB/alpha factors and equations. Header-only, and it adds
// no link dependency on glint_raster: it uses raster's types (State, Vertex), which need
// nothing compiled, and calls none of its functions. (The raster headers it includes do
// declare the CPU pipeline, drawTriangles above among them; a program that calls those
// links glint_raster itself.)
//
// RasterTriangles runs shaders/raster/clip.vert (gl_Position = the clip position,
// varying 0 passed through) and shaders/raster/varying.frag (output varying 0): the
// programmable stages of raster::drawTriangles' default shader. Only varying 0 is
// uploaded; vertices without varyings get opaque white, as drawTriangles gives them.

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/raster/pipeline.h"
#include "glint/raster/state.h"
#include "glint/render/state.h"

#include <epoxy/gl.h>

#include <span>
#include <string_view>
#include <vector>

namespace glint::render {

inline GLenum toGl(raster::CompareFunc func) {
  switch (func) {
    case raster::CompareFunc::Never: return GL_NEVER;
    case raster::CompareFunc::Less: return GL_LESS;
    case raster::CompareFunc::Equal: return GL_EQUAL;
    case raster::CompareFunc::LessEqual: return GL_LEQUAL;
    case raster::CompareFunc::Greater: return GL_GREATER;
    case raster::CompareFunc::NotEqual: return GL_NOTEQUAL;
    case raster::CompareFunc::GreaterEqual: return GL_GEQUAL;
    case raster::CompareFunc::Always: return GL_ALWAYS;
  }
  return GL_ALWAYS;
}

inline GLenum toGl(raster::StencilOp op) {
  switch (op) {
    case raster::StencilOp::Keep: return GL_KEEP;
    case raster::StencilOp::Zero: return GL_ZERO;
    case raster::StencilOp::Replace: return GL_REPLACE;
    case raster::StencilOp::Incr: return GL_INCR;
    case raster::StencilOp::Decr: return GL_DECR;
    case raster::StencilOp::IncrWrap: return GL_INCR_WRAP;
    case raster::StencilOp::DecrWrap: return GL_DECR_WRAP;
    case raster::StencilOp::Invert: return GL_INVERT;
  }
  return GL_KEEP;
}

inline GLenum toGl(raster::BlendFactor factor) {
  switch (factor) {
    case raster::BlendFactor::Zero: return GL_ZERO;
    case raster::BlendFactor::One: return GL_ONE;
    case raster::BlendFactor::SrcColor: return GL_SRC_COLOR;
    case raster::BlendFactor::OneMinusSrcColor: return GL_ONE_MINUS_SRC_COLOR;
    case raster::BlendFactor::DstColor: return GL_DST_COLOR;
    case raster::BlendFactor::OneMinusDstColor: return GL_ONE_MINUS_DST_COLOR;
    case raster::BlendFactor::SrcAlpha: return GL_SRC_ALPHA;
    case raster::BlendFactor::OneMinusSrcAlpha: return GL_ONE_MINUS_SRC_ALPHA;
    case raster::BlendFactor::DstAlpha: return GL_DST_ALPHA;
    case raster::BlendFactor::OneMinusDstAlpha: return GL_ONE_MINUS_DST_ALPHA;
  }
  return GL_ONE;
}

inline GLenum toGl(raster::BlendEquation equation) {
  switch (equation) {
    case raster::BlendEquation::Add: return GL_FUNC_ADD;
    case raster::BlendEquation::Subtract: return GL_FUNC_SUBTRACT;
    case raster::BlendEquation::ReverseSubtract: return GL_FUNC_REVERSE_SUBTRACT;
    case raster::BlendEquation::Min: return GL_MIN;
    case raster::BlendEquation::Max: return GL_MAX;
  }
  return GL_FUNC_ADD;
}

inline GLenum toGl(raster::Face face) {
  switch (face) {
    case raster::Face::Front: return GL_FRONT;
    case raster::Face::Back: return GL_BACK;
    case raster::Face::FrontAndBack: return GL_FRONT_AND_BACK;
  }
  return GL_BACK;
}

inline GLenum toGl(raster::Winding winding) { return winding == raster::Winding::Cw ? GL_CW : GL_CCW; }

inline StencilFace toGl(const raster::StencilFace& face) {
  return StencilFace{.func = toGl(face.func),
                     .ref = face.ref,
                     .valueMask = face.valueMask,
                     .writeMask = face.writeMask,
                     .sfail = toGl(face.sfail),
                     .dpfail = toGl(face.dpfail),
                     .dppass = toGl(face.dppass)};
}

/// The PipelineState part of a raster::State (everything but viewport, depth range and the
/// blend equations, which PipelineState does not carry; applyRasterState sets those).
inline PipelineState pipelineStateFor(const raster::State& state) {
  return PipelineState{
      .depthTest = state.depthTest,
      .depthFunc = toGl(state.depthFunc),
      .depthWrite = state.depthMask,
      .colorMask = {state.colorMask.r, state.colorMask.g, state.colorMask.b, state.colorMask.a},
      .cull = state.cull,
      .cullFace = toGl(state.cullFace),
      .frontFace = toGl(state.frontFace),
      .stencil = {.enabled = state.stencilTest,
                  .front = toGl(state.stencilFront),
                  .back = toGl(state.stencilBack),
                  .separate = true},
      .blend = {.enabled = state.blend.enabled,
                .src = toGl(state.blend.srcRgb),
                .dst = toGl(state.blend.dstRgb),
                .srcAlpha = toGl(state.blend.srcAlpha),
                .dstAlpha = toGl(state.blend.dstAlpha),
                .separateAlpha = true,
                .equation = toGl(state.blend.equationRgb)},
  };
}

/// Sets all of `state` on the current context for drawing into a framebuffer of
/// `framebufferSize` (the size an unset viewport covers, as raster::effectiveViewport).
inline void applyRasterState(const raster::State& state, ivec2 framebufferSize) {
  pipelineStateFor(state).apply();
  glBlendEquationSeparate(toGl(state.blend.equationRgb), toGl(state.blend.equationAlpha));
  const raster::Viewport vp = state.viewport.value_or(raster::Viewport{0, 0, framebufferSize.x, framebufferSize.y});
  glViewport(vp.x, vp.y, vp.width, vp.height);
  glDepthRange(state.depthRange.nearVal, state.depthRange.farVal);
}

/// raster::Vertex data in a GL buffer: position (location 0) and varying 0 (location 1),
/// non-indexed, drawn as GL_TRIANGLES with the program described above.
class RasterTriangles {
public:
  RasterTriangles() = default;
  explicit RasterTriangles(std::span<const raster::Vertex> vertices, std::string_view name = "raster-triangles")
      : m_count(GLsizei(vertices.size())),
        m_program(gl::Program::fromFiles({"raster/clip.vert", "raster/varying.frag"})),
        m_vao(gl::VertexArray::create(name)) {
    std::vector<vec4> data;
    data.reserve(vertices.size() * 2);
    for (const raster::Vertex& v : vertices) {
      data.push_back(v.position);
      data.push_back(v.varyings.empty() ? vec4(1.0f) : v.varyings[0]);
    }
    if (data.empty()) return;
    m_buffer = gl::Buffer(std::span<const vec4>(data), 0, name);
    m_vao.attribute(0, 0, 4, 0);
    m_vao.attribute(1, 0, 4, sizeof(vec4));
    m_vao.vertexBuffer(0, m_buffer, 0, GLsizei(2 * sizeof(vec4)));
  }

  /// Draws vertices [first, first + count) (all by default) with the current GL state.
  void draw(GLint first = 0, GLsizei count = -1) const {
    if (count < 0) count = m_count - first;
    if (count <= 0) return;
    m_program.use();
    m_vao.bind();
    glDrawArrays(GL_TRIANGLES, first, count);
  }
  GLsizei vertexCount() const { return m_count; }

private:
  GLsizei m_count = 0;
  gl::Program m_program;
  gl::VertexArray m_vao;
  gl::Buffer m_buffer;
};

}  // namespace glint::render
