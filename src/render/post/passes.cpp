#include "glint/render/post/passes.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <algorithm>
#include <cctype>
#include <limits>

namespace glint::render::post {

namespace {
void checkSizes(const char* pass, const gl::Texture& input, const gl::Texture& output) {
  if (input.width() != output.width() || input.height() != output.height()) {
    fail(ErrorKind::Usage, "{}: input {}x{} and output {}x{} must have the same size", pass, input.width(),
         input.height(), output.width(), output.height());
  }
}

// Binds `output` as the colour target of `framebuffer`, the viewport to its size, and the
// state every post pass draws with (no depth, blending or culling).
void bindOutput(gl::Framebuffer& framebuffer, const gl::Texture& output) {
  framebuffer.attach(GL_COLOR_ATTACHMENT0, output);
  framebuffer.checkComplete();
  framebuffer.bind();
  glViewport(0, 0, output.width(), output.height());
  glDisable(GL_SCISSOR_TEST);
  PipelineState{.depthWrite = false}.apply();
}

void bindInput(const gl::Texture& texture, GLuint unit) {
  texture.bind(unit);
  gl::Sampler::unbind(unit);  // texelFetch ignores sampling state; keep the unit predictable
}

void finish() { glBindFramebuffer(GL_FRAMEBUFFER, 0); }
}  // namespace

// ---------------------------------------------------------------------------
SepiaPass::SepiaPass() : m_pass("post/sepia.frag"), m_framebuffer(gl::Framebuffer::create("post-sepia")) {}

void SepiaPass::run(const gl::Texture& input, const gl::Texture& output, const SepiaOptions& options) {
  checkSizes("sepia", input, output);
  const dvec3 c = sepiaOffset(options);
  // t·c must stay in [0, 1] − Y per channel: t ≤ Y / max(−c_k) and t ≤ (1 − Y) / max(c_k).
  double most = 0.0, least = 0.0;
  for (int k = 0; k < 3; ++k) {
    most = std::max(most, c[k]);
    least = std::max(least, -c[k]);
  }
  const float big = std::numeric_limits<float>::max();
  const vec2 limits(least > 0 ? float(1.0 / least) : big, most > 0 ? float(1.0 / most) : big);
  bindOutput(m_framebuffer, output);
  bindInput(input, 0);
  const auto& program = m_pass.program();
  program.set("uInput", 0);
  program.set("uOffset", vec3(c));
  program.set("uLimits", limits);
  m_pass.drawWithCurrentState();
  finish();
}

// ---------------------------------------------------------------------------
SobelPass::SobelPass() : m_pass("post/sobel.frag"), m_framebuffer(gl::Framebuffer::create("post-sobel")) {}

void SobelPass::run(const gl::Texture& input, const gl::Texture& output, const SobelOptions& options) {
  checkSizes("sobel", input, output);
  bindOutput(m_framebuffer, output);
  bindInput(input, 0);
  const auto& program = m_pass.program();
  program.set("uInput", 0);
  program.set("uOutput", int(options.output));
  program.set("uScale", options.scale);
  m_pass.drawWithCurrentState();
  finish();
}

// ---------------------------------------------------------------------------
EdgesPass::EdgesPass() : m_pass("post/edges.frag"), m_framebuffer(gl::Framebuffer::create("post-edges")) {}

void EdgesPass::run(const gl::Texture& input, const gl::Texture& output, const EdgesOptions& options) {
  checkSizes("edges", input, output);
  bindOutput(m_framebuffer, output);
  bindInput(input, 0);
  const auto& program = m_pass.program();
  program.set("uInput", 0);
  program.set("uScale", options.scale);
  program.set("uThreshold", options.threshold);
  m_pass.drawWithCurrentState();
  finish();
}

// ---------------------------------------------------------------------------
KuwaharaPass::KuwaharaPass()
    : m_stats("post/kuwahara_stats.frag"), m_select("post/kuwahara_select.frag"),
      m_statsFramebuffer(gl::Framebuffer::create("post-kuwahara-stats")),
      m_framebuffer(gl::Framebuffer::create("post-kuwahara")) {}

void KuwaharaPass::run(const gl::Texture& input, const gl::Texture& output, const KuwaharaOptions& options,
                       bool showQuadrant) {
  checkSizes("kuwahara", input, output);
  const int s = options.size;
  if (s < 2 || s > 8) fail(ErrorKind::Usage, "kuwahara: quadrant size must be 2..8, got {}", s);
  const ivec2 statsSize(input.width() + s - 1, input.height() + s - 1);
  if (!m_statistics || m_statistics.width() != statsSize.x || m_statistics.height() != statsSize.y) {
    m_statistics = gl::Texture(GL_TEXTURE_2D, "post-kuwahara-statistics");
    m_statistics.storage(GL_RGBA32F, statsSize.x, statsSize.y);
  }
  // Pass 1: statistics of every block.
  bindOutput(m_statsFramebuffer, m_statistics);
  bindInput(input, 0);
  m_stats.program().set("uInput", 0);
  m_stats.program().set("uSize", s);
  m_stats.drawWithCurrentState();
  // Pass 2: four fetches, the calmest quadrant's mean.
  bindOutput(m_framebuffer, output);
  bindInput(input, 0);
  bindInput(m_statistics, 1);
  const auto& program = m_select.program();
  program.set("uInput", 0);
  program.set("uStatistics", 1);
  program.set("uSize", s);
  program.set("uShowQuadrant", showQuadrant);
  m_select.drawWithCurrentState();
  finish();
}

}  // namespace glint::render::post
