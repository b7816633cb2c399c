#version 450 core
// One step of the VGP353 lecture's wave simulation (sim/water.h documents the model):
//   F  = k·(n + s + e + w − 4h) + k_rest·(0 − h)
//   v' = (v + Δt/m · F) · exp(−damping·Δt)
//   h' = h + Δt · v'
// Same order of operations as sim::WaveField::step, the CPU reference.

layout(location = 0) out vec2 fragState;  // R = height, G = velocity (RG32F)

uniform sampler2D uState;
uniform float uSpringConstant;     // k, between neighbours
uniform float uRestoringConstant;  // k_rest, towards height 0 (the slide's "0.5 - me.x" term)
uniform float uTimeOverMass;       // Δt / m (the slide's "mass" uniform)
uniform float uDampingFactor;      // exp(−damping·Δt), computed once on the CPU
uniform float uTimeStep;           // Δt (the slide's "time")
uniform bool uWrap;                // periodic edges; otherwise a missing neighbour is the texel itself

float heightAt(ivec2 p, ivec2 size, float self) {
  if (uWrap) return texelFetch(uState, (p + size) % size, 0).r;
  // A reflecting wall: no spring across the edge, i.e. the neighbour reads as the texel itself.
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) return self;
  return texelFetch(uState, p, 0).r;
}

void main() {
  ivec2 size = textureSize(uState, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 me = texelFetch(uState, p, 0).rg;
  // `precise` keeps the compiler from fusing multiply-adds, so the GPU rounds like the CPU.
  precise float neighbours = heightAt(p + ivec2(0, 1), size, me.x) + heightAt(p - ivec2(0, 1), size, me.x) +
                             heightAt(p + ivec2(1, 0), size, me.x) + heightAt(p - ivec2(1, 0), size, me.x);
  precise float force = uSpringConstant * (neighbours - 4.0 * me.x) + uRestoringConstant * (0.0 - me.x);
  precise float v = (me.y + uTimeOverMass * force) * uDampingFactor;
  precise float h = me.x + uTimeStep * v;
  fragState = vec2(h, v);
}
