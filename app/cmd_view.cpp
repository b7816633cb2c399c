// glint view — the interactive viewer: a GLFW window, a Dear ImGui panel, every scene.
//
// Keys: ←/→ previous/next variant, ↑/↓ previous/next scene, Space pause time,
// R reload shaders, Tab hide/show the panel, Esc quit; a scene's own keys (Option::key)
// are shown beside its options. Run from a source checkout,
// shaders are re-read from shaders/ whenever a file changes (hot reload).
#include "common.h"

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
#include <imgui.h>
#include <imgui_stdlib.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

namespace glint::app {
namespace fs = std::filesystem;

namespace {
struct ViewArgs {
  std::string scene;
  std::string size = "1280x800";
  std::string screenshot;
  int frames = 0;
  std::string shaderDir;
  std::vector<std::string> settings;  // --set name=value, applied to every scene that has the option
};

// Newest modification time of any file under dir (0 when dir is not set).
fs::file_time_type newestShaderTime(const fs::path& dir) {
  fs::file_time_type newest{};
  std::error_code ec;
  if (dir.empty()) return newest;
  for (const auto& entry : fs::recursive_directory_iterator(dir, ec))
    if (entry.is_regular_file(ec)) newest = std::max(newest, entry.last_write_time(ec));
  return newest;
}

class Viewer {
public:
  Viewer(const ViewArgs& args, const GlobalOptions& global)
      : m_args(args), m_window(parseSize(args.size), "glint", global.glDebug), m_registry(scenes::Registry::builtin()) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini litter in the working directory
    ImGui::StyleColorsDark();
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
      handleKeys();
      checkHotReload();
      drawFrame(dt);
      ++frame;
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
  void handleOptionKeys() {
    if (!m_scene) return;
    for (auto& o : m_scene->options()) {
      if (!o.key || !pressed(int(o.key))) continue;  // GLFW's key codes for A-Z and 0-9 are their ASCII codes
      if (auto* b = std::get_if<bool*>(&o.value)) **b = !**b;
      if (auto* i = std::get_if<int*>(&o.value)) **i = **i >= int(o.max) ? int(o.min) : **i + 1;
    }
  }

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

  bool pressed(int key) {
    const bool down = glfwGetKey(m_window.handle(), key) == GLFW_PRESS;
    const bool was = m_keys[key];
    m_keys[key] = down;
    return down && !was;
  }

  void handleKeys() {
    const bool imguiWantsKeys = ImGui::GetIO().WantCaptureKeyboard;
    if (pressed(GLFW_KEY_ESCAPE)) m_window.requestClose();
    if (imguiWantsKeys) return;
    if (pressed(GLFW_KEY_RIGHT)) step(+1, false);
    if (pressed(GLFW_KEY_LEFT)) step(-1, false);
    if (pressed(GLFW_KEY_DOWN)) step(+1, true);
    if (pressed(GLFW_KEY_UP)) step(-1, true);
    if (pressed(GLFW_KEY_SPACE)) m_paused = !m_paused;
    if (pressed(GLFW_KEY_R)) load(m_current);
    if (pressed(GLFW_KEY_TAB)) m_showPanel = !m_showPanel;
    handleOptionKeys();
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
        m_scene->render({.target = target, .time = m_time, .deltaTime = m_paused ? 0.0 : dt});
        m_timer.end();
      } else {
        target.bind();
        render::clear(GL_COLOR_BUFFER_BIT, vec4(0.3f, 0.1f, 0.1f, 1.0f));  // no scene: a dim red backdrop
      }
    }
    m_frameMs = 0.9 * m_frameMs + 0.1 * dt * 1000.0;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (m_showPanel) drawPanel();
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
    ImGui::TextWrapped("arrows: variant/scene   space: pause   R: reload   Tab: panel   Esc: quit");
    ImGui::PopStyleColor();
    ImGui::End();
  }

  const ViewArgs& m_args;
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
  std::map<int, bool> m_keys;
  fs::file_time_type m_shaderTime{};
  std::chrono::steady_clock::time_point m_lastPoll{};
};
}  // namespace

Command viewCommand(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<ViewArgs>();
  auto* cmd = app.add_subcommand("view", "Open the interactive viewer (a window with a panel of variants and options)");
  cmd->footer("Keys: left/right variant, up/down scene, space pause, R reload shaders, Tab panel, Esc quit.\n"
              "Without a display, run it under Xvfb: xvfb-run -s '-screen 0 1280x800x24' glint view");
  cmd->add_option("scene", args->scene, "scene or scene/variant to start with (default: the first)");
  cmd->add_option("--size", args->size, "Window size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--shaders", args->shaderDir,
                  "Directory to hot-reload shaders from (default: the source tree's shaders/ when it exists)");
  cmd->add_option("--screenshot", args->screenshot, "Save the window (scene + panel) to this image after --frames frames and exit");
  cmd->add_option("--frames", args->frames, "Frames to draw before --screenshot (default 2)");
  cmd->add_option("--set", args->settings, "name=value: set a scene option (as glint render --set), in every scene "
                                           "that has it, e.g. --set input=/dev/video0 for post/camera");
  return Command{.run = [args, &global] {
    if (!args->scene.empty()) scenes::Registry::builtin().resolve(args->scene);  // fail fast on a typo
    fs::path dir = args->shaderDir.empty() ? fs::path(GLINT_SOURCE_SHADER_DIR) : fs::path(args->shaderDir);
    std::error_code ec;
    if (fs::is_directory(dir, ec)) {
      gl::ShaderSources::setDirectory(dir);
    } else if (!args->shaderDir.empty()) {
      fail(ErrorKind::Usage, "--shaders: '{}' is not a directory", args->shaderDir);
    }
    Viewer viewer(*args, global);
    return viewer.run();
  }};
}

}  // namespace glint::app
