#pragma once
// glint/render/post/chain.h — a chain of post effects on the GPU, frames in and out.
//
// Contents
//   uploadFrame / readFrame   an RGBA8 Image ↔ an RGBA8 texture, rows NOT flipped (texel
//                             row 0 = the picture's top row: the passes' convention)
//   Chain                     the effects of render/post/effects.h in order, ping-ponging
//                             between two RGBA8 textures
//   FrameStream               a Chain fed and drained through pixel buffer objects, a few
//                             frames in flight (glint post's GPU stage)
//   FrameView                 draws a processed frame upright into a target, with an
//                             optional before/after split
//
/// ```cpp
/// #include <glint/gl/context.h>
/// const auto context = glint::gl::HeadlessContext::create();
/// const glint::Image photo = glint::loadImage("photo.png");
/// const std::vector<std::string> specs = {"kuwahara", "edges"};
/// glint::render::post::Chain chain({photo.width(), photo.height()}, glint::render::post::parseEffects(specs));
/// const glint::gl::Texture input = glint::render::post::uploadFrame(photo);
/// const glint::gl::Texture& out = chain.run(input);  // the chain's own texture, until the next run
/// glint::saveImage(glint::render::post::readFrame(out), "npr.png");
/// ```
//
// Every intermediate is RGBA8, as a frame between two effects of a video pipeline is: a
// chain's result equals the CPU references applied one after another with 8-bit rounding
// in between, within a step per effect. The effects' own intermediates (Kuwahara's
// statistics, the FFT's buffers) are float.

#include "glint/gl/objects.h"
#include "glint/gl/render_target.h"
#include "glint/image/image.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/post/effects.h"

#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint::render::post {

/// A new RGBA8 texture holding `image` (U8 RGB or RGBA; row 0 into texel row 0).
gl::Texture uploadFrame(const Image& image, std::string_view label = "post-frame");
/// An RGBA8 texture → U8 RGBA Image, texel row 0 into row 0.
Image readFrame(const gl::Texture& texture);

class Chain {
public:
  /// Builds each effect's pass for frames of `size`. Error(Usage) from validateEffect.
  /// `precision`: U8 (RGBA8 targets, as a video's frames) or F32 (RGBA32F targets: a float
  /// image's sRGB-encoded values, unclamped, so that decoding the result gives linear light
  /// back; `glint post` on EXR).
  Chain(ivec2 size, std::vector<Effect> effects, PixelType precision = PixelType::U8);
  ~Chain();
  Chain(Chain&&) noexcept;
  Chain& operator=(Chain&&) noexcept;

  /// Runs every effect on `input` (an RGBA8, or RGBA32F for an F32 chain, texture of the chain's size) and returns the
  /// texture holding the result — one of the chain's own, valid until the next run(); the
  /// input itself when the chain is empty. The caller's framebuffer binding and viewport are
  /// put back (render::SavedTarget).
  const gl::Texture& run(const gl::Texture& input);
  /// The same with an Image in and out (uploads, runs, reads back): U8 RGB(A) in and U8 RGBA
  /// out, or F32 RGB(A) in and F32 RGBA out for an F32 chain.
  Image run(const Image& input);

  /// Replaces the effects (a viewer changing parameters or switching effects). Stages
  /// whose effect (table entry) is unchanged keep their GL objects and take the new parameters on the next
  /// run; the others are rebuilt. Error(Usage) as the constructor.
  void setEffects(std::vector<Effect> effects);

  ivec2 size() const;
  const std::vector<Effect>& effects() const;
  /// "kuwahara(size=3) → edges(scale=2,threshold=0.25)"
  std::string describe() const;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// A Chain behind pixel buffer objects. push() copies a frame into the next upload buffer
/// (persistently mapped), uploads it to a texture from there and runs the chain, then starts
/// an asynchronous readback into the next download buffer behind a fence; pop() waits for the
/// oldest frame's fence and copies it out. With `depth` frames in flight the CPU copies of
/// frame n overlap the GPU work of frames n − 1 … n − depth + 1.
///
/// ```cpp
/// const std::vector<std::string> specs = {"sepia"};
/// glint::render::post::FrameStream stream({640, 480}, glint::render::post::parseEffects(specs));
/// const std::vector<glint::Image> frames(10, glint::Image(640, 480, 4, glint::PixelType::U8));
/// std::vector<glint::Image> results;
/// glint::Image out;
/// for (const glint::Image& frame : frames) {
///   if (stream.full() && stream.pop(out)) results.push_back(out);  // the oldest result, in order
///   stream.push(frame);
/// }
/// while (stream.pop(out)) results.push_back(out);
/// ```
class FrameStream {
public:
  FrameStream(ivec2 size, std::vector<Effect> effects, int depth = 3);
  ~FrameStream();
  FrameStream(const FrameStream&) = delete;
  FrameStream& operator=(const FrameStream&) = delete;

  /// Queues one frame (U8 RGBA of the stream's size). Error(Internal) when full().
  void push(const Image& frame);
  /// The oldest queued frame's result, into `out` (resized if needed). False when empty.
  bool pop(Image& out);
  bool full() const;
  bool empty() const;
  ivec2 size() const;
  const Chain& chain() const;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// Draws a frame texture (image orientation) upright, letterboxed into `target`; with
/// `split` in (0, 1), `before` fills the left `split` of the picture and `after` the rest,
/// with a thin divider — WWDC 2003 session 212's before/after demo.
class FrameView {
public:
  FrameView();
  void draw(const gl::Target& target, const gl::Texture& after, const gl::Texture* before = nullptr,
            float split = 0.0f);

private:
  FullscreenPass m_pass;
  gl::Sampler m_sampler;  // bilinear, clamped: frames are scaled to the window
};

}  // namespace glint::render::post
