#include "glint/gl/debug.h"

#include "glint/core/error.h"
#include "glint/core/log.h"

#include <epoxy/gl.h>

#include <atomic>
#include <string_view>

namespace glint::gl {
namespace {
std::atomic<std::uint64_t> g_errors{0};
std::atomic<std::uint64_t> g_notable{0};

const char* typeName(GLenum type) {
  switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    default: return "other";
  }
}

void GLAPIENTRY onMessage(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei length, const GLchar* message,
                          const void*) {
  const std::string_view text(message, length < 0 ? std::char_traits<char>::length(message) : std::size_t(length));
  const bool notable = severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM;
  if (notable) ++g_notable;
  if (type == GL_DEBUG_TYPE_ERROR || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR) {
    ++g_errors;
    log::error("GL {} {}: {}", typeName(type), id, text);
  } else if (notable) {
    log::warn("GL {} {}: {}", typeName(type), id, text);
  } else {
    log::debug("GL {} {}: {}", typeName(type), id, text);
  }
}
}  // namespace

void enableDebugOutput() {
  glEnable(GL_DEBUG_OUTPUT);
  // Synchronous: the callback runs inside the offending call, so a debugger's
  // backtrace (or the order of log lines) points at the culprit.
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onMessage, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

std::uint64_t debugErrorCount() { return g_errors.load(); }

std::uint64_t debugNotableCount() { return g_notable.load(); }

void checkGlError(const char* where) {
  const GLenum e = glGetError();
  if (e == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  ++g_errors;
  fail(ErrorKind::Internal, "OpenGL error 0x{:x} in {}", e, where);
}

}  // namespace glint::gl
