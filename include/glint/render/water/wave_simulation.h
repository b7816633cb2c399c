#pragma once
// glint/render/water/wave_simulation.h — the VGP353 lecture's wave simulation on the GPU: a
// spring-network height field stepped by a fragment shader between two framebuffer
// textures (ping-pong), with drops drawn into it periodically.
//
// The physics, its parameters and their stable range are documented in sim/water.h, whose
// CPU WaveField is the reference this class is tested against (tests/water/wave_gpu_test:
// equal within float tolerance after 100 steps).
//
// State: two RG32F textures, R = height, G = velocity (the slide stores the height in RGB
// and the velocity in A of an 8-bit texture, biased by 0.5; float channels need neither).
// Each step renders a full-screen pass reading the current texture (texelFetch of the texel
// and its four neighbours) into the other one, then swaps. A drop is drawn into the current
// texture as a small quad with additive blending ("draw new waves into texture").
//
// Time: advanceTo(t) runs whole steps of params().timeStep until the simulated time reaches
// t. Scenes call it with FrameInput::time, so the viewer steps by the real frame time and
// `glint render --time t` runs the same steps headless: the picture at a time is always the
// same. Drops follow sim::rainDrop's schedule (by step number).
//
/// ```cpp
/// #include <glint/render/bump/height_to_normal.h>
/// glint::render::water::WaveSimulation waves({256, 256});  // with a current GL context
/// glint::render::bump::HeightToNormalPass normals;
/// glint::gl::Texture normalMap(GL_TEXTURE_2D, "water-normals");
/// normalMap.storage(GL_RGBA8, 256, 256);
/// const double time = 2.5;  // FrameInput::time
/// waves.advanceTo(time);
/// normals.run(waves.state(), normalMap, {.scale = 40.0f});  // heights are in .r
/// ```

#include "glint/gl/objects.h"
#include "glint/render/gpu_mesh.h"
#include "glint/sim/water.h"

#include <array>

namespace glint::render::water {

class WaveSimulation {
public:
  /// A field of `size` texels at rest. Error(Usage) for invalid params (sim::WaveParams::validate).
  explicit WaveSimulation(ivec2 size, const sim::WaveParams& params = {}, const sim::RainOptions& rain = {});

  /// One step: the scheduled drop, if any, then the spring update.
  void step();
  /// Steps until time() ≥ `time`. A time before the current one restarts from rest (and
  /// re-simulates): with a constant time step the state at a given time never depends on
  /// how it was reached.
  void advanceTo(double time);
  /// Back to rest, step 0.
  void reset();
  /// Draws one drop into the current state (heights only).
  void addDrop(const sim::Drop& drop);

  /// Replaces the state (size must match) / reads it back, for tests and the CPU comparison.
  void upload(const sim::WaveField& field);
  sim::WaveField download() const;

  /// The current RG32F state texture (R = height, G = velocity), nearest filtering, clamped.
  const gl::Texture& state() const { return m_state[m_current]; }
  ivec2 size() const { return m_size; }
  long steps() const { return m_steps; }
  /// Simulated seconds: the sum of the steps' Δt.
  double time() const { return m_timeBase + double(m_steps - m_stepsBase) * double(m_timeStepOfSteps); }

  /// Parameters are read at every step, so the viewer can change them while the water moves
  /// (a new timeStep applies from the next step on). Call validate() on them after changing;
  /// step() assumes valid values.
  sim::WaveParams& params() { return m_params; }
  const sim::WaveParams& params() const { return m_params; }
  sim::RainOptions& rain() { return m_rain; }
  const sim::RainOptions& rain() const { return m_rain; }

private:
  void stepOnce();
  void rebaseIfTimeStepChanged();

  ivec2 m_size;
  sim::WaveParams m_params;
  sim::RainOptions m_rain;
  float m_timeStepOfSteps = 0;  // Δt of the steps since m_stepsBase
  double m_timeBase = 0;        // simulated time at step m_stepsBase (where Δt last changed)
  long m_stepsBase = 0;
  long m_steps = 0;
  int m_current = 0;
  std::array<gl::Texture, 2> m_state;
  std::array<gl::Framebuffer, 2> m_framebuffers;
  FullscreenPass m_step;
  gl::Program m_drop;
  gl::VertexArray m_emptyVao;  // the drop quad is generated from gl_VertexID
};

}  // namespace glint::render::water
