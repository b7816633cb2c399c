#include "cross_check.h"

#include "glint/gl/context.h"
#include "glint/gl/render_target.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace glint::test {

GlCanvas::GlCanvas(ivec2 size, GLenum depthStencilFormat) : m_size(size) {
  m_color = gl::Texture(GL_TEXTURE_2D, "raster-gl-color");
  m_color.storage(GL_RGBA8, size.x, size.y);
  m_depthStencil = gl::Texture(GL_TEXTURE_2D, "raster-gl-depth-stencil");
  m_depthStencil.storage(depthStencilFormat, size.x, size.y);
  m_framebuffer = gl::Framebuffer::create("raster-gl");
  m_framebuffer.attach(GL_COLOR_ATTACHMENT0, m_color);
  m_framebuffer.attach(GL_DEPTH_STENCIL_ATTACHMENT, m_depthStencil);
  m_framebuffer.checkComplete();
}

void GlCanvas::clear(const vec4& color, float depth, int stencil) {
  m_framebuffer.bind();
  render::PipelineState{}.apply();  // every write mask on
  glDisable(GL_SCISSOR_TEST);
  glClearNamedFramebufferfv(m_framebuffer.id(), GL_COLOR, 0, &color.x);
  glClearNamedFramebufferfi(m_framebuffer.id(), GL_DEPTH_STENCIL, 0, depth, stencil);
}

void GlCanvas::draw(const raster::State& state, const render::RasterTriangles& triangles, GLint first, GLsizei count,
                    std::optional<raster::Viewport> scissor) {
  m_framebuffer.bind();
  render::applyRasterState(state, m_size);
  if (scissor) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(scissor->x, scissor->y, scissor->width, scissor->height);
  } else {
    glDisable(GL_SCISSOR_TEST);
  }
  triangles.draw(first, count);
  glDisable(GL_SCISSOR_TEST);
}

GlBuffers GlCanvas::read() const {
  const Image color = gl::readColor(m_framebuffer, m_size);
  const Image depth = gl::readDepth(m_framebuffer, m_size);
  const Image stencil = gl::readStencil(m_framebuffer, m_size);
  GlBuffers out;
  out.width = m_size.x;
  out.height = m_size.y;
  const std::size_t n = std::size_t(m_size.x) * std::size_t(m_size.y);
  out.color.resize(n);
  out.depth.resize(n);
  out.stencil.resize(n);
  for (int y = 0; y < m_size.y; ++y) {
    const int row = m_size.y - 1 - y;  // readback images are top row first
    for (int x = 0; x < m_size.x; ++x) {
      const std::size_t i = out.index(x, y);
      out.color[i] = vec4(color.at(x, row, 0), color.at(x, row, 1), color.at(x, row, 2), color.at(x, row, 3));
      out.depth[i] = depth.at(x, row, 0);
      out.stencil[i] = stencil.pixels<std::uint8_t>()[std::size_t(row) * std::size_t(m_size.x) + std::size_t(x)];
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------

ReferenceRecorder::ReferenceRecorder(raster::Framebuffer& fb)
    : m_fb(fb),
      m_gradient(fb.depths().size(), 0.0f),
      m_writer(fb.depths().size(), -1),
      m_ambiguous(fb.depths().size(), 0),
      m_clipEdge(fb.depths().size(), 0) {}

double ReferenceRecorder::depthTolerance(std::size_t i) const { return kDepthAbsolute + m_gradient[i] * kPositionError; }

std::size_t ReferenceRecorder::ambiguousCount() const {
  return std::size_t(std::count(m_ambiguous.begin(), m_ambiguous.end(), std::uint8_t(1)));
}

std::size_t ReferenceRecorder::clipEdgeCount() const {
  return std::size_t(std::count(m_clipEdge.begin(), m_clipEdge.end(), std::uint8_t(1)));
}

namespace {
bool isOriginal(const glm::dvec3& weights) {
  return weights == glm::dvec3(1, 0, 0) || weights == glm::dvec3(0, 1, 0) || weights == glm::dvec3(0, 0, 1);
}

/// Marks pixels of `mask` (w×h, bottom row first) whose centre lies within `slack` of
/// segment a–b, inside the pixel rectangle `rect`.
void markNearSegment(std::vector<std::uint8_t>& mask, int w, const raster::Viewport& rect, glm::dvec2 a, glm::dvec2 b,
                     double slack) {
  const int x0 = std::max(rect.x, int(std::floor(std::min(a.x, b.x) - 1)));
  const int x1 = std::min(rect.x + rect.width - 1, int(std::ceil(std::max(a.x, b.x) + 1)));
  const int y0 = std::max(rect.y, int(std::floor(std::min(a.y, b.y) - 1)));
  const int y1 = std::min(rect.y + rect.height - 1, int(std::ceil(std::max(a.y, b.y) + 1)));
  const glm::dvec2 d = b - a;
  const double length2 = glm::dot(d, d);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const glm::dvec2 p(x + 0.5, y + 0.5);
      const double t = length2 > 0 ? std::clamp(glm::dot(p - a, d) / length2, 0.0, 1.0) : 0.0;
      if (glm::length(p - (a + t * d)) <= slack) mask[std::size_t(y) * std::size_t(w) + std::size_t(x)] = 1;
    }
  }
}
}  // namespace

void ReferenceRecorder::markClipEdges(const std::array<vec4, 3>& clip, const raster::State& state) {
  const auto polygon = raster::clipTriangle({glm::dvec4(clip[0]), glm::dvec4(clip[1]), glm::dvec4(clip[2])});
  if (polygon.size() < 3) return;
  const raster::Viewport viewport = raster::effectiveViewport(state, m_fb.width(), m_fb.height());
  const raster::Viewport rect{std::max(viewport.x, 0), std::max(viewport.y, 0),
                              std::min(viewport.x + viewport.width, m_fb.width()) - std::max(viewport.x, 0),
                              std::min(viewport.y + viewport.height, m_fb.height()) - std::max(viewport.y, 0)};
  const raster::DepthRange range = raster::clampDepthRange(state.depthRange);
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const raster::ClipVertex& a = polygon[k];
    const raster::ClipVertex& b = polygon[(k + 1) % polygon.size()];
    if (isOriginal(a.weights) && isOriginal(b.weights)) continue;
    markNearSegment(m_clipEdge, m_fb.width(), rect, glm::dvec2(raster::clipToWindow(a.position, viewport, range)),
                    glm::dvec2(raster::clipToWindow(b.position, viewport, range)), kClipEdgeSlack);
  }
}

raster::DrawStats ReferenceRecorder::draw(const raster::State& state, std::span<const raster::Vertex> vertices) {
  // Varying 1 carries (triangle id, |∇z|) to the fragment shader below.
  std::vector<raster::Vertex> tagged;
  tagged.reserve(vertices.size());
  const ivec2 size{m_fb.width(), m_fb.height()};
  for (std::size_t t = 0; t + 3 <= vertices.size(); t += 3) {
    const std::array<vec4, 3> clip = {vertices[t].position, vertices[t + 1].position, vertices[t + 2].position};
    std::array<float, 12> key{};
    for (std::size_t k = 0; k < 12; ++k) key[k] = clip[k / 4][int(k % 4)];
    const int id = m_ids.emplace(key, int(m_ids.size())).first->second;
    const vec4 tag(float(id), float(depthGradient(clip, state, size)), 0.0f, 0.0f);
    markClipEdges(clip, state);
    for (std::size_t k = t; k < t + 3; ++k)
      tagged.push_back({vertices[k].position, {vertices[k].varyings.empty() ? vec4(1.0f) : vertices[k].varyings[0], tag}});
  }

  const bool decisive = state.depthTest && state.depthFunc != raster::CompareFunc::Always &&
                        state.depthFunc != raster::CompareFunc::Never;
  const auto shader = [&](const raster::Fragment& f) -> std::optional<vec4> {
    const std::size_t i = m_fb.index(f.pixel.x, f.pixel.y);
    const int id = int(std::lround(f.varyings[1].x));
    const float gradient = f.varyings[1].y;
    // Mirror processFragment's decisions to know who writes depth.
    const raster::StencilFace& face = f.frontFacing ? state.stencilFront : state.stencilBack;
    const bool stencilPasses = !state.stencilTest || raster::stencilTestPasses(face, m_fb.stencils()[i]);
    if (!stencilPasses || !state.depthTest) return f.varyings[0];
    const float z = m_fb.storedDepth(f.fragCoord.z), stored = m_fb.depths()[i];
    const double delta = std::abs(double(z) - double(stored));
    const double band = kDepthAbsolute + gradient * kPositionError + depthTolerance(i);
    if (decisive && delta <= band && !(delta == 0.0 && id == m_writer[i])) m_ambiguous[i] = 1;
    if (raster::compare(state.depthFunc, z, stored) && state.depthMask) {
      m_gradient[i] = gradient;
      m_writer[i] = id;
    }
    return f.varyings[0];
  };
  return raster::drawTriangles(m_fb, state, tagged, {}, shader);
}

double depthGradient(const std::array<vec4, 3>& clip, const raster::State& state, ivec2 size) {
  const raster::Viewport viewport = raster::effectiveViewport(state, size.x, size.y);
  const raster::DepthRange range = raster::clampDepthRange(state.depthRange);
  const auto polygon = raster::clipTriangle({glm::dvec4(clip[0]), glm::dvec4(clip[1]), glm::dvec4(clip[2])});
  if (polygon.size() < 3) return 0.0;
  std::vector<glm::dvec3> window;
  for (const raster::ClipVertex& v : polygon) window.push_back(raster::clipToWindow(v.position, viewport, range));
  // The best-conditioned fan triangle of the clipped polygon defines the plane.
  std::size_t best = 1;
  double bestArea = 0.0;
  for (std::size_t k = 1; k + 1 < window.size(); ++k) {
    const double area = std::abs(raster::signedArea2(glm::dvec2(window[0]), glm::dvec2(window[k]), glm::dvec2(window[k + 1])));
    if (area > bestArea) bestArea = area, best = k;
  }
  const auto plane = raster::planeEquation(window[0], window[best], window[best + 1]);
  return plane ? std::hypot(plane->a, plane->b) : 0.0;
}

Agreement compareBuffers(const ReferenceRecorder& recorder, const raster::Framebuffer& ref, const GlBuffers& gl,
                         const std::function<bool(int, int)>& compareDepth, double colorTolerance,
                         const std::function<bool(int, int)>& compareColor) {
  Agreement a;
  auto where = [](int x, int y) { return "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")"; };
  for (int y = 0; y < ref.height(); ++y) {
    for (int x = 0; x < ref.width(); ++x) {
      const std::size_t i = ref.index(x, y);
      ++a.pixels;
      const bool tie = recorder.ambiguous()[i] != 0, clipEdge = recorder.clipEdge()[i] != 0;
      if (tie || clipEdge) {
        ++a.excluded;
        a.excludedDepthTies += tie;
        a.excludedClipEdges += clipEdge;
        a.excludedMismatches += gl.stencil[i] != ref.stencils()[i];
        continue;
      }
      if (gl.stencil[i] != ref.stencils()[i] && a.stencilMismatches++ == 0)
        a.firstStencilMismatch = where(x, y) + ": GL " + std::to_string(gl.stencil[i]) + ", reference " +
                                 std::to_string(ref.stencils()[i]);
      if (compareDepth(x, y)) {
        ++a.depthCompared;
        const double error = std::abs(double(gl.depth[i]) - double(ref.depths()[i]));
        const double tolerance = recorder.depthTolerance(i);
        a.maxDepthError = std::max(a.maxDepthError, error);
        const double gradient = (tolerance - kDepthAbsolute) / kPositionError;
        if (gradient > 0) a.maxDepthShift = std::max(a.maxDepthShift, (error - kDepthAbsolute) / gradient);
        if (error > tolerance && a.depthOutside++ == 0)
          a.firstDepthOutside = where(x, y) + ": GL " + std::to_string(gl.depth[i]) + ", reference " +
                                std::to_string(ref.depths()[i]) + ", tolerance " + std::to_string(tolerance);
      }
      if (!compareColor || compareColor(x, y)) {
        double worst = 0.0;
        for (int c = 0; c < 4; ++c) worst = std::max(worst, double(std::abs(gl.color[i][c] - ref.colors()[i][c])));
        a.maxColorError = std::max(a.maxColorError, worst);
        if (worst > colorTolerance) ++a.colorOutside;
      }
    }
  }
  return a;
}

bool isLlvmpipe() { return gl::queryContextInfo().renderer.find("llvmpipe") != std::string::npos; }

}  // namespace glint::test
