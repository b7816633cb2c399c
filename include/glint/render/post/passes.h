#pragma once
// glint/render/post/passes.h — WWDC 2003 session 212's image-space effects as GPU passes, texture in,
// texture out: compute shaders (shaders/post/*.comp, one invocation a texel), or the
// fragment shaders on a full-screen triangle they replace (*.frag, PassStage::Fragment).
//
// Why compute (issue 37): a datacenter GPU (H100, H200) runs graphics on a small part of the
// chip — 8 ROPs, 2 of 66 TPCs — while compute shaders use every SM; a minimal RGBA8 pass
// measured 11–25× faster as a compute shader there. Both stages share one function per
// texel (post/<pass>.glsl), so they give the same bytes
// (tests/post/gpu_test.cpp: PostGpu.ComputeAndFragmentPassesGiveTheSameTexels).
//
// Contents
//   TexelPass      what the texel-wise passes share: compute or fragment, sizes checked
//   SepiaPass      "a dot product and an add" (shaders/post/sepia.glsl)
//   SobelPass      the two 3×3 kernels, eight texel fetches (sobel.glsl)
//   EdgesPass      Sobel lines composited over the image (edges.glsl)
//   KuwaharaPass   the calmest of four quadrants' means. Compute: one pass of 16×16
//                  shared-memory tiles, each block's sums taken once per tile
//                  (kuwahara.comp). Fragment: WWDC 2003 session 212's two passes, statistics of every
//                  s×s block into a float texture (kuwahara_stats.glsl), then four fetches
//                  and the calmest mean (kuwahara_select.glsl)
//
// Conventions: image/post.h's, exactly — same luma weights, same border rule (texelFetch
// at clamped coordinates), same arithmetic. Textures hold frames in image orientation:
// texel row 0 is the picture's TOP row (as decoded video and image files are uploaded
// without flipping, render/post/chain.h's uploadFrame), so "down" is +y in texel
// coordinates and the Sobel signs match OpenCV's on the same rows. Inputs and outputs are
// 2D textures of equal size; outputs RGBA8 (glint post: the result is rounded to 8 bits,
// one step of the reference at most) or RGBA32F (a float chain), the formats the compute
// shaders store.
//
/// ```cpp
/// glint::gl::Texture frame(GL_TEXTURE_2D, "frame"), result(GL_TEXTURE_2D, "result");
/// frame.storage(GL_RGBA8, 640, 480);
/// result.storage(GL_RGBA8, 640, 480);
/// glint::render::post::SepiaPass sepia;
/// sepia.run(frame, result, {.i = 0.2f, .q = 0.0f});
/// ```
//
// A compute run() binds the output as image unit 0 and ends with the memory barrier that
// lets the next pass sample it; a fragment run() sets the state it draws with (depth, blend
// and culling off; the viewport to the output) and puts the caller's framebuffer binding and
// viewport back (render::SavedTarget). Cost: one
// pass (Kuwahara two) per pixel, independent of what the frame shows — WWDC 2003 session 212's point
// about post effects.

#include "glint/gl/objects.h"
#include "glint/image/post.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/post/effects.h"

#include <optional>
#include <string>

namespace glint::render::post {

/// Where a pass runs: a compute shader (the default) or its fragment version.
enum class PassStage { Compute, Fragment };

/// A compute pass's program in both output formats (RGBA8, RGBA32F: the chain's targets),
/// made on first use, and its dispatch over an output texture.
class ComputePass {
public:
  explicit ComputePass(std::string file) : m_file(std::move(file)) {}
  /// The program for `output`'s format (RGBA8 or RGBA32F; Error(Usage) for another).
  const gl::Program& program(const gl::Texture& output);
  /// Binds `output` as image unit 0 and runs one invocation a texel, then the barrier that
  /// lets the next pass sample, read back or attach it.
  void dispatch(const gl::Texture& output);

private:
  std::string m_file;
  gl::Program m_rgba8, m_rgba32f;
};

/// What the texel-wise passes (sepia, Sobel, edges) share: the pass as a compute shader
/// (post/<name>.comp) or, for PassStage::Fragment, the full-screen fragment shader
/// (post/<name>.frag) into a framebuffer of its own. A pass's run() is begin(), its
/// uniforms, finish().
class TexelPass {
public:
  TexelPass(const char* name, PassStage stage);
  PassStage stage() const { return m_stage; }
  /// Checks that `input` and `output` have one size (Error(Usage) naming the pass), binds
  /// `input` to unit 0 (uniform uInput) and returns the program for the pass's uniforms.
  const gl::Program& begin(const gl::Texture& input, const gl::Texture& output);
  /// Runs the pass into `output`: a dispatch, or a draw that puts the caller's framebuffer
  /// and viewport back.
  void finish(const gl::Texture& output);

private:
  const char* m_name;
  PassStage m_stage;
  ComputePass m_compute;
  std::optional<FullscreenPass> m_fragment;  ///< PassStage::Fragment only
  gl::Framebuffer m_framebuffer;
};

class SepiaPass {
public:
  explicit SepiaPass(PassStage stage = PassStage::Compute) : m_pass("sepia", stage) {}
  void run(const gl::Texture& input, const gl::Texture& output, const SepiaOptions& options = {});
  PassStage stage() const { return m_pass.stage(); }

private:
  TexelPass m_pass;
};

class SobelPass {
public:
  explicit SobelPass(PassStage stage = PassStage::Compute) : m_pass("sobel", stage) {}
  void run(const gl::Texture& input, const gl::Texture& output, const SobelOptions& options = {});
  PassStage stage() const { return m_pass.stage(); }

private:
  TexelPass m_pass;
};

class EdgesPass {
public:
  explicit EdgesPass(PassStage stage = PassStage::Compute) : m_pass("edges", stage) {}
  void run(const gl::Texture& input, const gl::Texture& output, const EdgesOptions& options = {});
  PassStage stage() const { return m_pass.stage(); }

private:
  TexelPass m_pass;
};

class KuwaharaPass {
public:
  explicit KuwaharaPass(PassStage stage = PassStage::Compute);
  PassStage stage() const { return m_stage; }
  /// The filtered image into `output`. Compute: one pass (post/kuwahara.comp), each 16×16
  /// tile summing its blocks once in shared memory. Fragment: pass 1 into an RGBA32F
  /// statistics texture of (w + s − 1) × (h + s − 1) texels (one per block position,
  /// including blocks hanging over the border; reallocated when the size or s changes),
  /// pass 2 into `output`. With `showQuadrant`, `output` gets the chosen quadrant's number q
  /// instead of the mean, as q/255 in every channel (tests read it back).
  void run(const gl::Texture& input, const gl::Texture& output, const KuwaharaOptions& options = {},
           bool showQuadrant = false);

private:
  PassStage m_stage;
  ComputePass m_compute;
  std::optional<FullscreenPass> m_stats, m_select;  ///< PassStage::Fragment only
  gl::Texture m_statistics;                         ///< PassStage::Fragment only
  gl::Framebuffer m_statsFramebuffer;
  gl::Framebuffer m_framebuffer;
};

/// A one-shader effect: `shader` (a path under shaders/, e.g. "post/edges.frag") reads the
/// frame as `uniform sampler2D uInput` (texelFetch) and takes each parameter of the effect
/// as a uniform named "u" + the parameter's name with a capital ("threshold" → uThreshold;
/// Float as float, Int and Choice as int). A parameter the shader does not use is ignored.

}  // namespace glint::render::post
