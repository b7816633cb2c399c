#include "glint/render/post/passes.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <limits>
#include <vector>

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

}  // namespace

// ---------------------------------------------------------------------------
const gl::Program& ComputePass::program(const gl::Texture& output) {
  const GLenum format = output.internalFormat();
  if (format != GL_RGBA8 && format != GL_RGBA32F)
    fail(ErrorKind::Usage, "{}: the output must be RGBA8 or RGBA32F", m_file);
  gl::Program& p = format == GL_RGBA32F ? m_rgba32f : m_rgba8;
  if (!p) p = gl::Program::fromFiles({m_file}, format == GL_RGBA32F ? std::vector<std::string>{"FLOAT_OUTPUT 1"}
                                                                    : std::vector<std::string>{});
  return p;
}

void ComputePass::dispatch(const gl::Texture& output) {
  const gl::Program& p = program(output);
  p.use();
  output.bindImage(0, GL_WRITE_ONLY, output.internalFormat());
  glDispatchCompute(GLuint((output.width() + 15) / 16), GLuint((output.height() + 15) / 16), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
}

// ---------------------------------------------------------------------------
TexelPass::TexelPass(const char* name, PassStage stage)
    : m_name(name), m_stage(stage), m_compute(fmt::format("post/{}.comp", name)),
      m_framebuffer(gl::Framebuffer::create(fmt::format("post-{}", name))) {
  if (stage == PassStage::Fragment) m_fragment.emplace(fmt::format("post/{}.frag", name));
}

const gl::Program& TexelPass::begin(const gl::Texture& input, const gl::Texture& output) {
  checkSizes(m_name, input, output);
  input.bindUnsampled(0);
  const gl::Program& program = m_fragment ? m_fragment->program() : m_compute.program(output);
  program.set("uInput", 0);
  return program;
}

void TexelPass::finish(const gl::Texture& output) {
  if (!m_fragment) return m_compute.dispatch(output);
  const SavedTarget saved;  // the caller's framebuffer and viewport, put back on return
  bindOutput(m_framebuffer, output);
  m_fragment->drawWithCurrentState();
}

// ---------------------------------------------------------------------------
void SepiaPass::run(const gl::Texture& input, const gl::Texture& output, const SepiaOptions& options) {
  const gl::Program& program = m_pass.begin(input, output);
  const dvec3 c = sepiaOffset(options);
  // t·c must stay in [0, 1] − Y per channel: t ≤ Y / max(−c_k) and t ≤ (1 − Y) / max(c_k).
  double most = 0.0, least = 0.0;
  for (int k = 0; k < 3; ++k) {
    most = std::max(most, c[k]);
    least = std::max(least, -c[k]);
  }
  const float big = std::numeric_limits<float>::max();
  const vec2 limits(least > 0 ? float(1.0 / least) : big, most > 0 ? float(1.0 / most) : big);
  program.set("uOffset", vec3(c));
  program.set("uLimits", limits);
  m_pass.finish(output);
}

void SobelPass::run(const gl::Texture& input, const gl::Texture& output, const SobelOptions& options) {
  const gl::Program& program = m_pass.begin(input, output);
  program.set("uOutput", int(options.output));
  program.set("uScale", options.scale);
  m_pass.finish(output);
}

void EdgesPass::run(const gl::Texture& input, const gl::Texture& output, const EdgesOptions& options) {
  const gl::Program& program = m_pass.begin(input, output);
  program.set("uScale", options.scale);
  program.set("uThreshold", options.threshold);
  m_pass.finish(output);
}

// ---------------------------------------------------------------------------
KuwaharaPass::KuwaharaPass(PassStage stage)
    : m_stage(stage), m_compute("post/kuwahara.comp"),
      m_statsFramebuffer(gl::Framebuffer::create("post-kuwahara-stats")),
      m_framebuffer(gl::Framebuffer::create("post-kuwahara")) {
  if (stage == PassStage::Fragment) {
    m_stats.emplace("post/kuwahara_stats.frag");
    m_select.emplace("post/kuwahara_select.frag");
  }
}

void KuwaharaPass::run(const gl::Texture& input, const gl::Texture& output, const KuwaharaOptions& options,
                       bool showQuadrant) {
  checkSizes("kuwahara", input, output);
  const int s = options.size;
  if (s < 2 || s > 8) fail(ErrorKind::Usage, "kuwahara: quadrant size must be 2..8, got {}", s);
  input.bindUnsampled(0);
  if (!m_stats) {  // one compute pass
    const gl::Program& program = m_compute.program(output);
    program.set("uInput", 0);
    program.set("uSize", s);
    program.set("uShowQuadrant", showQuadrant);
    return m_compute.dispatch(output);
  }
  const ivec2 statsSize(input.width() + s - 1, input.height() + s - 1);
  if (!m_statistics || m_statistics.width() != statsSize.x || m_statistics.height() != statsSize.y) {
    m_statistics = gl::Texture(GL_TEXTURE_2D, "post-kuwahara-statistics");
    m_statistics.storage(GL_RGBA32F, statsSize.x, statsSize.y);
  }
  const SavedTarget saved;  // the caller's framebuffer and viewport, put back on return
  // Pass 1: statistics of every block.
  const gl::Program& stats = m_stats->program();
  stats.set("uInput", 0);
  stats.set("uSize", s);
  bindOutput(m_statsFramebuffer, m_statistics);
  m_stats->drawWithCurrentState();
  // Pass 2: four fetches, the calmest quadrant's mean.
  input.bindUnsampled(0);
  m_statistics.bindUnsampled(1);
  const gl::Program& select = m_select->program();
  select.set("uInput", 0);
  select.set("uStatistics", 1);
  select.set("uSize", s);
  select.set("uShowQuadrant", showQuadrant);
  bindOutput(m_framebuffer, output);
  m_select->drawWithCurrentState();
}

}  // namespace glint::render::post
