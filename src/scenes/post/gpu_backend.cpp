// glint post's GPU backend (scenes/post_gpu.h): the job's GL side.
#include "glint/scenes/post_gpu.h"

#include "glint/core/error.h"
#include "glint/gl/context.h"
#include "glint/render/post/chain.h"
#include "glint/render/post/effects.h"
#include "glint/video/transcode.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint::scenes {

namespace {

using glint::post::Effect;
using render::post::Chain;
using render::post::FrameStream;

// A FrameStream owned together with the processor that drives it.
class OwnedStream final : public video::FrameProcessor {
public:
  OwnedStream(ivec2 size, std::vector<Effect> effects) : m_stream(size, std::move(effects)), m_processor(m_stream) {}
  const FrameStream& stream() const { return m_stream; }
  void process(video::Frame&& frame, const Emit& emit) override { m_processor.process(std::move(frame), emit); }
  void flush(const Emit& emit) override { m_processor.flush(emit); }

private:
  FrameStream m_stream;
  video::StreamProcessor<FrameStream> m_processor;
};

class Backend final : public glint::post::GpuBackend {
public:
  bool onlySoftwareDevices() override { return gl::onlySoftwareDevices(); }

  std::string start(bool debug) override {
    if (!m_context) m_context = gl::HeadlessContext::create({.profile = gl::Profile::Core, .debug = debug});
    return gl::queryContextInfo().renderer;
  }

  int maxTextureSize() override { return gl::queryContextInfo().maxTextureSize; }

  Image runImage(const std::vector<Effect>& effects, const Image& frame, std::string& described) override {
    requireContext();
    Chain chain({frame.width(), frame.height()}, effects, frame.type() == PixelType::F32 ? PixelType::F32 : PixelType::U8);
    described = chain.describe();
    return chain.run(frame);
  }

  std::unique_ptr<video::FrameProcessor> videoProcessor(ivec2 size, const std::vector<Effect>& effects,
                                                        std::string& described) override {
    requireContext();
    auto processor = std::make_unique<OwnedStream>(size, effects);
    described = processor->stream().chain().describe();
    return processor;
  }

private:
  void requireContext() const {
    if (!m_context) fail(ErrorKind::Internal, "post's GPU backend used before start()");
  }
  std::unique_ptr<gl::HeadlessContext> m_context;
};

}  // namespace

std::unique_ptr<glint::post::GpuBackend> postGpuBackend() { return std::make_unique<Backend>(); }

}  // namespace glint::scenes
