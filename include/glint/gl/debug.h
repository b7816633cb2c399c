#pragma once
// glint/gl/debug.h — KHR_debug output: GL errors become log lines and are counted.
//
// enableDebugOutput() installs a synchronous callback on the current context.
// Errors and undefined behaviour are logged as errors and counted; performance
// and portability notes are logged at debug level. Tests assert that
// debugErrorCount() did not grow while a scene rendered. The CLI turns it on
// with --gl-debug.

#include <cstdint>

namespace glint::gl {

/// Installs the callback on the current context (idempotent).
void enableDebugOutput();
/// GL_DEBUG_TYPE_ERROR / UNDEFINED_BEHAVIOR messages seen so far in this process.
std::uint64_t debugErrorCount();
/// Throws Error(Internal) naming the first pending glGetError code, if any. Cheap
/// enough for once per frame; a safety net when the debug callback is off.
void checkGlError(const char* where);

}  // namespace glint::gl
