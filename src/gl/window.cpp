#include "glint/gl/window.h"

#include "glint/core/error.h"
#include "glint/gl/debug.h"

#include <epoxy/gl.h>
// GLFW after epoxy: epoxy provides the GL declarations.
#include <GLFW/glfw3.h>

namespace glint::gl {

namespace {
std::string g_lastGlfwError;
void onGlfwError(int, const char* description) { g_lastGlfwError = description; }
}  // namespace

Window::Window(ivec2 size, const std::string& title, bool debug) {
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) {
    fail(ErrorKind::NoGpu, "cannot open a window: {} (no display? try `xvfb-run -s '-screen 0 1280x800x24' glint view`)",
         g_lastGlfwError.empty() ? "GLFW failed to initialise" : g_lastGlfwError);
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);
  m_window = glfwCreateWindow(size.x, size.y, title.c_str(), nullptr, nullptr);
  if (!m_window) {
    const std::string reason = g_lastGlfwError;
    glfwTerminate();
    fail(ErrorKind::NoGpu, "cannot create an OpenGL 4.5 core window: {}", reason);
  }
  glfwMakeContextCurrent(m_window);
  glfwSwapInterval(1);
  if (debug) enableDebugOutput();
}

Window::~Window() {
  if (m_window) glfwDestroyWindow(m_window);
  glfwTerminate();
}

bool Window::shouldClose() const { return glfwWindowShouldClose(m_window); }
void Window::requestClose() { glfwSetWindowShouldClose(m_window, GLFW_TRUE); }
void Window::swapBuffers() { glfwSwapBuffers(m_window); }
void Window::pollEvents() { glfwPollEvents(); }
void Window::setTitle(const std::string& title) { glfwSetWindowTitle(m_window, title.c_str()); }

ivec2 Window::framebufferSize() const {
  ivec2 s;
  glfwGetFramebufferSize(m_window, &s.x, &s.y);
  return s;
}

}  // namespace glint::gl
