#pragma once
// glint/core/error.h — the one exception type glint throws, and its exit codes.
//
// Every failure a user can cause (bad option, unreadable file, no GPU) is an
// Error with a one-line, human-readable message. Front ends print the message
// and exit with exitCode(kind); nothing else is printed, no stack traces.
//
/// ```cpp
/// #include <cstdlib>
/// const std::string text = "1920";  // a --size the user typed
/// try {
///   if (text.find('x') == std::string::npos) glint::fail(glint::ErrorKind::Usage, "size must be WxH, got '{}'", text);
///   throw glint::Error(glint::ErrorKind::Input, "cannot read 'foo.png': no such file");
/// } catch (const glint::Error& e) {
///   fmt::print(stderr, "{}\n", e.what());
///   std::exit(glint::exitCode(e.kind()));  // 2 for Usage
/// }
/// ```

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace glint {

enum class ErrorKind {
  Internal,   ///< a bug in glint (exit 1)
  Usage,      ///< bad command line: unknown scene, malformed size (exit 2)
  Input,      ///< unreadable, corrupt or unsuitable input data (exit 3)
  Output,     ///< output cannot be written (exit 4)
  NoGpu,      ///< no suitable OpenGL context (exit 5)
  OutOfMemory,  ///< the allocator could not satisfy the job (exit 6); jobs estimated above the
                ///< machine's memory are refused before they start (Usage, exit 2)
  Interrupted ///< the user pressed Ctrl-C (exit 130)
};

/// Process exit status a front end returns for an error of this kind.
int exitCode(ErrorKind kind);

class Error : public std::runtime_error {
public:
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), m_kind(kind) {}
  ErrorKind kind() const { return m_kind; }

private:
  ErrorKind m_kind;
};

/// Throws Error(kind, fmt::format(format, args...)).
template <typename... Args>
[[noreturn]] void fail(ErrorKind kind, fmt::format_string<Args...> format, Args&&... args) {
  throw Error(kind, fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace glint
