// The interactive viewer (viewer/viewer.h): a GLFW window, a Dear ImGui panel, every scene.
//
// Keys: ←/→ previous/next variant, ↑/↓ previous/next scene, Space pause time,
// R reload shaders, F12 screenshot, Tab hide/show the panel, Esc quit; other letters and
// digits go to the scene (Scene::keyPressed: an option's key, shown beside it, or
// pipedream's demo toggles). Run from a source
// checkout, shaders are re-read from shaders/ whenever a file changes (hot reload).
//
// The mouse moves the camera of every 3D scene (the scenes pass their camera through
// FrameInput::camera): left drag orbits around the camera's target, right or middle drag
// pans, the wheel zooms, C or Home returns to the scene's own camera. The moved view
// stays while stepping through the variants of one scene (they are made to be compared
// from one viewpoint) and goes back to the defined camera on another scene. 2D views
// (images, NDC geometry) ask for no camera, and the mouse leaves them alone.
#include "glint/viewer/viewer.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/gl/debug.h"
#include "glint/gl/shader.h"
#include "glint/gl/timer.h"
#include "glint/gl/window.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>

namespace glint::viewer {
namespace fs = std::filesystem;

namespace {
/// What a mouse drag over the scene does.
enum class Drag {
  None,   ///< no drag, or one that belongs to the panel
  Orbit,  ///< left button: turn around the camera's target
  Pan,    ///< right or middle button: move eye and target in the view plane
};

/// One input event, as GLFW reported it.
struct InputEvent {
  enum class Kind {
    Key,     ///< a key pressed (code: GLFW_KEY_*)
    Button,  ///< a mouse button pressed or released (code: GLFW_MOUSE_BUTTON_*, action)
    Move,    ///< the pointer moved to `value` (window units)
    Wheel,   ///< the wheel turned by value.y notches (positive: away from the user)
  };
  Kind kind;
  int code = 0;
  int action = 0;
  vec2 value{0.0f};
};

constexpr float kOrbitPerHeight = kPi;  // radians of turn for a drag over the window's height
constexpr float kZoomPerNotch = 0.9f;   // distance factor per wheel notch towards the scene

// Newest modification time of any file under dir (0 when dir is not set).
fs::file_time_type newestShaderTime(const fs::path& dir) {
  fs::file_time_type newest{};
  std::error_code ec;
  if (dir.empty()) return newest;
  for (const auto& entry : fs::recursive_directory_iterator(dir, ec))
    if (entry.is_regular_file(ec)) newest = std::max(newest, entry.last_write_time(ec));
  return newest;
}

/// DejaVu Sans (Debian's fonts-dejavu-core): ImGui's built-in font has ASCII only, and the
/// scenes' texts use —, ×, ·, ², √, −, →, σ.
constexpr const char* kPanelFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr float kPanelFontPixels = 15.0f;

/// Every text the panel shows of a registry: summaries, variants' and options' descriptions
/// would be built from the scenes themselves, so the names and descriptions of the registry.
std::string panelText(const scenes::Registry& registry) {
  std::string text;
  for (const scenes::SceneDesc& s : registry.scenes()) {
    text += s.name + s.summary;
    for (const scenes::VariantDesc& v : s.variants) text += v.name + v.description;
  }
  return text;
}

/// Loads the panel's font into the current ImGui context with a glyph for every character
/// of `text` (and ASCII): false, and ImGui's own font, when the font file is missing.
bool loadPanelFont(const std::string& text) {
  ImGuiIO& io = ImGui::GetIO();
  std::error_code ec;
  if (!fs::exists(kPanelFont, ec)) return false;
  ImFontGlyphRangesBuilder builder;
  builder.AddRanges(io.Fonts->GetGlyphRangesDefault());
  builder.AddText(text.c_str());
  builder.AddText("—×·²√−→σ°…");  // option descriptions and notes are made as scenes load
  static ImVector<ImWchar> ranges;  // ImGui keeps a pointer to them until the atlas is built
  ranges.clear();
  builder.BuildRanges(&ranges);
  return io.Fonts->AddFontFromFileTTF(kPanelFont, kPanelFontPixels, nullptr, ranges.Data) != nullptr;
}

class Viewer {
public:
  Viewer(const ViewerOptions& args, const scenes::Registry& registry)
      : m_args(args), m_window(args.size, "glint", args.glDebug), m_registry(registry) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini litter in the working directory
    ImGui::StyleColorsDark();
    if (!loadPanelFont(panelText(registry)))
      log::warn("view: {} is missing (Debian's fonts-dejavu-core): the panel shows ? for non-ASCII text", kPanelFont);
    installInputCallbacks();  // before ImGui's backend, which then chains to them
    ImGui_ImplGlfw_InitForOpenGL(m_window.handle(), true);
    ImGui_ImplOpenGL3_Init("#version 450");
    const auto& all = m_registry.allVariants();
    m_variants.assign(all.begin(), all.end());
    if (!args.scene.empty()) {
      const auto ref = m_registry.resolve(args.scene);
      for (std::size_t i = 0; i < m_variants.size(); ++i)
        if (m_variants[i].scene == ref.scene && m_variants[i].variant == ref.variant) m_current = i;
    }
    m_shaderTime = newestShaderTime(gl::ShaderSources::directory());
    load(m_current);
  }

  ~Viewer() {
    m_scene.reset();  // GL objects go before the context
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwSetWindowUserPointer(m_window.handle(), nullptr);
  }

  int run() {
    auto last = std::chrono::steady_clock::now();
    int frame = 0;
    while (!m_window.shouldClose()) {
      m_window.pollEvents();
      const auto now = std::chrono::steady_clock::now();
      const double dt = std::chrono::duration<double>(now - last).count();
      last = now;
      if (!m_paused) m_time += dt;
      handleInput();
      checkHotReload();
      drawFrame(dt);
      ++frame;
      if (m_shotRequested) saveShot();
      m_shotRequested = false;
      if (!m_args.screenshot.empty() && frame >= std::max(m_args.frames, 2)) {
        const ivec2 size = m_window.framebufferSize();
        saveImage(gl::readColor(gl::Framebuffer::defaultFramebuffer(), size), m_args.screenshot);
        log::info("screenshot → {}", m_args.screenshot);
        return 0;
      }
      m_window.swapBuffers();
    }
    return 0;
  }

private:
  void load(std::size_t index) {
    const auto ref = m_variants[index];
    if (ref.scene->profile != gl::Profile::Core) {
      m_error = "this variant needs a compatibility-profile context; the viewer's window is core — use `glint render`";
      m_scene.reset();
      m_current = index;
      updateTitle();
      return;
    }
    try {
      auto scene = ref.scene->create(ref.variant);
      applySettings(*scene);
      m_scene = std::move(scene);
      m_error.clear();
    } catch (const Error& e) {
      m_error = e.what();  // keep the previous scene running (e.g. a shader typo while hot-reloading)
      if (index != m_current) m_scene.reset();
    }
    if (index != m_current) m_time = ref.scene->defaultTime;
    if (ref.scene != m_variants[m_current].scene) resetView();  // another scene, another world: its own camera
    m_defined.reset();  // known again once the new scene has drawn a frame
    m_current = index;
    updateTitle();
  }

  // --set: each assignment goes to every scene that has such an option (others ignore it).
  void applySettings(scenes::Scene& scene) const {
    for (const auto& assignment : m_args.settings) {
      const std::string name = assignment.substr(0, assignment.find('='));
      const auto options = scene.options();
      if (std::any_of(options.begin(), options.end(), [&](const scenes::Option& o) { return o.name == name; }))
        scenes::setOption(scene, assignment);
    }
  }

  // Options with a key (Option::key): a bool toggles, an int steps through its range.
  void updateTitle() { m_window.setTitle("glint — " + m_variants[m_current].fullName()); }

  void step(int delta, bool wholeScene) {
    const std::size_t n = m_variants.size();
    std::size_t i = m_current;
    if (!wholeScene) {
      i = (i + n + std::size_t(delta + int(n))) % n;
    } else {
      const auto* scene = m_variants[m_current].scene;
      do {
        i = (i + n + std::size_t(delta + int(n))) % n;
      } while (m_variants[i].scene == scene && i != m_current);
      while (delta < 0 && i > 0 && m_variants[i - 1].scene == m_variants[i].scene) --i;  // first variant
    }
    load(i);
  }

  // -- Input ---------------------------------------------------------------------------
  // Keys and the mouse arrive through GLFW's callbacks and are handled in the order they
  // happened: a key tapped between two frames, or a press, drag and release between two
  // frames (a slow frame, or synthetic input), is seen whole, and "C, then drag" never
  // becomes "drag, then C". Polling the state once a frame would lose or reorder them.

  static Viewer* self(GLFWwindow* window) { return static_cast<Viewer*>(glfwGetWindowUserPointer(window)); }

  void installInputCallbacks() {
    GLFWwindow* w = m_window.handle();
    glfwSetWindowUserPointer(w, this);
    using Kind = InputEvent::Kind;
    glfwSetKeyCallback(w, [](GLFWwindow* window, int key, int, int action, int) {
      if (Viewer* v = self(window); v && action == GLFW_PRESS) v->m_input.push_back({.kind = Kind::Key, .code = key});
    });
    glfwSetMouseButtonCallback(w, [](GLFWwindow* window, int button, int action, int) {
      if (Viewer* v = self(window)) v->m_input.push_back({.kind = Kind::Button, .code = button, .action = action});
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* window, double x, double y) {
      if (Viewer* v = self(window)) v->m_input.push_back({.kind = Kind::Move, .value = vec2(float(x), float(y))});
    });
    glfwSetScrollCallback(w, [](GLFWwindow* window, double, double y) {
      if (Viewer* v = self(window)) v->m_input.push_back({.kind = Kind::Wheel, .value = vec2(0.0f, float(y))});
    });
  }

  /// Handles the events since the last frame, in order. A screenshot (F12) ends the batch:
  /// the frame drawn next shows exactly the events before it; the rest wait a frame.
  void handleInput() {
    while (!m_input.empty()) {
      const InputEvent e = m_input.front();
      m_input.pop_front();
      switch (e.kind) {
        case InputEvent::Kind::Key: keyPressed(e.code); break;
        case InputEvent::Kind::Button: mouseButton(e.code, e.action); break;
        case InputEvent::Kind::Move: mouseMoved(e.value); break;
        case InputEvent::Kind::Wheel: mouseWheel(e.value.y); break;
      }
      if (m_shotRequested) return;
    }
  }

  void keyPressed(int key) {
    if (key == GLFW_KEY_ESCAPE) m_window.requestClose();
    // Keys go to the panel only while one of its text fields is edited (Ctrl+click on a
    // slider). Not io.WantCaptureKeyboard: it also holds while the panel is being dragged,
    // and it dates from the last frame, which a key pressed right after a drag outruns.
    if (ImGui::GetIO().WantTextInput) return;
    switch (key) {
      case GLFW_KEY_RIGHT: step(+1, false); break;
      case GLFW_KEY_LEFT: step(-1, false); break;
      case GLFW_KEY_DOWN: step(+1, true); break;
      case GLFW_KEY_UP: step(-1, true); break;
      case GLFW_KEY_SPACE: m_paused = !m_paused; break;
      case GLFW_KEY_R: load(m_current); break;
      case GLFW_KEY_TAB: m_showPanel = !m_showPanel; break;
      case GLFW_KEY_C:
      case GLFW_KEY_HOME: resetView(); break;
      case GLFW_KEY_F12: m_shotRequested = true; break;
      default:
        // Letters and digits the viewer leaves free go to the scene (GLFW's codes are ASCII).
        if (m_scene && ((key >= GLFW_KEY_A && key <= GLFW_KEY_Z) || (key >= GLFW_KEY_0 && key <= GLFW_KEY_9)))
          m_scene->keyPressed(key);
        break;
    }
  }

  // A press belongs to the panel when it lands on it, or while one of its popups is open
  // or one of its widgets is held. That is what io.WantCaptureMouse says, asked for the
  // press's own position: ImGui 1.86 computes WantCaptureMouse from where the pointer was
  // at the last frame, which a quick move-and-click has already left.
  bool panelOwns(vec2 p) const {
    const bool onPanel = p.x >= m_panelMin.x && p.y >= m_panelMin.y && p.x < m_panelMax.x && p.y < m_panelMax.y;
    return onPanel || m_panelBusy;
  }

  void mouseButton(int button, int action) {
    if (action == GLFW_RELEASE) {
      if (button == m_dragButton) m_drag = Drag::None;
      return;
    }
    if (m_drag != Drag::None || !m_defined || panelOwns(m_cursor)) return;
    if (button == GLFW_MOUSE_BUTTON_LEFT) m_drag = Drag::Orbit;
    else if (button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE) m_drag = Drag::Pan;
    else return;
    m_dragButton = button;
  }

  void mouseMoved(vec2 p) {
    const vec2 delta = p - m_cursor;
    m_cursor = p;
    if (m_drag == Drag::None || !m_defined) return;
    int width = 0, height = 0;
    glfwGetWindowSize(m_window.handle(), &width, &height);  // cursor positions are in window units
    const float h = float(std::max(height, 1));
    // Grab the scene: it follows the pointer. Dragging right turns the eye to the left
    // (yaw down), dragging down lifts it (pitch up) — the convention of Blender and
    // three.js's OrbitControls.
    if (m_drag == Drag::Orbit) m_view.orbitBy(-delta.x / h * kOrbitPerHeight, delta.y / h * kOrbitPerHeight, *m_defined);
    else m_view.panBy(vec2(-delta.x, delta.y) / h, *m_defined);
  }

  void mouseWheel(float notches) {
    if (!m_defined || panelOwns(m_cursor)) return;  // over the panel the wheel scrolls the panel
    m_view.zoomBy(std::pow(kZoomPerNotch, notches));
  }

  void resetView() {
    m_view = {};
    m_drag = Drag::None;
  }

  /// F12: the window as it is now, into --shot-dir as glint-view-N.png (the first N not taken).
  void saveShot() {
    const fs::path dir(m_args.shotDir);
    const auto name = [&](int n) { return dir / fmt::format("glint-view-{}.png", n); };
    std::error_code ec;
    int n = 1;
    while (fs::exists(name(n), ec)) ++n;
    const fs::path path = name(n);
    try {
      saveImage(gl::readColor(gl::Framebuffer::defaultFramebuffer(), m_window.framebufferSize()), path);
      log::info("screenshot → {}", path.string());
    } catch (const Error& e) {
      m_error = e.what();  // e.g. an unwritable --shot-dir: say so in the panel, keep running
    }
  }

  void checkHotReload() {
    const auto& dir = gl::ShaderSources::directory();
    if (dir.empty()) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - m_lastPoll < std::chrono::milliseconds(500)) return;
    m_lastPoll = now;
    const auto newest = newestShaderTime(dir);
    if (newest != m_shaderTime) {
      m_shaderTime = newest;
      log::info("shaders changed: reloading {}", m_variants[m_current].fullName());
      load(m_current);
    }
  }

  void drawFrame(double dt) {
    const ivec2 size = m_window.framebufferSize();
    const gl::Framebuffer screen = gl::Framebuffer::defaultFramebuffer();
    const gl::Target target{&screen, size};
    if (size.x > 0 && size.y > 0) {
      if (m_scene) {
        m_timer.begin();
        render::resetState();  // ImGui and the previous scene leave state behind
        const scenes::FrameInput frame{.target = target, .time = m_time, .deltaTime = m_paused ? 0.0 : dt, .view = m_view};
        m_scene->render(frame);
        m_timer.end();
        m_defined = frame.definedCamera;  // empty for a 2D view: the mouse then leaves it alone
        if (!m_defined) m_drag = Drag::None;
      } else {
        target.bind();
        render::clear(GL_COLOR_BUFFER_BIT, vec4(0.3f, 0.1f, 0.1f, 1.0f));  // no scene: a dim red backdrop
        m_defined.reset();
      }
    }
    m_frameMs = 0.9 * m_frameMs + 0.1 * dt * 1000.0;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    m_panelMin = m_panelMax = vec2(0.0f);
    if (m_showPanel) drawPanel();
    m_panelBusy = ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopup) || ImGui::IsAnyItemActive();
    ImGui::Render();
    screen.bind();
    glViewport(0, 0, size.x, size.y);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }

  void drawPanel() {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("glint");
    const auto& ref = m_variants[m_current];
    if (ImGui::BeginCombo("scene", ref.scene->name.c_str())) {
      for (std::size_t i = 0; i < m_variants.size(); ++i) {
        if (m_variants[i].variant != 0) continue;
        if (ImGui::Selectable(m_variants[i].scene->name.c_str(), m_variants[i].scene == ref.scene)) load(i);
      }
      ImGui::EndCombo();
    }
    ImGui::TextWrapped("%s", ref.scene->summary.c_str());
    ImGui::Separator();
    ImGui::Text("variant  (left/right arrows)");
    for (std::size_t i = 0; i < m_variants.size(); ++i) {
      if (m_variants[i].scene != ref.scene) continue;
      if (ImGui::RadioButton(m_variants[i].desc().name.c_str(), i == m_current)) load(i);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", m_variants[i].desc().description.c_str());
    }
    ImGui::TextWrapped("%s", ref.desc().description.c_str());
    if (m_scene) {
      auto options = m_scene->options();
      if (!options.empty()) {
        ImGui::Separator();
        ImGui::Text("options");
      }
      for (auto& o : options) {
        const std::string label = o.key ? fmt::format("{} [{}]", o.name, o.key) : o.name;
        if (auto* f = std::get_if<float*>(&o.value)) ImGui::SliderFloat(label.c_str(), *f, o.min, o.max);
        if (auto* i = std::get_if<int*>(&o.value)) ImGui::SliderInt(label.c_str(), *i, int(o.min), int(o.max));
        if (auto* b = std::get_if<bool*>(&o.value)) ImGui::Checkbox(label.c_str(), *b);
        if (auto* text = std::get_if<std::string*>(&o.value)) ImGui::InputText(label.c_str(), *text);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", o.description.c_str());
      }
      const auto notes = m_scene->notes();
      if (!notes.empty()) ImGui::TextWrapped("%s", notes.c_str());
    }
    ImGui::Separator();
    ImGui::Text("frame %.2f ms   GPU %.3f ms", m_frameMs, m_timer.latestMs());
    ImGui::Text("time %.2f s %s", m_time, m_paused ? "(paused: space)" : "");
    if (!m_error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", m_error.c_str());
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    if (!m_defined) {
      ImGui::TextWrapped("2D view: no camera to move");
    } else if (m_view.isIdentity()) {
      ImGui::TextWrapped("mouse: left drag orbit, right/middle drag pan, wheel zoom");
    } else {
      ImGui::TextWrapped("view moved: yaw %.0f°, pitch %.0f°, zoom %.2f%s  (C or Home: the scene's camera)",
                         double(glm::degrees(m_view.yaw)), double(glm::degrees(m_view.pitch)), double(m_view.zoom),
                         m_view.pan == vec3(0.0f) ? "" : ", panned");
    }
    ImGui::TextWrapped("arrows: variant/scene   space: pause   R: reload   F12: screenshot   Tab: panel   Esc: quit");
    ImGui::PopStyleColor();
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    m_panelMin = vec2(pos.x, pos.y);
    m_panelMax = vec2(pos.x + size.x, pos.y + size.y);
    ImGui::End();
  }

  const ViewerOptions& m_args;
  gl::Window m_window;
  const scenes::Registry& m_registry;
  std::vector<scenes::VariantRef> m_variants;
  std::size_t m_current = 0;
  std::unique_ptr<scenes::Scene> m_scene;
  std::string m_error;
  gl::GpuTimer m_timer;
  double m_time = 0.0;
  double m_frameMs = 16.0;
  bool m_paused = false;
  bool m_showPanel = true;
  std::deque<InputEvent> m_input;  // events since the last frame, in order
  bool m_shotRequested = false;
  // The camera: the user's change to it, and the camera the scene defined last frame
  // (empty for a 2D view).
  glint::OrbitControl m_view;
  std::optional<glint::Camera> m_defined;
  Drag m_drag = Drag::None;
  int m_dragButton = -1;
  vec2 m_cursor{0.0f};
  // The panel's rectangle last frame (window units; empty when hidden), and whether a popup
  // is open or a widget held: presses there belong to ImGui.
  vec2 m_panelMin{0.0f}, m_panelMax{0.0f};
  bool m_panelBusy = false;
  fs::file_time_type m_shaderTime{};
  std::chrono::steady_clock::time_point m_lastPoll{};
};
}  // namespace

int run(const ViewerOptions& options, const scenes::Registry& registry) {
  if (!options.scene.empty()) registry.resolve(options.scene);  // fail fast on a typo
  if (std::error_code ec; !fs::is_directory(options.shotDir, ec))
    fail(ErrorKind::Usage, "--shot-dir: '{}' is not a directory", options.shotDir);
  Viewer viewer(options, registry);
  return viewer.run();
}

std::u32string glyphsMissingFromPanelFont(const scenes::Registry& registry) {
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGuiContext* context = ImGui::CreateContext();
  std::u32string missing;
  const std::string text = panelText(registry);
  if (!loadPanelFont(text)) {
    missing = U"(no font)";
  } else {
    ImGuiIO& io = ImGui::GetIO();
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    io.Fonts->GetTexDataAsAlpha8(&pixels, &width, &height);  // builds the atlas: no GL needed
    const ImFont* font = io.Fonts->Fonts.back();
    for (const char* p = text.c_str(); *p;) {
      unsigned int c = 0;
      p += ImTextCharFromUtf8(&c, p, nullptr);
      if (c >= 0x80 && !font->FindGlyphNoFallback(ImWchar(c)) && missing.find(char32_t(c)) == std::u32string::npos)
        missing += char32_t(c);
    }
  }
  ImGui::DestroyContext(context);
  ImGui::SetCurrentContext(previous);
  return missing;
}

}  // namespace glint::viewer
