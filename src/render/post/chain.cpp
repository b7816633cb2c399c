#include "glint/render/post/chain.h"

#include "glint/core/error.h"
#include "glint/image/post.h"
#include "glint/render/state.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <string_view>

namespace glint::render::post {

gl::Texture uploadFrame(const Image& image, std::string_view label) {
  gl::Texture texture(GL_TEXTURE_2D, label);
  if (image.type() == PixelType::F32) {  // a float image's encoded values, unclamped
    if (image.channels() < 3) fail(ErrorKind::Usage, "post effects take RGB or RGBA images, got {} channel(s)", image.channels());
    const Image rgba = image.withChannels(4);
    texture.storage(GL_RGBA32F, rgba.width(), rgba.height());
    texture.upload(0, rgba.width(), rgba.height(), GL_RGBA, GL_FLOAT, rgba.bytes().data());
    return texture;
  }
  const Image rgba = postInput(image);
  texture.storage(GL_RGBA8, rgba.width(), rgba.height());
  texture.upload(0, rgba.width(), rgba.height(), GL_RGBA, GL_UNSIGNED_BYTE, rgba.bytes().data());
  return texture;
}

Image readFrame(const gl::Texture& texture) {
  if (texture.internalFormat() == GL_RGBA32F) {
    Image image(texture.width(), texture.height(), 4, PixelType::F32);
    texture.read(0, GL_RGBA, GL_FLOAT, image.bytes().size(), image.bytes().data());
    return image;
  }
  Image image(texture.width(), texture.height(), 4, PixelType::U8);
  texture.read(0, GL_RGBA, GL_UNSIGNED_BYTE, image.bytes().size(), image.bytes().data());
  return image;
}

// ---------------------------------------------------------------------------
// One effect's GPU pass: the table entry's stage, run with the effect's current values.
struct Stage {
  Effect effect;
  std::unique_ptr<EffectStage> pass;

  explicit Stage(Effect e) : effect(std::move(e)), pass(gpuStage(*effect.def)) {}
  void run(const gl::Texture& in, const gl::Texture& out) { pass->run(in, out, effect); }
};

struct Chain::Impl {
  ivec2 size;
  GLenum format = GL_RGBA8;  ///< of the targets: GL_RGBA8, or GL_RGBA32F for an F32 chain
  std::vector<Effect> effects;
  std::vector<Stage> stages;
  gl::Texture targets[2];
};

Chain::Chain(ivec2 size, std::vector<Effect> effects, PixelType precision) : m_impl(std::make_unique<Impl>()) {
  if (size.x < 1 || size.y < 1) fail(ErrorKind::Usage, "frame size must be positive, got {}x{}", size.x, size.y);
  if (precision != PixelType::U8 && precision != PixelType::F32)
    fail(ErrorKind::Usage, "a post chain works on U8 or F32 frames, not {}", pixelTypeName(precision));
  m_impl->format = precision == PixelType::F32 ? GL_RGBA32F : GL_RGBA8;
  for (const auto& e : effects) validateEffect(e, size);
  m_impl->size = size;
  m_impl->effects = std::move(effects);
  for (const auto& e : m_impl->effects) m_impl->stages.emplace_back(e);
  for (int i = 0; i < 2 && i < int(m_impl->effects.size()); ++i) {
    m_impl->targets[i] = gl::Texture(GL_TEXTURE_2D, i == 0 ? "post-ping" : "post-pong");
    m_impl->targets[i].storage(m_impl->format, size.x, size.y);
  }
}

Chain::~Chain() = default;
Chain::Chain(Chain&&) noexcept = default;
Chain& Chain::operator=(Chain&&) noexcept = default;

const gl::Texture& Chain::run(const gl::Texture& input) {
  Impl& c = *m_impl;
  if (input.width() != c.size.x || input.height() != c.size.y) {
    fail(ErrorKind::Usage, "frame {}x{} does not match the chain's {}x{}", input.width(), input.height(), c.size.x,
         c.size.y);
  }
  if (!c.stages.empty() && input.internalFormat() != c.format)
    fail(ErrorKind::Usage, "a {} frame for a chain of {} targets", input.internalFormat() == GL_RGBA32F ? "float" : "8-bit",
         c.format == GL_RGBA32F ? "float" : "8-bit");
  const gl::Texture* current = &input;
  // Each stage puts the caller's framebuffer and viewport back (render::SavedTarget).
  for (std::size_t i = 0; i < c.stages.size(); ++i) {
    const gl::Texture& out = c.targets[i % 2];
    c.stages[i].run(*current, out);
    current = &out;
  }
  return *current;
}

Image Chain::run(const Image& input) {
  const gl::Texture texture = uploadFrame(input, "post-input");
  return readFrame(run(texture));
}

void Chain::setEffects(std::vector<Effect> effects) {
  Impl& c = *m_impl;
  for (const auto& e : effects) validateEffect(e, c.size);
  if (c.stages.size() > effects.size()) c.stages.erase(c.stages.begin() + std::ptrdiff_t(effects.size()), c.stages.end());
  for (std::size_t i = 0; i < effects.size(); ++i) {
    if (i < c.stages.size() && c.stages[i].effect.def == effects[i].def) {
      c.stages[i].effect = effects[i];
    } else if (i < c.stages.size()) {
      c.stages[i] = Stage(effects[i]);
    } else {
      c.stages.emplace_back(effects[i]);
    }
  }
  for (int i = 0; i < 2 && i < int(effects.size()); ++i) {
    if (c.targets[i]) continue;
    c.targets[i] = gl::Texture(GL_TEXTURE_2D, i == 0 ? "post-ping" : "post-pong");
    c.targets[i].storage(c.format, c.size.x, c.size.y);
  }
  c.effects = std::move(effects);
}

ivec2 Chain::size() const { return m_impl->size; }
const std::vector<Effect>& Chain::effects() const { return m_impl->effects; }

std::string Chain::describe() const {
  std::string s;
  for (const auto& e : m_impl->effects) s += (s.empty() ? "" : " → ") + e.describe();
  return s.empty() ? "(no effect)" : s;
}

// ---------------------------------------------------------------------------
// FrameStream's parts: in a named namespace, not an anonymous one, since FrameStream::Impl
// (a member of a public class) holds them.
namespace stream_detail {
// A persistently mapped buffer for pixel transfers.
struct MappedBuffer {
  gl::Buffer buffer;
  std::byte* data = nullptr;

  MappedBuffer(std::size_t bytes, bool upload, std::string_view name) {
    const GLbitfield access = GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT | (upload ? GL_MAP_WRITE_BIT : GL_MAP_READ_BIT);
    buffer = gl::Buffer(bytes, nullptr, access, name);
    data = static_cast<std::byte*>(buffer.map(0, bytes, access));
    if (!data) fail(ErrorKind::Internal, "cannot map a {} MiB pixel buffer", bytes >> 20);
  }
};

struct Slot {
  MappedBuffer upload, download;
  gl::Texture input;
  GLsync fence = nullptr;
};
}  // namespace stream_detail
using stream_detail::MappedBuffer;
using stream_detail::Slot;

struct FrameStream::Impl {
  Chain chain;
  std::size_t bytes = 0;
  std::vector<Slot> slots;
  std::deque<std::size_t> inFlight;  // slot indices, oldest first
  std::size_t next = 0;

  Impl(ivec2 size, std::vector<Effect> effects) : chain(size, std::move(effects)) {}
};

FrameStream::FrameStream(ivec2 size, std::vector<Effect> effects, int depth)
    : m_impl(std::make_unique<Impl>(size, std::move(effects))) {
  if (depth < 1) fail(ErrorKind::Usage, "FrameStream: depth must be at least 1, got {}", depth);
  m_impl->bytes = std::size_t(size.x) * std::size_t(size.y) * 4;
  for (int i = 0; i < depth; ++i) {
    Slot slot{MappedBuffer(m_impl->bytes, true, "post-upload"), MappedBuffer(m_impl->bytes, false, "post-download"),
              gl::Texture(GL_TEXTURE_2D, "post-stream-input"), nullptr};
    slot.input.storage(GL_RGBA8, size.x, size.y);
    m_impl->slots.push_back(std::move(slot));
  }
}

FrameStream::~FrameStream() {
  for (auto& slot : m_impl->slots)
    if (slot.fence) glDeleteSync(slot.fence);
}

bool FrameStream::full() const { return m_impl->inFlight.size() == m_impl->slots.size(); }
bool FrameStream::empty() const { return m_impl->inFlight.empty(); }
ivec2 FrameStream::size() const { return m_impl->chain.size(); }
const Chain& FrameStream::chain() const { return m_impl->chain; }

void FrameStream::push(const Image& frame) {
  Impl& s = *m_impl;
  if (full()) fail(ErrorKind::Internal, "FrameStream::push while full: pop() first");
  const ivec2 size = s.chain.size();
  if (frame.width() != size.x || frame.height() != size.y || frame.channels() != 4 || frame.type() != PixelType::U8) {
    fail(ErrorKind::Usage, "FrameStream: expected a {}x{} RGBA8 frame", size.x, size.y);
  }
  Slot& slot = s.slots[s.next];
  s.next = (s.next + 1) % s.slots.size();
  std::memcpy(slot.upload.data, frame.bytes().data(), s.bytes);
  slot.upload.buffer.bind(GL_PIXEL_UNPACK_BUFFER);
  slot.input.upload(0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);  // from the bound buffer
  gl::Buffer::unbind(GL_PIXEL_UNPACK_BUFFER);
  const gl::Texture& result = s.chain.run(slot.input);
  slot.download.buffer.bind(GL_PIXEL_PACK_BUFFER);
  result.read(0, GL_RGBA, GL_UNSIGNED_BYTE, s.bytes, nullptr);  // into the bound buffer, asynchronously
  gl::Buffer::unbind(GL_PIXEL_PACK_BUFFER);
  slot.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  glFlush();  // start the work now; pop() waits for it
  s.inFlight.push_back(std::size_t(&slot - s.slots.data()));
}

bool FrameStream::pop(Image& out) {
  Impl& s = *m_impl;
  if (s.inFlight.empty()) return false;
  Slot& slot = s.slots[s.inFlight.front()];
  s.inFlight.pop_front();
  while (true) {
    const GLenum r = glClientWaitSync(slot.fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);
    if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED) break;
    if (r == GL_WAIT_FAILED) fail(ErrorKind::Internal, "waiting for a frame's readback failed");
  }
  glDeleteSync(slot.fence);
  slot.fence = nullptr;
  const ivec2 size = s.chain.size();
  if (out.width() != size.x || out.height() != size.y || out.channels() != 4 || out.type() != PixelType::U8) {
    out = Image(size.x, size.y, 4, PixelType::U8);
  }
  std::memcpy(out.bytes().data(), slot.download.data, s.bytes);
  return true;
}

// ---------------------------------------------------------------------------
FrameView::FrameView() : m_pass("post/show.frag"), m_sampler(gl::Sampler::create("post-view")) {
  m_sampler.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  m_sampler.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  m_sampler.parameter(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  m_sampler.parameter(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void FrameView::draw(const gl::Target& target, const gl::Texture& after, const gl::Texture* before, float split) {
  target.bind();
  render::clear(GL_COLOR_BUFFER_BIT, vec4(0.0f, 0.0f, 0.0f, 1.0f));
  // Letterbox: the largest rectangle of the frame's aspect ratio inside the target.
  const vec2 frame(float(after.width()), float(after.height()));
  const float scale = std::min(float(target.size.x) / frame.x, float(target.size.y) / frame.y);
  const ivec2 extent = max(ivec2(frame * scale + 0.5f), ivec2(1));
  const gl::Target picture = target.region((target.size - extent) / 2, extent);
  picture.bind();
  after.bind(0);
  (before ? *before : after).bind(1);
  m_sampler.bind(0);
  m_sampler.bind(1);
  const auto& program = m_pass.program();
  program.set("uAfter", 0);
  program.set("uBefore", 1);
  program.set("uSplit", before ? split : 0.0f);
  program.set("uDividerWidth", 2.0f / float(extent.x));
  m_pass.draw();
  gl::Sampler::unbind(0);
  gl::Sampler::unbind(1);
  target.bind();
}

}  // namespace glint::render::post
