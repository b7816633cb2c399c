// The Pipe Dream renderer's debug views and measurements (render/pipedream/renderer.h):
// the volumes' wireframe, the cut polygons' edges, the fill counts the benchmark and the
// tests read, and the one-line description. The frame's passes are renderer.cpp's.
#include "glint/render/pipedream/renderer.h"

#include "renderer_parts.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace glint::render::pipedream {

using detail::FramebufferSrgb;
using detail::kEdgeColor;
using detail::kVolumeWire;

void Renderer::drawVolumeWireframe() {
  const FramebufferSrgb srgb;
  const FrameStats saved = m_stats;
  m_compositeFbo.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  PipelineState{.depthTest = true, .depthWrite = false, .polygonMode = GL_LINE}.apply();
  m_extrude.set("uColor", scaled(kVolumeWire));
  for (int light = 0; light < m_lights; ++light) drawVolumesOf(light, false);
  PipelineState{}.apply();  // back to GL_FILL
  m_stats = saved;
}

void Renderer::drawEdges() {
  const FramebufferSrgb srgb;
  if (m_edgeCount == 0) return;
  m_compositeFbo.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  PipelineState{.depthTest = true, .depthFunc = GL_LEQUAL, .depthWrite = false}.apply();
  m_lit.set("uPass", 3);
  m_lit.set("uEmissive", vec3(kEdgeColor));
  m_lit.set("uModel", mat4(1.0f));
  m_lit.use();
  m_edges.draw(GL_LINES);
}

std::uint64_t Renderer::measureVolumeFill() {
  const FrameStats saved = m_stats;
  m_compositeFbo.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  if (m_mode == Mode::Naive) ensureNaiveCasters();
  PipelineState{.depthTest = false, .depthWrite = false, .colorMask = {false, false, false, false}}.apply();
  gl::Query query(GL_SAMPLES_PASSED, "pipedream-volume-fill");
  query.begin();
  for (int light = 0; light < m_lights; ++light) drawVolumesOf(light, m_mode == Mode::Naive);
  query.end();
  PipelineState{}.apply();
  m_stats = saved;
  return query.result();
}

namespace {
int bytesPerTexel(GLenum format) {
  switch (format) {
    case GL_R8: return 1;
    case GL_RG8: return 2;
    case GL_RGBA8:
    case GL_SRGB8_ALPHA8:
    case GL_DEPTH24_STENCIL8: return 4;
    case GL_RGBA16F: return 8;
    default: fail(ErrorKind::Internal, "pipedream: no texel size for format {:#x}", format);
  }
}
}  // namespace

std::vector<PassFill> Renderer::measureStaticFill(const gl::Target& target) {
  const FrameStats saved = m_stats;
  const Mode mode = m_mode;
  m_mode = Mode::StaticOnly;
  const std::uint64_t pixels = std::uint64_t(m_size.x) * std::uint64_t(m_size.y);
  const int color = bytesPerTexel(m_color.internalFormat()), weights = bytesPerTexel(m_weights.internalFormat());
  const int depth = bytesPerTexel(m_depthStencil.internalFormat());
  std::vector<PassFill> out;
  out.push_back({"clear", pixels, color + weights + depth});
  gl::Query query(GL_SAMPLES_PASSED, "pipedream-static-fill");
  const auto counted = [&](const auto& draw) {
    query.begin();
    draw();
    query.end();
    return query.result();
  };
  // The scene pass writes colour, weights and depth (the packed depth/stencil word).
  out.push_back({"scene", counted([&] { drawScene(); }), color + weights + depth});
  // The balls blend colour only (depth tested, not written).
  out.push_back({"balls", counted([&] { drawTranslucent(); }), color});
  out.push_back({"present", counted([&] { present(target); }), 4});
  m_mode = mode;
  m_stats = saved;
  PipelineState{}.apply();
  return out;
}

std::string Renderer::describe() const {
  std::array<std::size_t, 1u << kMaxLights> byMask{};
  std::size_t lit = 0;
  for (std::size_t m = 0; m + 1 < m_maskStart.size(); ++m) {
    byMask[m] = m_maskStart[m + 1] - m_maskStart[m];
    if (m) lit += byMask[m];
  }
  return fmt::format("{} cut triangles on {} vertices ({} reached by no light: the cheap shader; {} lit), {} uncut on {} "
                     "vertices; {} lights; {} dynamic casters, {} balls",
                     m_staticTriangles, m_staticVertices, byMask[0], lit, m_uncutTriangles, m_uncutVertices, m_lights,
                     m_stats.casters, m_stats.balls);
}

}  // namespace glint::render::pipedream
