// post/camera — WWDC 2003 session 212's live demo: a camera (640×480, like ATI's) through the post
// effects, switched on a key (E), with a before/after split (B). The input is an option:
// a V4L2 device (/dev/video0), a video file, or an FFmpeg lavfi graph — the default, a
// test pattern, so the scene runs (and is tested) without a camera.
//
// Cameras are read on a thread that keeps the newest frame (a live source waits for no
// one); files and lavfi graphs are read in step with FrameInput::time, so a headless
// render at --time T shows the frame at T, deterministically, and a file loops.
#include "post_common.h"

#include "glint/core/error.h"
#include "glint/render/post/chain.h"
#include "glint/render/state.h"
#include "glint/video/source.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace glint::scenes {
namespace {

using render::post::Effect;

struct CameraEffect {
  const char* name;
  std::vector<std::string> specs;
};

const std::vector<CameraEffect>& cameraEffects() {
  static const std::vector<CameraEffect> e = {
      {"none", {}},
      {"sepia", {"sepia"}},
      {"horizontal edges", {"sobel:output=horizontal"}},
      {"vertical edges", {"sobel:output=vertical"}},
      {"edges", {"sobel"}},
      {"kuwahara", {"kuwahara"}},
      {"posterize", {"posterize"}},
      {"spectrum", {"spectrum"}},
      {"low-pass", {"lowpass"}},
      {"blur", {"blur"}}};
  return e;
}

constexpr const char* kDefaultInput = "lavfi:testsrc2=size=640x480:rate=30";

bool isCamera(const std::string& input) { return input.starts_with("/dev/video"); }

// The newest frame of a live source, read on its own thread.
class LiveReader {
public:
  explicit LiveReader(video::Source source) : m_source(std::move(source)) {
    m_thread = std::thread([this] {
      video::Frame frame;
      try {
        while (!m_stop && m_source.read(frame)) {
          std::lock_guard lock(m_mutex);
          std::swap(m_latest, frame);
          m_fresh = true;
          ++m_frames;
        }
        if (!m_stop) setError("the source ended");
      } catch (const Error& e) {
        setError(e.what());
      }
    });
  }
  ~LiveReader() {
    m_stop = true;
    if (m_thread.joinable()) m_thread.join();
  }
  /// Copies the newest frame into `out` when there is one not taken yet.
  bool take(video::Frame& out) {
    std::lock_guard lock(m_mutex);
    if (!m_fresh) return false;
    std::swap(out, m_latest);
    m_fresh = false;
    return true;
  }
  std::string error() {
    std::lock_guard lock(m_mutex);
    return m_error;
  }
  const video::SourceInfo& info() const { return m_source.info(); }
  std::int64_t dropped() const { return m_source.droppedFrames(); }

private:
  void setError(const std::string& e) {
    std::lock_guard lock(m_mutex);
    m_error = e;
  }
  video::Source m_source;
  std::thread m_thread;
  std::atomic<bool> m_stop{false};
  std::mutex m_mutex;
  video::Frame m_latest;
  bool m_fresh = false;
  std::int64_t m_frames = 0;
  std::string m_error;
};

class CameraScene final : public Scene {
public:
  explicit CameraScene(int effect) : m_effect(effect) {}

  std::vector<Option> options() override {
    std::vector<Option> o = {
        {"input", "a camera (/dev/video0), a video file or lavfi:GRAPH", &m_input},
        {"effect", "0 none, 1 sepia, 2 horizontal edges, 3 vertical edges, 4 edges, 5 kuwahara, 6 posterize, "
                   "7 spectrum, 8 low-pass, 9 blur",
         &m_effect, 0.0f, float(cameraEffects().size() - 1), 'E'}};
    for (auto& c : m_compare.options()) o.push_back(c);
    for (auto& p : post::effectOptions(m_effects)) o.push_back(p);
    return o;
  }

  void render(const FrameInput& frame) override {
    if (m_input != m_openInput) open();
    m_effect = std::clamp(m_effect, 0, int(cameraEffects().size()) - 1);
    if (m_effect != m_builtEffect) {
      m_effects = post::chainOf(cameraEffects()[std::size_t(m_effect)].specs);
      m_builtEffect = m_effect;
    }
    advance(frame.time);
    if (!m_texture) {  // no picture yet (a camera still starting, or an input that failed)
      frame.target.bind();
      render::clear(GL_COLOR_BUFFER_BIT, vec4(0.25f, 0.08f, 0.08f, 1.0f));
      return;
    }
    const ivec2 size(m_texture.width(), m_texture.height());
    if (!m_chain || m_chain->size() != size) m_chain.emplace(size, m_effects);
    m_chain->setEffects(m_effects);
    m_view.draw(frame.target, m_chain->run(m_texture), &m_texture, m_compare.split());
  }

  std::string notes() const override {
    std::string s = fmt::format("{}: {} ({}). E: next effect, B: before/after.", m_openInput,
                                cameraEffects()[std::size_t(m_builtEffect < 0 ? 0 : m_builtEffect)].name,
                                m_chain ? m_chain->describe() : "");
    if (m_texture) s += fmt::format(" {}x{}, frame {}.", m_texture.width(), m_texture.height(), m_frame.index);
    if (m_live) s += fmt::format(" Live; {} frame(s) dropped by the device.", m_live->dropped());
    if (!m_error.empty()) s += " Error: " + m_error;
    return s;
  }

private:
  void open() {
    m_openInput = m_input;
    m_live.reset();
    m_file.reset();
    m_error.clear();
    m_loopOffset = 0.0;
    try {
      video::Source source = video::Source::open(m_input, {.camera = isCamera(m_input), .keepAudio = false});
      if (source.info().live) m_live = std::make_unique<LiveReader>(std::move(source));
      else m_file = std::move(source);
    } catch (const Error& e) {
      if (!m_texture) throw;  // nothing to show: say why (glint render exits with it; the viewer shows it)
      m_error = e.what();     // keep the last picture and say why in the notes
    }
  }

  // The frame to show at `time`: the newest one of a live source, or the last frame of a
  // file / lavfi graph whose timestamp is ≤ time (the first frame at time 0).
  void advance(double time) {
    bool got = false;
    if (m_live) {
      got = m_live->take(m_frame);
      if (const auto e = m_live->error(); !e.empty()) m_error = e;
    } else if (m_file) {
      try {
        if (!m_hasFrame) {
          got = m_hasFrame = m_file->read(m_frame);
        }
        video::Frame next;
        const double rate = m_file->info().frameRate.valid() ? m_file->info().frameRate.value() : 30.0;
        while (m_hasFrame && m_loopOffset + m_frame.seconds + 1.0 / rate <= time + 1e-9) {
          if (m_file->read(next)) {
            std::swap(m_frame, next);
            got = true;
          } else {  // the end: loop
            m_loopOffset += m_frame.seconds + 1.0 / rate;
            m_file = video::Source::open(m_openInput, {.keepAudio = false});
            m_hasFrame = false;
            got = m_hasFrame = m_file->read(m_frame);
          }
        }
      } catch (const Error& e) {
        m_error = e.what();
        m_file.reset();
      }
    }
    if (!got) return;
    const Image& image = m_frame.image;
    if (!m_texture || m_texture.width() != image.width() || m_texture.height() != image.height()) {
      m_texture = render::post::uploadFrame(image, "post-camera-frame");
    } else {
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      m_texture.upload(0, image.width(), image.height(), GL_RGBA, GL_UNSIGNED_BYTE, image.bytes().data());
    }
  }

  std::string m_input = kDefaultInput, m_openInput;
  int m_effect = 0, m_builtEffect = -1;
  std::vector<Effect> m_effects;
  post::BeforeAfter m_compare;
  std::unique_ptr<LiveReader> m_live;
  std::optional<video::Source> m_file;
  video::Frame m_frame;
  bool m_hasFrame = false;
  double m_loopOffset = 0.0;
  std::string m_error;
  gl::Texture m_texture;
  std::optional<render::post::Chain> m_chain;
  render::post::FrameView m_view;
};

struct CameraVariant {
  const char* name;
  const char* description;
  int effect;
};

const std::vector<CameraVariant> kVariants = {
    {"sepia", "the live input in sepia (E cycles the effects, B splits before/after)", 1},
    {"edges", "Sobel edges of the live input, both directions", 4},
    {"posterize", "Kuwahara posterize with edges, live", 6},
    {"spectrum", "the live input's spectrum, every frame", 7}};

}  // namespace

void registerPostCamera(Registry& registry) {
  std::vector<VariantDesc> variants;
  for (const auto& v : kVariants) variants.push_back({v.name, v.description});
  registry.add({.name = "post/camera",
                .summary = "WWDC 2003 session 212's live demo: a camera (--set input=/dev/video0), a video file or a lavfi "
                           "source through the post effects; E switches effects, B splits before/after",
                .variants = variants,
                .needsVideo = true,
                .defaultSize = {640, 480},
                .create = [](int v) { return std::make_unique<CameraScene>(kVariants[std::size_t(v)].effect); }});
}

}  // namespace glint::scenes
