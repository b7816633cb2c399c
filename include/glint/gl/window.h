#pragma once
// glint/gl/window.h — a GLFW window with an OpenGL 4.5 core context.
//
// The viewer's window: double-buffered, with a depth + stencil default framebuffer
// (24/8 bits requested explicitly: techniques such as stencil shadow volumes need
// them and some platforms default to no stencil). Throws Error(NoGpu) when no
// display or no 4.5 context is available, naming what to do (run under Xvfb, ...).

#include "glint/core/math.h"

#include <string>

struct GLFWwindow;

namespace glint::gl {

class Window {
public:
  Window(ivec2 size, const std::string& title, bool debug = false);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return m_window; }
  bool shouldClose() const;
  void requestClose();
  void swapBuffers();
  /// Polls events (input, resize, close).
  void pollEvents();
  /// Size of the default framebuffer in pixels (may differ from the window size on HiDPI).
  ivec2 framebufferSize() const;
  void setTitle(const std::string& title);

private:
  GLFWwindow* m_window = nullptr;
};

}  // namespace glint::gl
