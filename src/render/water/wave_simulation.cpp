#include "glint/render/water/wave_simulation.h"

#include "glint/core/error.h"
#include "glint/render/state.h"

#include <cmath>
#include <string>

namespace glint::render::water {

WaveSimulation::WaveSimulation(ivec2 size, const sim::WaveParams& params, const sim::RainOptions& rain)
    : m_size(size), m_params(params), m_rain(rain), m_step("water/step.frag"),
      m_drop(gl::Program::fromFiles({"water/drop.vert", "water/drop.frag"})),
      m_emptyVao(gl::VertexArray::create("wave-drop")) {
  if (size.x < 1 || size.y < 1) fail(ErrorKind::Usage, "wave grid must be at least 1x1, got {}x{}", size.x, size.y);
  m_params.validate();
  for (int i = 0; i < 2; ++i) {
    const std::string name = i == 0 ? "wave-state-a" : "wave-state-b";
    m_state[std::size_t(i)] = gl::Texture(GL_TEXTURE_2D, name);
    m_state[std::size_t(i)].storage(GL_RG32F, size.x, size.y);
    // Nearest + clamp: texelFetch ignores both, but whoever samples the state (the water
    // surface's displacement) gets exact texels and no wrap-around at the walls.
    m_state[std::size_t(i)].filtering(GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
    m_framebuffers[std::size_t(i)] = gl::Framebuffer::create(name);
    m_framebuffers[std::size_t(i)].attach(GL_COLOR_ATTACHMENT0, m_state[std::size_t(i)]);
    m_framebuffers[std::size_t(i)].checkComplete();
  }
  reset();
}

void WaveSimulation::reset() {
  const float zero[2] = {0.0f, 0.0f};
  for (auto& texture : m_state) texture.clear(0, GL_RG, GL_FLOAT, zero);
  m_steps = 0;
  m_stepsBase = 0;
  m_timeBase = 0;
  m_current = 0;
  m_timeStepOfSteps = m_params.timeStep;
}

void WaveSimulation::addDrop(const sim::Drop& drop) {
  const SavedTarget saved;  // the caller's framebuffer and viewport, put back on return
  const gl::Framebuffer& fb = m_framebuffers[std::size_t(m_current)];
  fb.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  // Additive blending in the float target: height += splash, velocity += 0.
  PipelineState{.depthTest = false, .depthWrite = false, .blend = {.enabled = true, .src = GL_ONE, .dst = GL_ONE}}.apply();
  m_drop.set("uCentre", drop.centre);
  m_drop.set("uRadius", drop.radius);
  m_drop.set("uAmplitude", drop.amplitude);
  m_drop.set("uReach", 3.0f * drop.radius + 1.0f);
  m_drop.set("uStateSize", vec2(m_size));
  m_drop.use();
  m_emptyVao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 6);
  glBindVertexArray(0);
  PipelineState{.depthTest = true}.apply();
}

void WaveSimulation::stepOnce() {
  const int next = 1 - m_current;
  const SavedTarget saved;
  m_framebuffers[std::size_t(next)].bind();
  glViewport(0, 0, m_size.x, m_size.y);
  const gl::Program& program = m_step.program();
  m_state[std::size_t(m_current)].bind(0);
  gl::Sampler::unbind(0);
  program.set("uState", 0);
  program.set("uSpringConstant", m_params.springConstant);
  program.set("uRestoringConstant", m_params.restoringConstant);
  program.set("uTimeOverMass", m_params.timeStep / m_params.mass);
  program.set("uDampingFactor", m_params.dampingFactor());
  program.set("uTimeStep", m_params.timeStep);
  program.set("uWrap", m_params.wrap);
  m_step.draw();
  m_current = next;
}

void WaveSimulation::rebaseIfTimeStepChanged() {
  if (m_params.timeStep == m_timeStepOfSteps) return;
  // A new Δt from here on: keep the time reached so far (the drop schedule, counted in
  // steps, shifts a little; nothing else depends on the history).
  m_timeBase = time();
  m_stepsBase = m_steps;
  m_timeStepOfSteps = m_params.timeStep;
}

void WaveSimulation::step() {
  rebaseIfTimeStepChanged();
  if (auto drop = sim::rainDrop(m_steps, m_params, m_rain, m_size)) addDrop(*drop);
  stepOnce();
  ++m_steps;
}

void WaveSimulation::advanceTo(double time) {
  rebaseIfTimeStepChanged();
  if (time < this->time() - 1e-9) reset();
  // Whole steps: step n covers [n·Δt, (n + 1)·Δt). Counting from the last change of Δt keeps
  // the count exact (no accumulated rounding) while Δt is constant.
  const long target = m_stepsBase + long(std::ceil((time - m_timeBase) / double(m_params.timeStep) - 1e-6));
  while (m_steps < target) step();
}

void WaveSimulation::upload(const sim::WaveField& field) {
  if (field.size() != m_size) {
    fail(ErrorKind::Usage, "wave field {}x{} does not match the simulation's {}x{}", field.size().x, field.size().y,
         m_size.x, m_size.y);
  }
  // WaveField rows start at the bottom, like texture rows: no flip.
  m_state[std::size_t(m_current)].upload(0, m_size.x, m_size.y, GL_RG, GL_FLOAT, field.data().data());
}

sim::WaveField WaveSimulation::download() const {
  sim::WaveField field(m_size);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  state().read(0, GL_RG, GL_FLOAT, field.data().size() * sizeof(vec2), field.data().data());
  return field;
}

}  // namespace glint::render::water
