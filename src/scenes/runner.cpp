#include "glint/scenes/runner.h"

#include "glint/core/error.h"
#include "glint/gl/debug.h"
#include "glint/gl/render_target.h"
#include "glint/gl/timer.h"
#include "glint/render/state.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace glint::scenes {

void ContextPool::use(gl::Profile profile) {
  if (!available(profile)) throw Error(ErrorKind::NoGpu, m_failures[profile]);
  m_contexts[profile]->makeCurrent();
}

bool ContextPool::available(gl::Profile profile) {
  if (m_contexts.count(profile)) return true;
  if (m_failures.count(profile)) return false;
  try {
    m_contexts[profile] = gl::HeadlessContext::create({.profile = profile, .debug = m_debug});
    return true;
  } catch (const Error& e) {
    m_contexts.erase(profile);
    m_failures[profile] = e.what();
    return false;
  }
}

std::string ContextPool::unavailableReason(gl::Profile profile) const {
  auto it = m_failures.find(profile);
  return it == m_failures.end() ? std::string() : it->second;
}

namespace {
double checkedTime(double time) {
  if (!std::isfinite(time)) fail(ErrorKind::Usage, "time must be a finite number of seconds");
  return time;
}
}  // namespace

VariantRenderer::VariantRenderer(const VariantRef& ref, const RenderRequest& request)
    : m_ref(ref), m_size(request.size.x > 0 ? request.size : ref.scene->defaultSize) {
  m_scene = ref.scene->create(ref.variant);
  for (const auto& assignment : request.options) setOption(*m_scene, assignment);
  m_target = std::make_unique<gl::RenderTarget>(m_size, GL_RGBA8, "frame");
}

VariantRenderer::~VariantRenderer() = default;

RenderResult VariantRenderer::frame(double time, int timingRepeats) {
  const FrameInput frame{.target = m_target->target(), .time = checkedTime(time), .deltaTime = 0.0};
  // Every frame starts from default state, whatever the previous scene left.
  auto renderFrame = [&] {
    render::resetState();
    m_scene->render(frame);
  };
  RenderResult result;
  renderFrame();
  if (timingRepeats > 0) {
    result.gpuMs = gl::GpuTimer::measureMs(renderFrame, timingRepeats, 0);
    std::vector<double> cpu;
    for (int i = 0; i < timingRepeats; ++i) {
      const auto start = std::chrono::steady_clock::now();
      renderFrame();
      glFinish();
      cpu.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::nth_element(cpu.begin(), cpu.begin() + long(cpu.size() / 2), cpu.end());
    result.cpuMs = cpu[cpu.size() / 2];
    // Timed repeats must leave the same picture as a single frame (deterministic scenes).
    renderFrame();
  }
  result.image = gl::readColor(m_target->framebuffer(), m_size);
  // A window shows colour only; destination alpha is a working value of some
  // techniques, not transparency, so the picture is made opaque.
  auto px = result.image.pixels<std::uint8_t>();
  for (std::size_t i = 3; i < px.size(); i += 4) px[i] = 255;
  result.notes = m_scene->notes();
  gl::checkGlError(m_ref.fullName().c_str());
  return result;
}

RenderResult renderVariant(const VariantRef& ref, const RenderRequest& request) {
  const double time = checkedTime(request.time.value_or(ref.scene->defaultTime));  // before the scene is made
  VariantRenderer renderer(ref, request);
  return renderer.frame(time, request.timingRepeats);
}

ReferenceCheck checkAgainstReference(const Image& reference, const Image& actual, bool implementationDefined) {
  ImageDifference diff = compareImages(reference, actual);
  ReferenceCheck check;
  check.meanAbs = diff.meanAbs;
  check.maxAbs = diff.maxAbs;
  check.differingFraction = double(diff.differingPixels) / double(std::max<std::size_t>(reference.pixelCount(), 1));
  check.pass = implementationDefined ? check.meanAbs <= ReferenceCheck::kMaxMeanDifferenceImplementationDefined
                                     : check.meanAbs <= ReferenceCheck::kMaxMeanDifference &&
                                           check.differingFraction <= ReferenceCheck::kMaxDifferingFraction;
  check.visual = std::move(diff.visual);
  return check;
}

}  // namespace glint::scenes
